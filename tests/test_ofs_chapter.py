"""Chapter helpers of Yang, Feng & Fan (2012): paired study, scale sweep, tables, claims."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest

from fusion import data
from fusion import readings as rd
from fusion.book.chapters import ofs as ch
from fusion.book.chapters import ofs_audit as oa
from fusion.book.ledger import STATUSES, Comparison
from fusion.scenarios import thermocouples as th


@pytest.fixture(scope="module")
def study() -> th.PairedStudy:
    return th.paired_study(7, 20, ch.METHODS)


def test_paired_study_matches_monte_carlo(study: th.PairedStudy) -> None:
    clean = th.monte_carlo(7, 20, ch.METHODS)
    failed = th.monte_carlo(7, 20, ch.METHODS, failure={})
    for m in ch.METHODS:
        np.testing.assert_array_equal(study.clean[m], clean[m])
        np.testing.assert_array_equal(study.failed[m], failed[m])


def test_paired_study_failure_only_changes_the_window(study: th.PairedStudy) -> None:
    # outside samples 50-80 the failure case is the same draw
    for m in ch.METHODS:
        np.testing.assert_array_equal(study.clean[m][:, :49], study.failed[m][:, :49])
        np.testing.assert_array_equal(study.clean[m][:, 80:], study.failed[m][:, 80:])
    assert study.errors("mean", True).shape == (20, 31)
    assert study.mae("mean", False).shape == (20,)
    # the mean's error under failure is shifted by the average bias 1.2 °C on average
    assert study.mae("mean", True).mean() > study.mae("mean", False, window=True).mean() + 0.8


def test_best_share_sums_to_at_most_one(study: th.PairedStudy) -> None:
    shares = [study.best_share(m, False) for m in ch.METHODS]
    assert 0.0 <= min(shares) and sum(shares) <= 1.0 + 1e-12
    assert np.all((study.set_size >= 1) & (study.set_size <= 10))


def test_scale_sweep_shape_and_default_scale() -> None:
    scales = np.array([0.5, 2.0])
    sw = th.scale_sweep(3, 5, scales)
    assert sw.shape == (2, 5)
    direct = th.monte_carlo(3, 5, {"o": {"method": "optimal_fusion_set"}})["o"].mean(axis=1)
    np.testing.assert_allclose(sw[1], direct)
    with pytest.raises(ValueError, match="scales"):
        th.scale_sweep(3, 5, [0.0])


def test_tables_reproduce_two_member_rows() -> None:
    tabs = ch.reproduce_tables()
    t2 = data.YANG2012_TABLE2.columns
    np.testing.assert_allclose(tabs.ofs[1:4], t2["optimal_set"][1:4], atol=5e-5)
    np.testing.assert_allclose(tabs.mean, data.YANG2012_TABLE1.values.mean(axis=0))
    assert not tabs.audit.loc[1, "within the readings?"]
    assert list(tabs.totals.index) == ["optimal fusion set", "arithmetic mean", "support degree (rebuilt)"]


def test_table1_values_do_not_depend_on_scale() -> None:
    v = ch.table1_by_scale([0.25, 2.0, 32.0])
    assert v.shape == (3, 6)
    # sets of at most two members: equal weights whatever the scale
    assert np.ptp(v, axis=0).max() == 0.0


def test_unit_dependence_kelvin_is_invariant() -> None:
    z = th.simulate(np.random.default_rng(0), n_samples=50)
    u = ch.unit_dependence(z)
    assert u["k_maxdiff"] < 1e-9
    assert u["members_same"] is True
    assert u["f_maxdiff"] > 0


def test_eq9_parenthesisation_cancels() -> None:
    z = th.simulate(np.random.default_rng(1), n_samples=60)
    r = ch.eq9_readings(z, weight_epochs=None)
    assert r["n_sets"] > 0
    assert r["form_maxdiff"] < 1e-12
    assert r["self_valdiff"] >= 0


def test_figures_are_returned() -> None:
    z = th.simulate(np.random.default_rng(2), n_samples=100)
    err = th.absolute_errors(z, ch.METHODS)
    for fig in (ch.figure_readings(z, highlight=(4,)), ch.figure_errors(err)):
        assert fig.axes
        matplotlib.pyplot.close(fig)


def test_claims_ledger(study: th.PairedStudy, tmp_path) -> None:
    # small study: the ledger refuses comparisons below 100 runs without a reason
    with pytest.raises(ValueError, match="runs"):
        ch.claims(ch.reproduce_tables(), study, study, np.ones((6, 3), bool), [2.0],
                  np.ones((1, 20)), np.ones((1, 20)), ch.table1_by_scale([2.0]), {"f_maxdiff": 0.0})
    big = th.paired_study(5, 100, ch.METHODS)
    t1 = data.YANG2012_TABLE1.values
    sums = rd.fuse_epochs(t1.T, "optimal_fusion_set", threshold="sum").members
    led = ch.claims(ch.reproduce_tables(), big, big, sums, [1.0, 2.0], np.ones((2, 100)), np.ones((2, 100)),
                    ch.table1_by_scale([1.0, 2.0]), {"f_maxdiff": 0.1})
    assert sum(c.headline for c in led.claims) == 1
    assert all(c.status in STATUSES for c in led.claims)
    by_id = {c.id: c for c in led.claims}
    assert by_id["yang-table2-ofs"].status == "not reproduced"
    # eqs. 3-4 as printed (sums) keep every reading: that alternative is contradicted
    alt = by_id["yang-eq3-5-rejects"].alternatives[0]
    assert alt.evidence.status() == "contradicted"
    assert isinstance(by_id["yang-fig4-vs-mean"].evidence, Comparison)
    nums = ch.ledger_numbers(led)
    lo, hi = nums["ofs_yang_fig4_vs_mean_lo"], nums["ofs_yang_fig4_vs_mean_hi"]
    assert lo <= nums["ofs_yang_fig4_vs_mean_diff"] <= hi
    assert led.write(tmp_path)
    labels = {lab for c in led.claims for lab in (c.link, *c.critiques)}
    assert {"ofs-crit-eq34", "ofs-crit-eq6", "ofs-crit-eq9", "ofs-crit-tables", "ofs-beyond"} <= labels


def test_family_values_eq6_is_the_package_and_two_member_sets_ignore_the_family() -> None:
    z = th.simulate(np.random.default_rng(3), n_samples=200)
    assert np.allclose(ch.family_values(z, "laplace"), rd.fuse_epochs(z, "optimal_fusion_set").values)
    assert np.allclose(ch.family_values(z, "laplace", 5.0), rd.fuse_epochs(z, "optimal_fusion_set", scale=5.0).values)
    # another family changes the weights of sets with three or more members
    assert not np.allclose(ch.family_values(z, "gauss"), ch.family_values(z, "laplace"))
    t1 = data.YANG2012_TABLE1.values.T   # sets of one or two members: equal weights whatever the function
    for fam in ("gauss", "cauchy"):
        assert np.allclose(ch.family_values(t1, fam), ch.family_values(t1, "laplace"))
    with pytest.raises(ValueError, match="family"):
        ch.family_values(z, "triangle")
    with pytest.raises(ValueError, match="scale"):
        ch.family_values(z, "gauss", 0.0)


def test_alpha_study_reuses_the_draws_and_alternatives_are_added() -> None:
    big = th.paired_study(5, 100, ch.METHODS)
    al = th.paired_study(5, 100, ch.alpha_methods((0.5, 2.0)))
    assert np.array_equal(al.mae("optimal_fusion_set", False), big.mae("optimal_fusion_set", False))
    z = th.simulate(np.random.default_rng(5), n_runs=100)
    fc = ch.family_mae(z)
    fail = ch.family_mae(th.inject_failure(z, **data.YANG2012_FAILURE), window=(50, 80))
    assert np.allclose(fc[next(iter(fc))], big.mae("optimal_fusion_set", False))
    assert np.allclose(fail[next(iter(fail))], big.mae("optimal_fusion_set", True))
    t1 = data.YANG2012_TABLE1.values
    sums = rd.fuse_epochs(t1.T, "optimal_fusion_set", threshold="sum").members
    led = ch.claims(ch.reproduce_tables(), big, big, sums, [1.0, 2.0], np.ones((2, 100)), np.ones((2, 100)),
                    ch.table1_by_scale([1.0, 2.0]), {"f_maxdiff": 0.1}, alpha_study=al,
                    family_clean=fc, family_fail=fail, joint=oa.joint_audit(window=1.0))
    by_id = {c.id: c for c in led.claims}
    # the joint audit's full explanation reproduces Table 2 and the two totals; Table 1 as printed does not
    # it is recorded as an explanation of the discrepancy, not as a reading (no alternative)
    for cid, n in (("yang-table2-ofs", "6 of 6 values"), ("yang-table2-mean", "all 6 means"),
                   ("yang-totals", "2 of 2 totals")):
        assert "explanation of the discrepancy" in by_id[cid].bound and n in by_id[cid].bound, cid
        assert not by_id[cid].alternatives, cid
        assert by_id[cid].status != "reproduced", cid
    # ref. [11]'s rule is not given: Table 3 cannot be checked, the rebuilt rule is a reading
    assert by_id["yang-table3-support"].status == "cannot be checked"
    assert by_id["yang-table3-support"].alternatives[0].evidence.status() == "not reproduced"
    sup = by_id["yang-table3-support"].alternatives[-1].evidence.summary()
    assert "0.129" in sup and sup.endswith("observations 3, 4")
    rank = {a.reading: a.evidence for a in by_id["yang-totals-ranking"].alternatives}
    # the optimal set's total (12.55 °C) is below the support degree's at α = 2 (15.54 °C), above it at 0.05
    assert rank["α = 2 °C⁻²"].holds and not rank["α = 0.05 °C⁻²"].holds
    fixed = next(r for r in rank if r.startswith("observation 5"))
    assert "mean 16.4333" in rank[fixed].ours           # the correction gives the printed mean total
    assert sum(a.choice == "support-degree α" for a in by_id["yang-fig4-vs-support"].alternatives) == 2
    mf = by_id["yang-membership-free"]
    assert "Gaussian" in mf.evidence.ours and "Cauchy" in mf.evidence.ours and "TOST" in mf.evidence.ours
    assert mf.alternatives[-1].evidence.status() == "cannot be checked"   # Table 1: vacuous
    rank_guard = next(a for a in by_id["yang-totals-ranking"].alternatives if a.choice == "one-member guard")
    assert "optimal set 13.6167" in rank_guard.evidence.ours
    for cid in ("yang-fig4-whole-vs-mean", "yang-fig4-whole-vs-support", "yang-fig2-fluctuation-support",
                "yang-fig4-fluctuation-mean", "yang-fig4-fluctuation-support", "yang-def3-keeps-valid",
                "yang-set-rejects-faulty"):
        assert cid in by_id, cid
    assert not by_id["yang-def3-keeps-valid"].evidence.holds    # without faults the set drops valid readings
    for cid in ("yang-fig2-vs-mean", "yang-fig2-vs-support", "yang-fig2-fluctuation", "yang-fig4-vs-mean",
                "yang-fig4-vs-support", "yang-fig4-unaffected", "yang-fig4-robust"):
        assert any(a.choice == "noise levels" for a in by_id[cid].alternatives), cid


def test_failure_modes_share_the_draws_and_differ_in_the_bias() -> None:
    fixed = th.paired_study(7, 100, ch.METHODS)
    for mode in th.FAILURE_MODES[1:]:
        other = th.paired_study(7, 100, ch.METHODS, failure_mode=mode)
        # same readings without failure, and outside the window with it
        assert np.array_equal(other.mae("mean", False), fixed.mae("mean", False))
        assert np.array_equal(other.failed["mean"][:, :49], fixed.failed["mean"][:, :49])
        # a random bias is on average smaller than the full one, so the mean is pulled up less
        assert other.mae("mean", True).mean() < fixed.mae("mean", True).mean()
    z = np.zeros((3, 100, 10))
    rng = np.random.default_rng(1)
    half = th.random_failure(z, rng, "random samples")
    assert set(np.unique(half[:, 49:80, 3])) <= {0.0, 4.0} and np.all(half[:, :49] == 0)
    size = th.random_failure(z, rng, "random size")
    assert np.all((size[:, 49:80, 9] >= 0) & (size[:, 49:80, 9] <= 8)) and np.ptp(size[:, 49:80, 9]) > 0
    assert np.array_equal(th.random_failure(z, rng, "fixed"), th.inject_failure(z))
    with pytest.raises(ValueError, match="mode"):
        th.random_failure(z, rng, "sometimes")
    with pytest.raises(TypeError, match="rng"):
        th.random_failure(z, 1, "fixed")  # type: ignore[arg-type]
    # the failing sensors' membership shares are computed on the window
    assert len(fixed.failed_member_share) == 2 and 0 <= min(fixed.failed_member_share) <= 1


def test_equivalence_is_a_tost_with_a_relative_margin() -> None:
    rng = np.random.default_rng(2)
    b = rng.normal(1.0, 0.1, 300)
    assert ch.equivalence(b + rng.normal(0, 0.01, 300), b, "x").holds          # within ±5 %
    assert not ch.equivalence(b * 1.10, b, "x").holds                            # a 10 % rise
    assert not ch.equivalence(b + rng.normal(0, 1.0, 300), b, "x").holds        # too noisy to show
    assert ch.equivalence(b * 1.03, b, "x", margin=0.05).holds != ch.equivalence(b * 1.03, b, "x", margin=0.02).holds
    with pytest.raises(ValueError, match="margin"):
        ch.equivalence(b, b, "x", margin=0.0)
    with pytest.raises(ValueError, match="paired"):
        ch.equivalence(b, b[:10], "x")
