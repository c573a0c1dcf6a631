"""Fuzz 60b: an ndarray subclass read through its own ``__iter__`` by ``sequence`` (C1) and trusted by its own
``min``/``max``/``tolist`` in the fast path of ``counts``/``seeds`` (C2); ``wls`` building and factoring the d x d
H^T W H of an H wider than tall before refusing it (C3). Report: /work/tmp/fuzz60b/report.md."""

from __future__ import annotations

import itertools
import time

import numpy as np
import pytest

from fusion._counts import as_rngs, counts, iterable, seed_array, seeds, sequence

from _helpers import refused_quickly


class _Iterating(np.ndarray):
    """An ndarray whose own ``__iter__`` and ``__len__`` disagree with its data (10**5 copies of its first entry)."""

    def __iter__(self):
        return itertools.repeat(self[0], 10**5)

    def __len__(self) -> int:
        return 10**5


class _Lying(np.ndarray):
    """An integer ndarray whose own ``min``, ``max`` and ``tolist`` disagree with its data."""

    def min(self, *args, **kwargs):
        return 5

    def max(self, *args, **kwargs):
        return 5

    def tolist(self):
        return [5] * 2


def _quick(call):
    t0 = time.process_time()
    out = call()
    assert time.process_time() - t0 < 1.0
    return out


def test_c1_an_ndarray_subclass_is_read_through_its_data():
    """Fuzz 60b C1: its items are its data (what the length check read), never its own ``__iter__``."""
    for reader in (sequence, iterable):
        assert _quick(lambda: reader(np.array([0.5, 0.25]).view(_Iterating), "x")) == [0.5, 0.25]
    a = np.empty(1, dtype=object)
    a[0] = np.random.default_rng(0)
    assert _quick(lambda: as_rngs(a.view(_Iterating), "rngs")) == [a[0]]
    with pytest.raises(ValueError, match=r"^x must have 3 items, got 2"):
        sequence(np.array([0.5, 0.25]).view(_Iterating), "x", length=3)


def test_c2_an_integer_ndarray_subclass_is_checked_on_its_data():
    """Fuzz 60b C2: the fast path of counts/seeds/seed_array reads the data, not the subclass's min/max/tolist."""
    bad = np.array([-5, 3])
    for call, match in ((lambda: seeds(bad.view(_Lying)), r"^seeds\[0\] must be an integer >= 0"),
                        (lambda: seed_array(bad.view(_Lying)), r"^seeds\[0\] must be an integer >= 0"),
                        (lambda: counts(np.array([-3, 30]).view(_Lying), "ns"), r"^ns\[0\] must be a positive")):
        with pytest.raises(ValueError, match=match):
            call()
    assert seeds(np.array([7, 8]).view(_Lying)) == [7, 8]
    assert counts(np.array([7, 8]).view(_Lying), "ns") == [7, 8]
    assert seed_array(np.array([7, 8]).view(_Lying)).tolist() == [7, 8]


class _Accepted(Exception):
    pass


def test_c3_wls_refuses_h_wider_than_tall_at_once():
    """Fuzz 60b C3: d > n makes H^T W H (d x d, rank at most n) singular: refused naming H before it is built (the
    old code ran 9.5-12.2 CPU-s at d = 12,000, a raw MemoryError at d = 20,000 and 10**6)."""
    from fusion.readings.weighting import wls
    for d in (4, 12_000, 10**6):
        refused_quickly(lambda: wls(np.ones((3, d)), np.eye(3), np.ones(3)),
                 ValueError, r"^H must have at least as many rows as columns, got \(3, ")
    assert wls(np.eye(3), np.ones(3), np.array([1.0, 2.0, 3.0])).tolist() == [1.0, 2.0, 3.0]  # d = n: solved


def test_c3_wls_counts_the_d_by_d_product_and_its_factors(monkeypatch):
    """Fuzz 60b C3: the work of H^T W H and its factorisation (n d**2 + d**3) is counted: H square of n = 2,600
    (1.05e9 units; the old n**2 (n + d) count gave 5.3e8 and ran it) is refused at once, 2,540 passes the budget."""
    from fusion.readings import weighting
    refused_quickly(lambda: weighting.wls(np.eye(2600), np.ones(2600), np.ones(2600)), ValueError, r"^H and W ask for .*work budget")
    real = weighting.work

    def budget(*args, **kwargs):
        real(*args, **kwargs)
        raise _Accepted
    monkeypatch.setattr(weighting, "work", budget)
    with pytest.raises(_Accepted):
        weighting.wls(np.eye(2540), np.ones(2540), np.ones(2540))
