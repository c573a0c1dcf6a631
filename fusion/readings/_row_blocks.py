"""Row blocks of the pairwise kernels of :mod:`fusion.readings.fusion_set` (issue 37: cache-sized passes).

The kernels of the optimal fusion set, its membership and the support degrees build an (N, n, n) array of
pairwise terms for N epochs of n readings; in blocks of rows each temporary stays in the caches. Every row's
result depends on that row only, and each reduction runs along one row, so the blocks give the unblocked results
bit for bit (tests/test_fusion_set_blocks.py).
"""

from __future__ import annotations

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
