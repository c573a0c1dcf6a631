"""The stage times of a Chernoff fusion of mixtures (:class:`FusionTimings`), re-exported by ``mixture``."""

from __future__ import annotations

from dataclasses import dataclass

from fusion._results import ResultSpec, number, validated_post_init

__all__ = ["FusionTimings"]


@dataclass(frozen=True)
class FusionTimings:
    """Seconds spent per stage by one call of :func:`fuse_mixtures` or :func:`fuse_mixtures_batch` (``timed=True``).

    Wall-clock times: not deterministic, for benchmarks only. A stage the call did not run takes 0.

    Attributes
    ----------
    first_order : float
        Step D, the first-order mixture :math:`g` (:func:`first_order_fusion`).
    sampling : float
        Step E, drawing the importance samples.
    densities : float
        Step F, :math:`\\log g` and the local mixture densities at the samples.
    optimiser : float
        Step G, the chosen optimiser.
    weights : float
        Steps H-I, the fused weights and moments.
    reference : float
        The SLSQP reference (``reference=True``).
    redraw : float
        The redrawn samples (``redraw=True``).

    Raises
    ------
    TypeError
        A field not a real number.
    ValueError
        A field negative or not finite. Each is stored as a float (a 0-d array is read, never kept: fuzz 29a C1).
    """

    # the patent's steps D-G
    first_order: float = 0.0
    sampling: float = 0.0
    densities: float = 0.0
    optimiser: float = 0.0
    # steps H-I
    weights: float = 0.0
    # what the caller asked for besides
    reference: float = 0.0
    redraw: float = 0.0

    __result_spec__ = ResultSpec({name: number() for name in ("first_order", "sampling", "densities", "optimiser",
                                                              "weights", "reference", "redraw")})
    __post_init__ = validated_post_init
