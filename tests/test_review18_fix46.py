"""Review 18's points fixed by fix46 that are not the thermocouple studies' count (tests/test_stability_entries46.py,
tests/test_bad_input_fuzz40a.py)."""

from __future__ import annotations

import re
import time

import pytest

from fusion._limits import loop_work


def test_split_ci_exactness_states_its_edge():
    """Point 2: the docstring said n_steps "at most 10^5"; the budget's edge is 4,347 steps (230 loop steps each since
    book audit 76)."""
    from fusion.book.chapters.ci import printed

    doc = printed.split_ci_exactness.__doc__
    found = re.search(r"n_steps : int\s+Steps, the initial one included \(at most ([\d,]+)", doc)
    stated = int(found[1].replace(",", ""))
    loop_work((stated,), 0, "n_steps", step=printed._SPLIT_CI_STEP)   # accepted
    with pytest.raises(ValueError, match="^n_steps"):
        loop_work((stated + 1,), 0, "n_steps", step=printed._SPLIT_CI_STEP)


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


def test_measured_simultaneous_arrays_are_rounded_up():
    """Point 7: tracemalloc's peaks of 2.01, 2.05, 2.08 and 3.1 arrays were counted as 2, 2, 2 and 3 (rounded down, so
    a request just inside the rule held more than the memory budget); counted as 3, 3, 3 and 4, a request between
    the two edges is refused by name at once. (Each call here is inside the edge of the rounded-down count.)"""
    import numpy as np

    from fusion._counts import MAX_ELEMENTS, allocation
    from fusion.estimates import ci
    from fusion.estimates.chernoff.mixture import is_objective
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion

    R = 2**21
    _refused_fast(is_objective, np.zeros((R, 1)), np.zeros(R), np.ones((43, 1)), match=r"^L and eps ask .*3 arrays of")
    allocation((R, 42), "L and eps", arrays=3)   # inside
    d = 10
    w = np.full(MAX_ELEMENTS // (3 * d * d) + 1, 0.5)
    assert w.size * d * d * 2 <= MAX_ELEMENTS
    _refused_fast(ci.ci_objective, w, np.eye(d), np.eye(d), match=r"^omega, P1 and P2 ask .*3 arrays of")
    w = np.full(MAX_ELEMENTS // (4 * 2 * d * d) + 1, 0.5)
    assert 2 * w.size * d * d * 3 <= MAX_ELEMENTS
    _refused_fast(ci.split_ci_objective, w, np.eye(d), np.eye(d), np.eye(d), np.eye(d),
                  match=r"^omega, P1d, P1i, P2d and P2i ask .*4 arrays of")
    N, n = 10, 946
    assert (N * n) ** 2 * 3 > MAX_ELEMENTS >= (N * n) ** 2 * 2
    _refused_fast(fuzzy_cluster_fusion, np.zeros((N, n)), np.broadcast_to(np.eye(n), (N, n, n)),
                  match=r"^xs and Ps ask .*3 arrays of")


def test_toy_study_refuses_what_is_objective_would():
    """Point 7's class: toy_study checked one (r, 101) array while is_objective holds three; an r between the edges
    was refused inside, naming is_objective's "L and eps". Refused at entry naming r."""
    import numpy as np

    from fusion._counts import MAX_ELEMENTS
    from fusion.book.chapters.chernoff.mixture import toy_study

    r = MAX_ELEMENTS // (3 * 101) + 1
    _refused_fast(toy_study, np.random.default_rng(0), r, match=r"^r ask .*3 arrays of")


def test_a_flat_list_beyond_the_limit_counts_exactly():
    """Point 11: a flat list longer than sequence_entries' limit was reported as "at least" its length though its count
    is exact; read within _EXACT_SCAN entries it is exact, a nested one or one beyond the scan stays "at least" (and
    fast: fuzz 39a E1)."""
    from fusion._entries import _EXACT_SCAN
    from fusion._validation import entries_text, given_entries

    assert given_entries([0.5] * 1000, 6) == 1000
    assert entries_text(given_entries(tuple(range(1000)), 6)) == "1e+03"
    assert given_entries([[0.5, 0.5]] * 1000, 6) == 1000.5            # rows not read: at least
    assert given_entries([[0.5] * 1000, [0.5]], 6) == 1001                 # the last one flat: exact
    big = [0.5] * (_EXACT_SCAN + 1)
    t0 = time.process_time()
    assert given_entries(big, 6) == _EXACT_SCAN + 1.5
    assert time.process_time() - t0 < 0.1
