"""Joint audit of Yang, Feng & Fan (2012) Tables 2-3 and the three-reading closed form (issue 15)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from fusion import data
from fusion import readings as rd
from fusion.book.chapters import ofs_audit as oa

T1 = data.YANG2012_TABLE1.values.T  # (6 observations, 3 sensors)
TEXT = "averages, d_i < d̄ (the text)"


@pytest.fixture(scope="module")
def result() -> oa.AuditResult:
    return oa.joint_audit()


# --- three readings: closed form ------------------------------------------------------------


def test_three_reading_closed_form_on_a_large_random_sample() -> None:
    rng = np.random.default_rng(15)
    cont = rng.normal(size=(100_000, 3)) * rng.uniform(0.01, 100, size=(100_000, 1))
    grid = np.round(rng.integers(-30, 31, size=(100_000, 3)) / 10 + 900, 1)  # 0.1 °C grid: exact ties g2 = 2 g1
    for x in (cont, grid):
        closed = oa.three_reading_set(x)
        np.testing.assert_array_equal(closed, rd.fuse_epochs(x, "optimal_fusion_set").members)
        np.testing.assert_array_equal(closed, oa.set_members(x, TEXT))
        srt = np.sort(x, axis=1)
        distinct = np.ptp(x, axis=1) > 0
        # never all three readings; the middle one always
        assert not closed[distinct].all(axis=1).any()
        mid = np.argsort(x, axis=1, kind="stable")[:, 1]
        assert closed[np.arange(len(x)), mid][distinct].all()
        # one member iff the gap ratio lies in [1/2, 2]
        g1, g2 = srt[:, 1] - srt[:, 0], srt[:, 2] - srt[:, 1]
        single = distinct & (g2 <= 2 * g1 * (1 + 1e-9)) & (g1 <= 2 * g2 * (1 + 1e-9))
        np.testing.assert_array_equal(closed.sum(axis=1)[distinct] == 1, single[distinct])
    # both kinds of set occur in the grid sample, ties included
    assert (oa.three_reading_set(grid).sum(axis=1) == 2).any() and (oa.three_reading_set(grid).sum(axis=1) == 1).any()


def test_eqs_6_to_12_cannot_matter_for_three_readings() -> None:
    """Sets of one or two members fuse to their mean whatever the scale of eq. 6."""
    rng = np.random.default_rng(2)
    x = 900 + rng.normal(size=(20_000, 3)) * 3
    members = oa.three_reading_set(x)
    mean_of_members = np.where(members, x, 0).sum(axis=1) / members.sum(axis=1)
    for scale in (0.1, 2.0, 50.0):
        np.testing.assert_allclose(rd.fuse_epochs(x, "optimal_fusion_set", scale=scale).values, mean_of_members,
                                   rtol=0, atol=1e-9)


@settings(max_examples=200, deadline=None)
# (no tiny readings: the shared validation refuses them below 1e-150, issue 35 rule 2)
@given(arrays(np.float64, st.integers(2, 12), elements=st.floats(-1e3, 1e3, allow_nan=False).map(lambda v: 0.0 if abs(v) < 1e-150 else v)))
def test_the_set_never_holds_every_distinct_reading(x: np.ndarray) -> None:
    """The d_i - d̄ sum to zero, so not all d_i can lie strictly below d̄."""
    members = rd.optimal_set_members(x)
    d = rd.mean_distances(x).d
    if members.all():
        assert np.ptp(d) <= 1e-9 * max(1.0, float(np.abs(d).max()))


def test_three_reading_set_rejects_bad_input() -> None:
    with pytest.raises(ValueError, match="x"):
        oa.three_reading_set([1.0, 2.0])
    with pytest.raises(ValueError, match="x"):
        oa.three_reading_set([1.0, np.nan, 2.0])
    assert oa.three_reading_set([5.0, 5.0, 5.0]).all()


# --- the joint audit --------------------------------------------------------------------------


def test_programs_and_rules_reduce_to_the_package() -> None:
    np.testing.assert_allclose(oa.run_program(T1, "correct", TEXT), rd.fuse_epochs(T1, "optimal_fusion_set").values)
    np.testing.assert_allclose(oa.run_program(T1, "correct", "sums as printed, d_i < d̄"),
                               rd.fuse_epochs(T1, "optimal_fusion_set", threshold="sum").values)
    assert oa.set_members(T1, "sums as printed, d_i < d̄").all()
    with pytest.raises(ValueError, match="rule"):
        oa.set_members(T1, "median")
    with pytest.raises(ValueError, match="program"):
        oa.run_program(T1, "cached")
    with pytest.raises(ValueError, match="order"):
        oa.run_program(T1, "buffer, clean start", order=[0, 0, 1, 2, 3, 4])


def test_stale_buffer_mechanics() -> None:
    """A two-slot buffer never reset: one-member observations are averaged with a stale slot."""
    x = np.array([[1.0, 2.0, 4.0], [10.0, 10.5, 20.0], [0.0, 3.0, 5.0]])  # sets {2}, {10, 10.5}, {3}
    np.testing.assert_allclose(oa.run_program(x, "correct"), [2.0, 10.25, 3.0])
    np.testing.assert_allclose(oa.run_program(x, "buffer, clean start"), [2.0, 10.25, (3.0 + 10.5) / 2])
    np.testing.assert_allclose(oa.run_program(x, "buffer, previous pass"), [(2.0 + 10.5) / 2, 10.25, (3.0 + 10.5) / 2])
    np.testing.assert_allclose(oa.run_program(x, "buffer, clean start", order=[1, 0, 2]),
                               [(2.0 + 10.5) / 2, 10.25, (3.0 + 10.5) / 2])


def test_corrections_enumerate_slips_first_without_duplicates() -> None:
    cors = oa.corrections(window=1.0)
    assert cors[0].kind == "none"
    keys = [(c.sensor, c.obs, round(c.value, 1)) for c in cors[1:]]
    assert len(keys) == len(set(keys))
    slips = {c.value for c in cors if (c.sensor, c.obs) == (1, 5) and c.kind == "one-digit slip"}
    assert len(slips) == 8 + 3 * 9 and 889.9 in slips  # no leading zero and 799.9 in slips and 899.8 in slips
    swaps = {c.value for c in cors if (c.sensor, c.obs) == (2, 5) and c.kind == "adjacent digits swapped"}
    assert swaps == {970.5, 905.7}  # 907.5: 0-7 and 7-5 swapped (9-0 would lead with a zero)


def test_joint_audit_finds_exactly_one_full_explanation(result: oa.AuditResult) -> None:
    """Pins what the search finds: every hypothesis explaining all 26 values uses the same correction."""
    full = result.full
    assert len(full) > 0
    assert set(full["correction"]) == {"obs. 5, sensor 1: 899.9 → 889.9 (one-digit slip)"}
    assert set(full["program"]) <= {"buffer, clean start", "buffer, previous pass", "three-slot buffer"}
    assert set(full["set rule"]) <= {TEXT, "averages, d_i ≤ d̄"}
    natural = full[full["observation order"] == "1-6"]
    assert set(natural["program"]) == {"buffer, previous pass"}
    t = result.table
    # no hypothesis with Table 1 as printed, and none with a correct program, explains every value
    assert t.loc[t["correction class"] == "none", "values explained (of 26)"].max() < 26
    assert t.loc[t["program"] == "correct", "values explained (of 26)"].max() < 26
    assert t.loc[t["program"] == "set not reset", "values explained (of 26)"].max() < 26
    # the rule d_i over n-1 gives the text's sets; the printed sums keep every reading
    assert set(result.same_sets["set rule"]) == {"d_i over n-1 (others only), d̄ their mean", "sums as printed, d_i ≤ d̄"}


def test_explain_shows_every_value_of_the_full_explanation() -> None:
    fix = oa.Correction(1, 5, 889.9, "one-digit slip")
    df = oa.explain(fix, "buffer, previous pass")
    for col in ("mean", "mean error", "optimal set", "optimal-set error"):
        np.testing.assert_allclose(df[(col, "printed")].dropna(), df[(col, "reconstructed")].dropna(), atol=1.5e-4)
    # the three values outside the readings' two-member midpoints pair the lone member with 904.0 (obs. 4, sensor 3)
    ofs = df[("optimal set", "reconstructed")].to_numpy()[:6]
    lone = np.array([898.3, 896.4, 899.4])
    np.testing.assert_allclose(ofs[[0, 4, 5]], (lone + 904.0) / 2)
    # a clean start misses observation 1 only
    clean = oa.explain(fix, "buffer, clean start")
    bad = np.abs(clean[("optimal set", "reconstructed")] - clean[("optimal set", "printed")]) > 5e-5
    assert list(clean.index[bad]) == ["1"]


def test_order_search_restricted_to_mean_consistent_data_loses_no_full_explanation() -> None:
    """The exhaustive order search over every slip finds the same full explanations as the pruned one."""
    wide = oa.joint_audit(window=0.1, order_search="slips")
    pruned = oa.joint_audit(window=0.1)
    cols = ["program", "set rule", "correction", "observation order"]
    key = lambda df: set(map(tuple, df[cols].to_numpy()))  # noqa: E731
    assert key(wide.full) == key(pruned.full)
    best = wide.table.groupby("program")["values explained (of 26)"].max()
    assert best.drop(["buffer, clean start", "buffer, previous pass", "three-slot buffer"]).max() < 26


def test_every_order_at_once_is_each_order_run_alone() -> None:
    """The joint audit's order search runs a step once per shared prefix of the orders (issue 37): bit for bit the
    values of each (table, order) run by itself, under every stateful program, on the slips and the corrected table."""
    import itertools

    cors = oa.corrections(window=0.1)
    pick = [0, 1, 7, 40, next(h for h, c in enumerate(cors) if (c.sensor, c.obs, c.value) == (1, 5, 889.9))]
    tabs = oa._tables([cors[h] for h in pick])
    orders = np.array(list(itertools.permutations(range(tabs.shape[1]))))
    rep, o_rep = np.repeat(np.arange(len(pick)), len(orders)), np.tile(orders, (len(pick), 1))
    for rule in (TEXT, "sums as printed, d_i ≤ d̄"):
        members = oa.set_members(tabs, rule)
        correct = oa._run(tabs, members, "correct", None)
        for prog in oa.PROGRAMS:
            if prog == "correct":
                continue
            alone = oa._run(tabs[rep], members[rep], prog, o_rep, correct=correct[rep])
            at_once = oa._run_every_order(tabs, members, prog, correct, orders).reshape(alone.shape)
            assert at_once.tobytes() == alone.tobytes(), (rule, prog)
            if rule == TEXT:  # not a trivial case: the program's values depend on the order
                assert np.ptp(alone.reshape(len(pick), len(orders), -1), axis=1).max() > 0.01, prog
    with pytest.raises(ValueError, match="every permutation"):
        oa._run_every_order(tabs, members, "set not reset", correct, orders[:-1])


def test_support_variants_find_no_common_alpha(result: oa.AuditResult) -> None:
    """Pins what the search finds for Table 3; the corrected data is the joint audit's full explanation."""
    fix = oa.full_explanation(result)[0]
    assert (fix.sensor, fix.obs, fix.value) == (1, 5, 889.9)
    t1 = data.YANG2012_TABLE1.values.T
    np.testing.assert_allclose(oa.support_values(t1, "Gaussian exp(-α d²)", "row sums", [0.25])[0],
                               rd.fuse_epochs(t1, "support_degree").values)
    tab = oa.support_variants()
    assert not tab.xs("one α for all six", axis=1, level=1).to_numpy().any()
    printed = tab[("Table 1 as printed", "reachable observations")]
    # support from the current observation never reaches observations 3-4; history-based Gaussian and linear
    # support do (the arctan kernel of the support-degree literature does not)
    for (kern, agg), obs in printed.items():
        assert ("3" in obs.split(", ")) == (agg == "row sums, accumulated over time"
                                            and kern.startswith(("Gaussian", "linear")))
    assert len(tab) == 20 and any(k.startswith("arctan") for k, _ in tab.index)
    corrected = tab[("obs. 5 sensor 1 = 889.9", "reachable observations")]
    # the correction makes observation 5 reachable for every rule without a self-reliability term
    assert all("5" in o.split(", ") and "5" not in p.split(", ")
               for (kern, agg), o, p in zip(corrected.index, corrected, printed) if "self-reliability" not in agg)


@pytest.mark.parametrize("n", [1, 2, 3, 5, 12, 13])
def test_members_first_is_the_stable_sort(n: int) -> None:
    """The tabulated permutation (issue 37) gives the integers of ``np.argsort(~mem, kind="stable")``, every pattern."""
    rng = np.random.default_rng(n)
    mem = rng.random((5000, n)) < rng.uniform(0.1, 0.9, size=(5000, 1))
    mem[:3] = [[True] * n, [False] * n, [j % 2 == 0 for j in range(n)]]
    got = oa._members_first(mem)
    assert got.dtype == np.intp and np.array_equal(got, np.argsort(~mem, axis=1, kind="stable"))
