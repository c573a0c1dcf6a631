"""The budget of the first-order fusion's product mixture (fuzz 35a C7).

The first-order Chernoff fusion of N mixtures padded to S components is a mixture of :math:`S^N` components, one per
tuple of components (``mixture._first_order_prepare``): every function that builds it counts that product at its entry
by the shared memory and work rules (``fusion._counts.allocation``, ``fusion._limits.work``), naming its caller's
arguments, so that 30 two-component mixtures (:math:`2^{30}` tuples, hours) or 24 (a 3 GiB array) are refused at once.
"""

from __future__ import annotations

import math

from fusion._counts import allocation
from fusion._limits import LOOP_STEP

#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one (tuple, mixture) entry of the product mixture in the whole
#: fusion (``fuse_mixtures``: the proposal, its samples' densities and the fused moments), ``FUSION_ENTRY + d * d``
#: times ``FUSION_SQUARE``: measured (OPENBLAS_NUM_THREADS=1, 2**10 to 2**14 tuples of two-component mixtures, 200
#: samples) about 0.5 us an entry at d = 2 and 0.86 us at d = 4.
FUSION_ENTRY, FUSION_SQUARE = 40, 3
#: The same for the first-order fusion alone (``first_order_fusion``): about 0.17-0.3 us an entry at d = 2, 0.26 us
#: at d = 4.
FIRST_ORDER_ENTRY, FIRST_ORDER_SQUARE = 28, 1
#: Units of one mixture's Python step in ``first_order_fusion`` and ``fuse_mixtures`` (``_mixture_arrays``'
#: reading of its arrays, its checks, the first-order fusion's per-mixture terms): measured 11-12 us a mixture
#: (one-component mixtures of d = 1, 10**4 to 10**6 of them; time.process_time, OPENBLAS_NUM_THREADS=1, the machine
#: shared), uncounted before (28 + d**2 units a mixture: 10**6 mixtures were accepted and ran 12 CPU-s, the edge,
#: 3.4e7, ~400 CPU-s; fix 72f, fuzz 64b's class), so about twice that.
MIXTURE_STEP = 25 * LOOP_STEP // 10
#: A tuple's units per sample and covariance entry (the samples' proposal densities, ``n_samples x d x d`` a tuple):
#: about 1.3 ns measured at 2**10 tuples and 5,000 to 20,000 samples, a fifth of a unit.
SAMPLE_DIVISOR = 5
#: Beyond ``2**MAX_LOG2_TUPLES`` tuples the product is beyond every budget (refused without forming its count).
MAX_LOG2_TUPLES = 100


def product_size(problems: int, n: int, s: int, d: int, names: str, n_samples: int = 0,
                 first_order: bool = False) -> tuple[int, int]:
    """The product mixture's tuples ``s ** n`` and the units of work of one tuple, its memory refused by name.

    Parameters
    ----------
    problems : int
        Fusion problems built at once (the product's arrays hold all of them).
    n, s, d : int
        Mixtures per problem, components per mixture (padded: the largest) and dimension.
    names : str
        The caller's arguments that set them, named in a refusal.
    n_samples : int
        Samples drawn from the product (0 for the first-order fusion alone).
    first_order : bool
        Weigh the first-order fusion alone (``first_order_fusion``) rather than the whole fusion.

    Returns
    -------
    tuple of int
        The tuples :math:`s^n` and the units of one tuple (for ``fusion._limits.work``'s ``weight``).

    Raises
    ------
    ValueError
        If the product's arrays are beyond the memory budget, naming ``names``.
    """
    if n * math.log2(max(s, 1)) > MAX_LOG2_TUPLES:
        raise ValueError(f"{names} ask for a product mixture of {s}**{n} component tuples (the first-order "
                         "fusion's), beyond the memory and work budgets")
    tuples = s**n
    allocation((problems, tuples, n, d, d), f"{names} (the product mixture's {s}**{n} component tuples)")
    entry, square = (FIRST_ORDER_ENTRY, FIRST_ORDER_SQUARE) if first_order else (FUSION_ENTRY, FUSION_SQUARE)
    return tuples, n * (entry + square * d * d) + -(-n_samples * d * d // SAMPLE_DIVISOR)


#: float64 a sample of one problem at the peak of ``fuse_mixtures`` beyond ``1.25 (K + d)`` (K = 1 + d + d(d+1)/2
#: quadratic features, ``_features``, and the d coordinates) and one a tuple (the product's densities at it): the
#: weights, densities and swarm vectors. tracemalloc's peak (fuse_mixtures, two mixtures, shared machine) per sample:
#: 32 at d = 1 (1 tuple), 35 at d = 2 (9), 87 at d = 10 (4), 556 at d = 30 (1 or 9), 2,016 at d = 60 (1), 110 at d = 2
#: (100 tuples), 1,307 at d = 1 (1,296 tuples of four mixtures), 127 at d = 10 with redraw and reference.
SAMPLE_EXTRA = 32


def sample_memory(problems: int, tuples: int, d: int, n_samples: int, names: str) -> None:
    """Refuse ``n_samples`` draws of ``problems`` fusions of dimension ``d`` (``tuples`` product components) beyond the
    memory budget, naming ``names`` (fuzz 58b C2: 10**6 samples of d = 30, a raw MemoryError; the samples'
    features alone are (n_samples, 496) there): ``1.25 (K + d) + tuples + SAMPLE_EXTRA`` float64 a sample."""
    per = math.ceil(1.25 * (1 + 2 * d + d * (d + 1) // 2)) + tuples + SAMPLE_EXTRA
    allocation((problems, n_samples, per), f"{names} (the samples' quadratic features and densities)")
