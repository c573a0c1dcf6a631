"""Row blocks of the pairwise kernels of :mod:`fusion.readings.fusion_set` (issue 37: cache-sized passes).

The kernels of the optimal fusion set, its membership and the support degrees build an (N, n, n) array of
pairwise terms for N epochs of n readings; in blocks of rows each temporary stays in the caches. Every row's
result depends on that row only, and each reduction runs along one row, so the blocks give the unblocked results
bit for bit (tests/test_fusion_set_blocks.py).
"""

from __future__ import annotations

import numpy as np

from fusion._guards import own_underflow
from fusion._validation import FloatArray

#: Elements of one (rows, n, n) block (8 MiB of float64 per temporary would leave the
#: caches; 2**17 elements, 1 MiB, keep each block's passes in them). Every row's result depends on that row only, and
#: each reduction runs along one row, so the blocks give the unblocked results bit for bit (tests/test_readings.py).
_BLOCK_ELEMENTS = 1 << 17


def _row_blocks(s: FloatArray) -> list[slice]:
    """Slices of the rows of ``s`` (N, n) into blocks of about :data:`_BLOCK_ELEMENTS` pairwise elements."""
    rows = max(1, _BLOCK_ELEMENTS // max(1, s.shape[1] ** 2))
    return [slice(i, i + rows) for i in range(0, s.shape[0], rows)] or [slice(0, 0)]


#: The n x n float64 arrays the pairwise kernel of each method of ``fuse_epochs`` holds at once for one row (0: no
#: pairwise kernel), declared to the shared reading conversion (``pairs`` of ``fusion._validation.as_reading_rows``,
#: rules 9 and 17): the differences and one more (their exponential, square or mask; the belief degree's eigenvectors
#: a third). The belief degree decomposes each row's matrix (:data:`CUBIC`).
PAIRS = {"mean": 0, "optimal_fusion_set": 2, "fusion_set_weights": 2, "support_degree": 2, "belief_degree": 3}
#: The methods whose kernel decomposes each row's n x n matrix (n**3 work a row).
CUBIC = frozenset({"belief_degree"})


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _support_block(s: FloatArray, alpha: float) -> FloatArray:
    """The support-degree weights of one block of rows of ``fusion.readings.fusion_set``'s readings."""
    R = np.exp(-alpha * (s[:, :, None] - s[:, None, :]) ** 2)
    total = R.sum(axis=2)  # >= 1 because r_ii = 1
    return total / total.sum(axis=1, keepdims=True)


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def _belief_rows(s: FloatArray, scale: float, binary_eps: float | None, limit: float | None = None) -> FloatArray:
    """The belief-degree kernel of rows ``s`` (N, n): ``exp(-|s_i - s_j| / (2 scale))``, 0 beyond ``limit``; the
    binary degree ``|s_i - s_j| <= binary_eps`` if given."""
    d = np.abs(s[:, :, None] - s[:, None, :])
    if binary_eps is not None:
        return (d <= binary_eps).astype(float)
    B = np.exp(-d / (2.0 * scale))
    return B if limit is None else np.where(d <= limit, B, 0.0)


def epochs_limit(rows: int, n: int, method: str, names: str) -> None:
    """Refuse, naming ``names``, what ``fuse_epochs`` would refuse of ``rows`` epochs of ``n`` readings fused by
    ``method``: its input budget (``MAX_INPUT_ELEMENTS``) and its kernel's memory and work (``pairwise`` with
    :data:`PAIRS` and :data:`CUBIC`, the arguments ``fusion._validation.as_reading_rows`` passes). A caller that
    draws the readings itself calls this at its entry, once per method, so that a request is refused by its own
    arguments before the draws (fuzz 39a D1: ``thermocouples.monte_carlo`` was refused inside ``fuse_epochs``)."""
    from fusion._counts import input_allocation, pairwise

    input_allocation((rows, n), names)
    if PAIRS[method]:
        pairwise(n, names, PAIRS[method], rows=rows, cubic=method in CUBIC)
