"""Issue 37: the optimal-fusion-set and support-degree kernels, computed in row blocks, give the one-block results bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.readings import fusion_set as fs


def _rows(seed: int, N: int, n: int) -> np.ndarray:
    """Readings with ties: some rows rounded to the degree, some identical, some with one far outlier."""
    rng = np.random.default_rng(seed)
    s = 20.0 + rng.normal(scale=2.0, size=(N, n))
    s[::7] = np.round(s[::7])
    s[3::11] = s[3::11, :1]
    s[5::13, 0] += 50.0
    return s


def _blocks_of(n: int) -> int:
    return max(1, fs._BLOCK_ELEMENTS // n**2)


@pytest.mark.parametrize("n", [1, 2, 3, 10, 17, 400])
def test_blocked_kernels_equal_one_block_bitwise(n: int) -> None:
    rows = _blocks_of(n)
    for N in (rows - 1, rows, rows + 1, 2 * rows + 5):
        if N < 1:
            continue
        s = _rows(n * 1000 + N, N, n)
        assert len(fs._row_blocks(s)) == -(-N // rows)
        for threshold in ("mean", "sum"):
            members = fs._members_rows(s, threshold)
            assert members.tobytes() == fs._members_block(s, threshold).tobytes()
            for scale, include_self in ((2.0, True), (0.7, False)):
                got = fs._set_weights(s, members, scale, include_self)
                assert got.tobytes() == fs._set_weights_block(s, members, scale, include_self).tobytes()
        for alpha in (0.25, 3.0):
            w, m = fs._support_weights(s, alpha)
            assert w.tobytes() == fs._support_block(s, alpha).tobytes() and m.all() and m.shape == s.shape


def test_blocked_fuse_epochs_equals_row_by_row() -> None:
    """Each epoch's fused value is the single-epoch call's, bit for bit, whatever block it falls in."""
    s = _rows(7, 2 * _blocks_of(10) + 3, 10)
    for method, opts in (("optimal_fusion_set", {}), ("fusion_set_weights", {"include_self": False}),
                         ("support_degree", {"alpha": 0.5})):
        batch = fs.fuse_epochs(s, method, **opts)
        for i in (0, _blocks_of(10) - 1, _blocks_of(10), len(s) - 1):
            one = fs.fuse_epochs(s[i], method, **opts)
            assert batch.weights[i].tobytes() == one.weights[0].tobytes()
            assert batch.members[i].tobytes() == one.members[0].tobytes()


def test_empty_rows() -> None:
    s = np.empty((0, 4))
    assert fs._members_rows(s, "mean").shape == (0, 4)
    assert fs._set_weights(s, np.ones((0, 4), bool), 2.0, True).shape == (0, 4)
    assert fs._support_weights(s, 0.25)[0].shape == (0, 4)


@pytest.mark.parametrize("n", [2, 10, 60])
def test_blocked_belief_weights_equal_one_block_bitwise(n: int) -> None:
    """The belief degree's Perron weights in row blocks (issue 35: a stack of rows no longer held whole) are the
    whole stack's, for the fuzzy, truncated and binary beliefs."""
    s = _rows(n, 2 * _blocks_of(n) + 5, n)
    assert len(fs._row_blocks(s)) == 3
    for scale, eps, limit in ((1.0, None, None), (0.5, None, 2.0), (1.0, 1.0, None)):
        w, m = fs._belief_weights(s, scale, eps, limit)
        whole = fs._perron_rows(fs._belief_rows(s, scale, eps, limit))
        assert w.tobytes() == whole.tobytes() and m.all() and m.shape == s.shape
