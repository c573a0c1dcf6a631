"""Fuzz 61a C2 and C4: arguments read once, and the read values (not the caller's objects) counted and used.

C2: ``fig5_hypotheses`` read ``flat_pair``'s size from the shapes as given; an array-like with only ``__array__``
(valid array_like) was taken for m = 1, and m = 3,000 with n_open = 8 ran 11.5-12.1 CPU-s before ``ci_objective``
refused under its own names. C4: ``sigma_sweep`` discarded its checked ``sigmas`` and ``names`` and read the caller's
objects again (budget, loop, index); ``fusion.scenarios.time_registration.monte_carlo`` and ``fusion_runs`` read
``names`` three and two times.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pytest

from _helpers import refused_quickly


class Arr:
    """A valid array_like with only ``__array__`` (no ``shape``)."""

    def __init__(self, a):
        self.a = a

    def __array__(self, dtype=None, copy=None):
        return self.a


class FlipIter(Sequence):
    """A Sequence honest on its first ``__iter__`` only."""

    def __init__(self, good, other):
        self.good, self.other, self.calls = list(good), list(other), 0

    def __len__(self):
        return len(self.good)

    def __getitem__(self, i):
        return self.good[i]

    def __iter__(self):
        self.calls += 1
        return iter(self.good) if self.calls == 1 else iter(self.other)


@pytest.fixture(scope="module")
def fig5_inputs():
    from fusion.scenarios.two_sensor import fruit_fly_over_seeds

    P1, P2 = np.diag([1.0, 4.0]), np.diag([4.0, 1.0])
    return P1, P2, fruit_fly_over_seeds(P1, P2, [0, 1], iterations=2)


def test_c2_fig5_hypotheses_counts_an_array_like_flat_pair_by_its_entries(fig5_inputs):
    from fusion._limits import DENSE_CUBE, MAX_WORK
    from fusion.book.chapters.ci import checks
    from fusion.book.chapters.ci.weights import fig5_hypotheses

    P1, P2, seeds = fig5_inputs
    names = r"^flat_pair and n_open \(the grid k/n_open on flat_pair's size\) ask for"

    def call(m, n_open):
        F = np.eye(m)
        return fig5_hypotheses(P1, P2, seeds, 0, n_open=n_open, flat_pair=(Arr(F), Arr(F)))

    refused_quickly(lambda: call(600, 300), ValueError, names + " an array")   # memory: before, ci_objective's names
    m = 1_500   # the work's edge: n_open + 8 cubes of DENSE_CUBE units
    n = int(MAX_WORK / (DENSE_CUBE * m**3)) - 8
    F = np.eye(m)
    got = checks._flat_pair_read([Arr(F), Arr(F)], n)   # inside: accepted by the budget alone, the arrays read
    assert all(isinstance(g, np.ndarray) and np.array_equal(g, F) for g in got)
    refused_quickly(lambda: call(m, n + 1), ValueError, names)


def test_c2_fig5_hypotheses_uses_the_pair_it_read(fig5_inputs):
    from fusion.book.chapters.ci.weights import fig5_hypotheses

    P1, P2, seeds = fig5_inputs

    class Once:   # its first conversion a covariance, any later one indefinite
        def __init__(self):
            self.reads = 0

        def __array__(self, dtype=None, copy=None):
            self.reads += 1
            return np.eye(2) if self.reads == 1 else -np.eye(2)

    a, b = Once(), Once()
    t = fig5_hypotheses(P1, P2, seeds, 0, short_budget=2, n_open=3, flat_pair=(a, b))
    plain = fig5_hypotheses(P1, P2, seeds, 0, short_budget=2, n_open=3, flat_pair=(np.eye(2), np.eye(2)))
    assert (a.reads, b.reads) == (1, 1)
    assert t.equals(plain)
    # an entry check refuses at entry, naming the entry
    refused_quickly(lambda: fig5_hypotheses(P1, P2, seeds, 0, short_budget=2, n_open=3,
                                            flat_pair=(np.eye(2), -np.eye(2))), ValueError, r"^flat_pair\[1\]")


def test_c4_sigma_sweep_uses_the_checked_lists():
    from fusion.book.chapters.time_registration import sigma_sweep

    plain = sigma_sweep([0.5, 1.0], ["reg_two_point"])
    # a second pass of 10**3 levels (10**4 ran 15.6 CPU-s budgeted as 2): the two levels checked are the ones run
    got = sigma_sweep(FlipIter([0.5, 1.0], np.linspace(0.1, 5, 1_000).tolist()), ["reg_two_point"])
    assert got.equals(plain)
    # two distinct names checked, a repeat on the second pass: still the two columns checked
    two = sigma_sweep([0.5, 1.0], FlipIter(["reg_two_point", "reg_least_squares"], ["reg_two_point"] * 2))
    assert list(two.columns) == ["reg_two_point", "reg_least_squares"]
    # a bad level on the second pass: never read (before: refused naming the inner sigma)
    assert sigma_sweep(FlipIter([0.5, 1.0], [float("nan")] * 2), ["reg_two_point"]).equals(plain)
    refused_quickly(lambda: sigma_sweep([0.5, float("nan")], ["reg_two_point"]), ValueError, r"^sigmas\[1\]")


def test_c4_class_time_registration_runs_read_names_once():
    from fusion.scenarios import time_registration as sc

    runs = sc.fusion_runs(FlipIter(["reg_two_point"], ["reg_least_squares"]), 1.0, 2, 0)
    assert list(runs.fused) == ["reg_two_point"]
    mc = sc.monte_carlo(FlipIter(["reg_two_point"], ["reg_least_squares"]), 1.0, 2, 0)
    assert list(mc.per_run) == ["reg_two_point"]


class Flip:
    """A valid array_like (only ``__array__``) whose first conversion is ``first``, every later one ``later``."""

    def __init__(self, first, later):
        self.first, self.later, self.reads = np.asarray(first, dtype=float), np.asarray(later, dtype=float), 0

    def __array__(self, dtype=None, copy=None):
        self.reads += 1
        return self.first if self.reads == 1 else self.later


def test_c4_class_robustness_readings_reads_t2_once():
    """The same class for array_like arguments checked and then converted again: the checked array is used."""
    from fusion.book.chapters.time_registration_robustness import robustness_readings
    from fusion.scenarios import time_registration as sc

    t2 = sc.instants()[1]
    got = robustness_readings(1.0, Flip(t2, t2[:3] + 0.5))
    want = robustness_readings(1.0, t2)
    assert [r.reading for r in got] == [r.reading for r in want]
    for g, w in zip(got, want):   # the instants run are the ones checked (before: the second conversion's)
        assert g.options.keys() == w.options.keys()
        assert all(np.array_equal(np.asarray(g.options[k], dtype=object), np.asarray(w.options[k], dtype=object))
                   for k in g.options)


def test_c4_class_single_sensor_crb_reads_truths_once():
    from fusion.book.chapters import chernoff_steps as cst
    from fusion.scenarios import range_bearing as rb

    s = rb.RangeBearingScenario(frames=6, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                n_components=2)
    truths = cst.study_truths(s, 1, 2)
    assert cst.single_sensor_crb(s, Flip(truths, truths * 1e3)) == cst.single_sensor_crb(s, truths)
