"""Records of chapter 05's per-step NEES and split CI's exactness, which tell their roles apart (issue 35, swaps)."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import hashlib

import numpy as np

from fusion._counts import as_rng
from fusion._counts import seed as check_seed
from fusion._frozen import ReadOnlyMapping
from fusion._validation import one_of
from fusion._results import ResultSpec, array, dict_of, flag, integer, keyed, number, text, validated_post_init
from fusion._validation import FloatArray

__all__ = ["NeesPerStep", "SplitExactness", "PairRuns"]


def stream_of(rng: np.random.Generator) -> str:
    """A digest of the state of ``rng``'s bit generator (the draws it will give): two runs started from one seed
    have the same one. ``rng`` is checked by the package's one rule (``fusion._counts.as_rng``: a Generator itself
    over one of numpy's bit generators, a TypeError naming ``rng`` otherwise; fuzz 60a D2: a subclass was read, and
    a non-Generator raised a raw AttributeError)."""
    return hashlib.sha256(repr(as_rng(rng, "rng").bit_generator.state).encode()).hexdigest()[:16]


class _Values(Mapping):
    """A read-only mapping over the dict field named by ``_items`` (the producer's former plain dict), so that a
    reader of that dict reads the result unchanged."""

    _items = ""

    def __getitem__(self, key: object) -> Any:
        return getattr(self, self._items)[key]

    def __iter__(self) -> Iterator[str]:
        return iter(getattr(self, self._items))

    def __len__(self) -> int:
        return len(getattr(self, self._items))


@dataclass(frozen=True, eq=False)
class NeesPerStep(_Values):
    """The mean NEES per step of :func:`~fusion.book.chapters.ci.nees_per_step`, with what the runs were.

    A mapping: rule -> NEES averaged over the runs at each step (``nees``). The other fields record the start
    and the runs, so that a reader refuses the true start's runs in the random start's place, or runs of
    other settings or of another seed.

    Attributes
    ----------
    nees : dict of str to ndarray, shape (K,)
        Rule -> mean NEES at each step.
    random_velocity : bool
        Whether the targets' initial velocity was drawn from the filters' prior (the random start).
    runs : int
        Runs averaged.
    T, velocity_sigma : float
        Sampling period (s) and prior velocity standard deviation (m/s).
    Q : ndarray, shape (4, 4)
    R1, R2 : ndarray, shape (2, 2)
        Process and measurement covariances.
    x_start : ndarray, shape (4,)
        Initial true state.
    stream : str
        Digest of the generator's state when the runs started (the same for two runs of one seed).
    """

    nees: Mapping[str, FloatArray]
    random_velocity: bool
    runs: int
    T: float
    velocity_sigma: float
    Q: FloatArray
    R1: FloatArray
    R2: FloatArray
    x_start: FloatArray
    stream: str

    __result_spec__ = ResultSpec({"nees": keyed("K"), "random_velocity": flag(), "runs": integer(1),
                                  "T": number(positive=True), "velocity_sigma": number(positive=True),
                                  "Q": array(4, 4, covariance=True), "R1": array(2, 2, covariance=True),
                                  "R2": array(2, 2, covariance=True), "x_start": array(4), "stream": text()})
    __post_init__ = validated_post_init
    _items = "nees"


@dataclass(frozen=True, eq=False)
class SplitExactness(_Values):
    """Split CI's exactness of :func:`~fusion.book.chapters.ci.split_ci_exactness`, with the case it is of.

    A mapping: number -> value (``numbers``). The other fields record the case, so that a reader refuses the
    exactness of another period, noise or number of steps than the runs it is set beside.

    Attributes
    ----------
    numbers : dict of str to float
        The numbers (keys as :func:`~fusion.book.chapters.ci.split_ci_exactness` lists them).
    Q : ndarray, shape (4, 4)
    R : ndarray, shape (2, 2)
        Process and measurement covariances (of each identical sensor).
    T, velocity_sigma, t_steady : float
        Sampling period (s), prior velocity standard deviation (m/s), start of the steady-state average (s).
    n_steps : int
        Steps.
    """

    numbers: Mapping[str, float]
    Q: FloatArray
    R: FloatArray
    T: float
    velocity_sigma: float
    t_steady: float
    n_steps: int

    __result_spec__ = ResultSpec({"numbers": dict_of(number()), "Q": array(4, 4, covariance=True),
                                  "R": array(2, 2, covariance=True), "T": number(positive=True),
                                  "velocity_sigma": number(positive=True), "t_steady": number(), "n_steps": integer(1)})
    __post_init__ = validated_post_init
    _items = "numbers"


#: The pairs of :class:`PairRuns` (``role``).
_PAIRS = ("identical", "unequal", "aniso")


class PairRuns(ReadOnlyMapping):
    """A read-only mapping of method -> per-run RMSE (m) of one sensor pair of :class:`PairedStudies`, recording the
    pair (``role``: ``"identical"``, ``"unequal"`` or ``"aniso"``) and the runs' seed (``seed``; None for the
    anisotropic pair, whose runs are its WeightPair's), so that :func:`paired_numbers` refuses one pair's runs in
    another's place. It compares equal to any mapping of the same items.

    Parameters
    ----------
    items : mapping of str to ndarray
        Method -> per-run RMSE (checked by the :class:`PairedStudies` that holds it).
    role : {"identical", "unequal", "aniso"}
        The pair.
    seed : int or None
        The runs' seed.

    Raises
    ------
    TypeError
        ``items`` not a mapping, ``role`` not a str, ``seed`` not an integer.
    ValueError
        ``role`` not a pair, ``seed`` negative.
    """

    __slots__ = ("role", "seed")

    def __init__(self, items: Mapping[str, Any], role: str, seed: int | None) -> None:
        if not isinstance(items, Mapping):
            raise TypeError(f"items must be a mapping of method -> per-run RMSE, got {type(items).__name__}")
        role = one_of(role, _PAIRS, "role")
        if seed is not None:
            seed = check_seed(seed, "seed")
        super().__init__(items)
        object.__setattr__(self, "role", role)
        object.__setattr__(self, "seed", seed)

    def __repr__(self) -> str:
        return f"PairRuns({self._items!r}, role={self.role!r}, seed={self.seed!r})"

    def __reduce__(self) -> tuple[type, tuple[Any, ...]]:  # type: ignore[override]
        return (type(self), (self._items, self.role, self.seed))
