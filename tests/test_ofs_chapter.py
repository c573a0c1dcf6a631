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
from fusion.book.chapters import ofs_fair
from fusion.book.claims import build_ledger, claims_dir
from fusion.book.claims import load as load_claims
from fusion.book.exact import ExactComparison
from fusion.book.figures import audit_figure
from fusion.book.ledger import Comparison
from fusion.readings.robust import robust_fuse
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
    # both readings fuse each epoch to a convex combination of its readings: the change is within the spread
    assert 0 < r["self_valdiff"] <= np.ptp(z, axis=1).max()
    # and at least the change of any one epoch, recomputed here from the readable weights of eq. 9
    row = next(x for x in z if rd.optimal_set_members(x).sum() >= 3)
    sel = rd.optimal_set_members(row)
    C = rd.fusion_degree_matrix(row[sel])
    w = [rd.consistency_degree(C) * rd.distribution_balance(C, include_self=s) for s in (True, False)]
    assert r["self_valdiff"] >= abs((w[0] / w[0].sum() - w[1] / w[1].sum()) @ row[sel]) - 1e-12


def test_figures_are_returned() -> None:
    z = th.simulate(np.random.default_rng(2), n_samples=100)
    err = th.absolute_errors(z, ch.METHODS)
    for fig in (ch.figure_readings(z, highlight=(4,)), ch.figure_errors(err)):
        assert audit_figure(fig) == []  # raises FigureStyleError on any breach of the book's figure rules
        matplotlib.pyplot.close(fig)


def test_evidence_of_every_record_and_the_claim_file_build_the_ledger(tmp_path) -> None:
    cf = load_claims(claims_dir() / f"{ch.SOURCE}.yaml")
    ev = ch.evidence(5, 100, cf)
    assert set(ev) == {s.id for s in cf.records if s.chapter == ch.CHAPTER}
    led = build_ledger(ch.SOURCE, None, ev, values=ch.claim_values(), claims=cf)
    assert led.write(tmp_path)
    by_id = {c.id: c for c in led.claims}
    # an undefined baseline (ref. [11]): the function's primary evidence is shown as the stand-in reading
    for spec in cf.records:
        if spec.baseline is not None and not spec.baseline["defined"]:
            stand_in, prim = by_id[spec.id].alternatives[0], ev[spec.id]["primary"]
            assert stand_in.kind == "stand-in"
            if isinstance(prim, Comparison):
                np.testing.assert_array_equal(stand_in.evidence.a, prim.a)
            elif isinstance(prim, ExactComparison):  # the record's margin may be applied to the stand-in (R9)
                assert (stand_in.evidence.a, stand_in.evidence.b, stand_in.evidence.claim) == (prim.a, prim.b, prim.claim)
            else:
                assert stand_in.evidence == prim
    # every stochastic reading runs at least the primary's runs, except the fair study's, shown apart
    for spec in cf.records:
        for r in spec.readings:
            e = ev[spec.id][r.key]
            if isinstance(e, Comparison) and r.kind == "open-choice":
                assert e.runs >= ev[spec.id]["primary"].runs, (spec.id, r.key)
    nums = ch.ledger_numbers(led, fields=ch.LEDGER_GLUE)
    lo, hi = nums["ofs_yang_fig2_vs_mean_lo"], nums["ofs_yang_fig2_vs_mean_hi"]
    assert lo <= nums["ofs_yang_fig2_vs_mean_diff"] <= hi
    m = ev["yang-fig2-vs-mean"]["primary"]
    assert nums["ofs_yang_fig2_vs_mean_margin"] == pytest.approx(0.05 * np.mean(m.b), abs=1e-4)
    with pytest.raises(ValueError, match="records not in the ledger"):
        ch.ledger_numbers(led, fields={"yang-nope": ("status",)})
    labels = {lab for c in led.claims for lab in (c.link, *c.critiques)}
    assert {"ofs-crit-eq34", "ofs-crit-eq6", "ofs-crit-eq9", "ofs-crit-tables", "ofs-beyond", "ofs-median"} <= labels


def test_paired_evidence_uses_the_same_draws_for_every_reading() -> None:
    prim = ch.ev_fig2_vs_mean({}, seed=5, runs=100)
    st = th.paired_study(5, 100, ch.METHODS)
    assert np.array_equal(prim.a, st.mae("optimal_fusion_set", False))
    assert np.array_equal(prim.b, st.mae("mean", False)) and prim.claim == "less"
    eq = ch.ev_fig2_vs_mean({"noise": "equal"}, seed=5, runs=100)
    assert not np.array_equal(eq.a, prim.a)
    # the α readings of the stand-in reuse the draws: the optimal set's errors are identical
    al = ch.ev_fig2_vs_support({"alpha": 2.0}, seed=5, runs=100)
    assert np.array_equal(al.a, prim.a) and not np.array_equal(al.b, ch.ev_fig2_vs_support({}, seed=5, runs=100).b)
    # whole run vs window: the window is 31 of the 100 samples
    w, whole = ch.ev_fig4_vs_mean({}, seed=5, runs=100), ch.ev_fig4_whole_vs_mean({}, seed=5, runs=100)
    e = st.errors("mean", True, window=False)
    outside = np.concatenate([e[:, :49], e[:, 80:]], axis=1)
    np.testing.assert_allclose(np.mean(whole.b), (31 * np.mean(w.b) + 69 * np.mean(outside)) / 100, rtol=1e-12)
    un = ch.ev_fig4_unaffected({}, seed=5, runs=100)
    assert un.claim == "equal" and np.mean(un.a) > np.mean(un.b)          # the failure raises the error
    rob = ch.ev_fig4_robust({}, seed=5, runs=100)
    assert np.mean(rob.a) < np.mean(rob.b)                                # ... less than the mean's
    with pytest.raises(ValueError, match="noise"):
        ch.ev_fig2_vs_mean({"noise": "loud"}, seed=5, runs=100)
    with pytest.raises(ValueError, match="alpha"):
        ch.ev_fig2_vs_mean({"alpha": 1.0}, seed=5, runs=100)


def test_table1_totals_ranking_and_the_median() -> None:
    t1 = data.YANG2012_TABLE1.values
    tot = ch.table1_totals(t1)
    assert tot["median"] == pytest.approx(np.abs(np.median(t1, axis=0) - 900).sum())
    assert tot["mean"] == pytest.approx(np.abs(t1.mean(axis=0) - 900).sum())
    assert tot["optimal_fusion_set"] == pytest.approx(np.abs(ch.tables().ofs - 900).sum())
    assert tot["median"] < tot["optimal_fusion_set"] < tot["mean"]                       # 10.1 < 12.55 < 15.63 °C
    med = ch.ev_median_total({}, seed=1, runs=1)  # R9: an exact comparison of totals against the 5 % margin
    assert (med.a, med.b, med.claim) == (pytest.approx(tot["median"]), pytest.approx(tot["optimal_fusion_set"]), "less")
    assert med.status() == ("reproduced" if tot["median"] < 0.95 * tot["optimal_fusion_set"] else "not distinguishable")
    # the stand-in's total crosses the optimal set's as α grows; the optimal set's does not depend on α
    sup = {a: ch.table1_totals(t1, a)["support_degree"] for a in (0.05, 2.0)}
    assert sup[0.05] < tot["optimal_fusion_set"] < sup[2.0]
    assert ch.ev_totals_ranking_support({"alpha": 0.05}, seed=1, runs=1).status() == "contradicted"
    assert ch.ev_totals_ranking_support({"alpha": 2.0}, seed=1, runs=1).status() == "reproduced"
    # the correction of the joint audit gives the printed mean total
    fixed = ch.table1_totals(ch.corrected_table1())
    assert fixed["mean"] == pytest.approx(data.YANG2012_TOTALS.columns["mean"][0], abs=5e-5)
    assert ch.ev_totals_ranking_mean({"data": "corrected"}, seed=1, runs=1).status() == "reproduced"
    guard = ch.table1_totals(t1, guard=True)["optimal_fusion_set"]
    assert guard == pytest.approx(13.6167, abs=1e-4) and ch.ev_totals_ranking_mean({"guard": "mean"}, seed=1, runs=1).status() == "reproduced"
    # the explanation reproduces the printed columns and totals; Table 1 as printed does not
    assert ch.ev_table2_ofs({"explanation": True}, seed=1, runs=1).status() == "reproduced"
    assert ch.ev_table2_ofs({}, seed=1, runs=1).status() == "not reproduced"
    assert ch.ev_totals({"explanation": True}, seed=1, runs=1).status() == "reproduced"
    assert ch.ev_table2_mean({"data": "corrected"}, seed=1, runs=1).status() == "reproduced"


def test_table3_stand_ins_and_obs_closer() -> None:
    pub = data.YANG2012_TABLE3.columns["reliability"]
    y = ch.ev_table3_support({}, seed=1, runs=1)
    np.testing.assert_allclose(y.ours, np.round(ch.tables().sup, 10), atol=1e-9)
    v = ch.ev_table3_support({"kernel": "Gaussian exp(-α d²)", "weights": "row sums", "data": "printed"}, seed=1, runs=1)
    # the closest single α of the Yager rule reproduces at most the reachable observations (not 3 or 4)
    hits = np.abs(np.asarray(v.ours) - pub) < 5e-5
    assert not hits[2] and not hits[3] and v.status() == "not reproduced"
    # the printed errors: at observation 6 the optimal set (1.70) is farther than the mean (1.5333)
    ev = ch.ev_obs_closer({}, seed=1, runs=1)  # one exact comparison per observation (R9, the chapter's margin)
    assert ev.status() == "contradicted" and dict(ev.parts)["observation 6"].status() == "contradicted"
    rec = ch.ev_obs_closer({"values": "recomputed"}, seed=1, runs=1)
    e = {k: np.abs(getattr(ch.tables(), k) - 900) for k in ("ofs", "mean")}
    worse = (e["ofs"] - e["mean"] > 0.05 * e["mean"])[[0, 2, 3, 4, 5]]  # beyond the margin on the wrong side
    assert (rec.status() == "contradicted") == bool(np.any(worse))


def test_eq5_drops_the_farthest_and_sums_drop_nothing() -> None:
    assert ch.ev_eq3_5_rejects({}, seed=3, runs=2000).holds
    assert not ch.ev_eq3_5_rejects({"rule": "sums"}, seed=3, runs=2000).holds
    # observation 2 of Table 1: sensor 2 (875.9 °C) is far from the others and is the one dropped
    m = rd.fuse_epochs(data.YANG2012_TABLE1.values.T, "optimal_fusion_set").members
    assert m[1].tolist() == [True, False, True]
    assert not ch.ev_eq9_defined({}, seed=1, runs=1).holds


def test_membership_free_parts() -> None:
    t1 = ch.ev_membership_free({"vary": "table1"}, seed=1, runs=1)
    assert all(p.holds for _, p in t1.parts)       # sets of one or two members: equal weights whatever the function
    fam = ch.ev_membership_free({}, seed=5, runs=100)
    assert len(fam.parts) == 4 and all(c.claim == "equal" for _, c in fam.parts)
    ms = ch.membership_study(5, 100)
    k0 = int(np.argmin(np.abs(ms.scales - 2.0)))
    # eq. 6 at scale 2 °C is the family study's reference, on the same draws
    C = ch.FailureCase.NONE
    np.testing.assert_allclose(ms.sweep[C][k0], ms.family[C][next(iter(ms.family[C]))])
    assert set(ms.sweep) == set(ms.family) == set(ms.ablation) == set(ch.FailureCase)
    sc = ch.ev_membership_free({"vary": "scale"}, seed=5, runs=100)
    assert len(sc.parts) == 2 * (len(ch.SCALES) - 1)
    assert [lab.rsplit(", ", 1)[1] for lab, _ in fam.parts] == ["no failure"] * 2 + ["failure"] * 2  # the cases' labels


def test_a_reading_names_its_case_by_label() -> None:
    """The claim file's ``case: no failure`` / ``case: failure`` reach the study as FailureCase keys; other text is refused."""
    ms = ch.membership_study(5, 100)
    for text, case in (("no failure", ch.FailureCase.NONE), ("failure", ch.FailureCase.FAILURE)):
        c = ch.ev_weights_reasonable({"case": text}, seed=5, runs=100)
        assert c.a == tuple(ms.ablation[case]["optimal_fusion_set"])
    with pytest.raises(ValueError, match=r"settings\['case'\]"):
        ch.ev_weights_reasonable({"case": "ofs_failure"}, seed=5, runs=100)


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


def test_fair_study_opposite_faults_cancel_in_the_mean_and_words_use_the_margin() -> None:
    st = ofs_fair.fair_study(3, n_runs=100, n_samples=20, sizes=(0,), counts=(0,), spreads=(1,), opposite=(2, 6))
    base = st.mae[(ofs_fair.SIZE, 0.0)]["mean"]
    for b in (2.0, 6.0):   # +b and -b cancel exactly in the mean, not in the optimal set
        np.testing.assert_allclose(st.mae[(ofs_fair.OPPOSITE, b)]["mean"], base, atol=1e-9)
        assert not np.allclose(st.mae[(ofs_fair.OPPOSITE, b)]["optimal_fusion_set"],
                               st.mae[(ofs_fair.SIZE, 0.0)]["optimal_fusion_set"])
    x = np.linspace(1.0, 2.0, 100)
    word = {r: ofs_fair._word(Comparison(x * r, x, "a", "b", "less", "m")) for r in (0.9, 0.99, 1.1)}
    assert word == {0.9: "better", 0.99: "within ±5 %", 1.1: "worse"}


def test_fair_weights_is_the_fair_study_restricted_to_the_ledgers_methods_bit_for_bit() -> None:
    # the ledger's reduced study (two methods, no opposite-sign sweep) against the full study on the same seed
    full, part = ch.fair(5, 4), ch.fair_weights(5, 4)
    assert set(part.mae) == {k for k in full.mae if k[0] != ofs_fair.OPPOSITE}
    for key, errors in part.mae.items():
        assert list(errors) == ["optimal_fusion_set", "uniform_set"]
        for m, v in errors.items():
            np.testing.assert_array_equal(v, full.mae[key][m])
    assert (part.n_runs, part.n_samples, part.seed) == (full.n_runs, full.n_samples, full.seed)
    # the fault-free points share one fusion of the clean readings: it is fair_errors's on them
    clean = 900.0 + np.random.default_rng(5).standard_normal((4, 100, 10))
    ref = ofs_fair.fair_errors(clean, np.ones(10))
    for key in ((ofs_fair.SIZE, 0.0), (ofs_fair.COUNT, 0.0), (ofs_fair.SPREAD, 1.0)):
        for m, v in ref.items():
            np.testing.assert_array_equal(full.mae[key][m], v)
    with pytest.raises(ValueError, match="methods"):
        ofs_fair.fair_study(3, n_runs=2, methods=("optimal_fusion_set", "oracle"))
    with pytest.raises(ValueError, match="methods"):
        ofs_fair.fair_errors(np.zeros((1, 2, 3)), np.ones(3), methods="oracle")


@pytest.mark.parametrize("mode", th.FAILURE_MODES)
@pytest.mark.parametrize("methods", [ch.METHODS, {"set": {"method": "optimal_fusion_set", "include_self": False},
                                                  "mean": {"method": "mean"}}])
def test_paired_study_fuses_again_only_the_epochs_the_failure_changes(mode: str, methods: dict) -> None:
    # the reference: every epoch of both arrays fused (absolute_errors), the set's members fused on their own
    st = th.paired_study(11, 6, methods, failure_mode=mode)
    rng = np.random.default_rng(11)
    z = th.simulate(rng, n_runs=6)
    z_fail = th.random_failure(z, rng, mode)
    for errors, arr in ((st.clean, z), (st.failed, z_fail)):
        ref = th.absolute_errors(arr, methods)
        assert list(errors) == list(ref)
        for label in ref:
            np.testing.assert_array_equal(errors[label], ref[label])
    members = rd.fuse_epochs(z.reshape(-1, 10), "optimal_fusion_set").members
    np.testing.assert_array_equal(st.set_size, members.sum(axis=1).reshape(6, 100).mean(axis=1))
    fm = rd.fuse_epochs(z_fail[:, 49:80].reshape(-1, 10), "optimal_fusion_set").members
    assert st.failed_member_share == (fm[:, 3].mean(), fm[:, 9].mean())
    assert not np.array_equal(st.clean["mean"], st.failed["mean"])


def test_window_studies_fuse_only_the_window_and_give_the_full_fusions_numbers() -> None:
    # references: every epoch fused, then the window's errors averaged (the code before issue 37)
    scales = [0.5, 2.0]
    methods = {f"s{k}": {"method": "optimal_fusion_set", "scale": s} for k, s in enumerate(scales)}
    e = th.monte_carlo(4, 5, methods, failure={})
    np.testing.assert_array_equal(th.scale_sweep(4, 5, scales, failure={}, window=(50, 80)),
                                  np.stack([e[f"s{k}"][:, 49:80].mean(axis=1) for k in range(2)]))
    with pytest.raises(ValueError, match="window"):
        th.scale_sweep(4, 5, scales, failure={}, window=(50, 101))
    z = th.inject_failure(th.simulate(np.random.default_rng(4), n_runs=5), **data.YANG2012_FAILURE)
    flat = z.reshape(-1, 10)
    fam = ch.family_mae(z, window=(50, 80))
    for label, f in ch.FAMILIES.items():
        ref = np.abs(ch.family_values(flat, f, 2.0).reshape(5, 100) - 900.0)[:, 49:80].mean(axis=1)
        np.testing.assert_array_equal(fam[label], ref)
    abl = ch.weight_ablation(z, window=(50, 80))
    ref = {"optimal_fusion_set": rd.fuse_epochs(flat, "optimal_fusion_set").values,
           "uniform_set": robust_fuse(flat, "uniform_set")}
    for k, v in ref.items():
        np.testing.assert_array_equal(abl[k], np.round(np.abs(v - 900.0).reshape(5, 100)[:, 49:80].mean(axis=1), 9))


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


def test_weight_study_relative_weights_and_the_stability_comparison() -> None:
    ws = ch.weight_study(4, 100)
    z = th.simulate(np.random.default_rng(4), n_runs=100)
    f = rd.fuse_epochs(z.reshape(-1, 10), "optimal_fusion_set")
    m = f.members.reshape(100, 100, 10)
    np.testing.assert_allclose(ws.member, m.mean(axis=(0, 1)))
    # sensor 1's relative weight in run 0, computed directly epoch by epoch
    w = f.weights.reshape(100, 100, 10)[0]
    direct = np.mean([w[t, 0] * m[0, t].sum() for t in range(100) if m[0, t, 0]])
    assert ws.relative[0, 0] == pytest.approx(direct)
    # the set's relative weights average to one (equal shares) in every epoch
    np.testing.assert_allclose((w * m[0].sum(axis=1, keepdims=True)).sum(axis=1) / m[0].sum(axis=1), 1.0)
    c = ch.ev_weights_stability({}, seed=4, runs=100)   # the primary: the precise half against the other half
    assert c.claim == "greater" and np.array_equal(c.b, ws.relative[:, 5:].mean(axis=1))
    assert np.array_equal(c.a, ws.relative[:, :5].mean(axis=1))
    pair = ch.ev_weights_stability({"sensors": (1, 10)}, seed=4, runs=100)
    assert np.array_equal(pair.b, ws.relative[:, 9])
    with pytest.raises(ValueError, match="sensors"):
        ch.ev_weights_stability({"sensors": (0, 11)}, seed=4, runs=100)


def test_healthy_dropped_share_is_a_share_on_the_failure_draws() -> None:
    out = ch.healthy_dropped_share(3, 20)
    assert 0.0 <= out["failure"] <= 1.0 and 0.0 <= out["clean"] <= 1.0 and out["epochs"] == 20 * 31
    assert out == ch.healthy_dropped_share(3, 20)


def test_ew_variance_fuse_downweights_a_persistent_fault_and_checks_input() -> None:
    rng = np.random.default_rng(0)
    z = 900.0 + rng.standard_normal((50, 100, 10))
    zf = z.copy()
    zf[:, 49:80, 3] += 8.0
    fused = ofs_fair.ew_variance_fuse(zf)
    assert np.allclose(fused[:, 0], zf[:, 0].mean(axis=1))
    assert np.abs(fused[:, 60:80] - 900.0).mean() < np.abs(zf[:, 60:80].mean(axis=2) - 900.0).mean() / 2
    with pytest.raises(ValueError):
        ofs_fair.ew_variance_fuse(z[0])
    with pytest.raises(ValueError):
        ofs_fair.ew_variance_fuse(z, lam=0.0)


def test_fault_shapes_study_and_table() -> None:
    s = ofs_fair.fault_shapes_study(1, 100)
    assert list(s) == list(ofs_fair.FAULT_SHAPES)
    assert all(v.shape == (100,) for errs in s.values() for v in errs.values())
    # translation equivariance: a true value of 905 °C changes no method's error
    assert all(np.allclose(s["no fault"][m], s["true value 905 °C, not 900 °C"][m], atol=1e-6) for m in s["no fault"])
    assert s["drift (ramp to +4, +8 °C)"]["mean"].mean() > s["no fault"]["mean"].mean()
    df = ofs_fair.fault_shapes_table(s, 1)
    assert df.shape == (len(ofs_fair.FAULT_SHAPES), 7)
