"""Fuzz 26d (chapters 01-04 and 07), classes B, C, D, E, F, W and the debatables DB2-DB8 (the second fixer's share):
bad input refused by the caller's argument name, valid input kept, the texts of a study taken from it (issue 35)."""

from __future__ import annotations

import re

import pytest

from fusion.book.chapters import ofs, ofs_fair


def _starts(e: pytest.ExceptionInfo, name: str) -> bool:
    return re.match(rf"{re.escape(name)}(?!\w)", str(e.value)) is not None


# --------------------------------------------------------------------------- D: fair_study with one sensor, budgets
@pytest.mark.parametrize("sweep", ["sizes", "opposite"])
def test_d_two_sensor_sweeps_need_two_sensors(sweep: str) -> None:
    kw = dict(sizes=(), counts=(), spreads=(), opposite=())
    kw[sweep] = (2.0,)
    with pytest.raises(ValueError) as e:
        ofs_fair.fair_study(0, 5, 5, n_sensors=1, **kw)
    assert _starts(e, sweep) and "n_sensors" in str(e.value), str(e.value)
    # two sensors hold them; one sensor still runs the sweeps that need one
    ofs_fair.fair_study(0, 5, 5, n_sensors=2, **kw)
    st = ofs_fair.fair_study(0, 5, 5, n_sensors=1, sizes=(), counts=(0, 1), spreads=(1, 2), opposite=())
    assert (ofs_fair.COUNT, 1.0) in st.mae


def test_d_fair_study_budgets_before_drawing() -> None:
    with pytest.raises(ValueError) as e:
        ofs_fair.fair_study(0, 10**6)   # 7.45 GiB of draws
    assert _starts(e, "n_runs") and "memory budget" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        ofs_fair.fair_study(0, 5000)    # 0.4 GB of draws, but about two minutes of fusing
    assert _starts(e, "n_runs") and "work budget" in str(e.value), str(e.value)
    # the work counts the points and methods asked: one point of one method at 5,000 runs is inside the budget
    ofs_fair.fair_study(0, 5000, 2, sizes=(1,), counts=(), spreads=(), opposite=(), methods=("mean",))


@pytest.mark.parametrize("fn", [ofs.fair, ofs.fair_weights])
@pytest.mark.parametrize("runs", [10**6, 10**4])
def test_d_fair_entries_name_runs(fn, runs: int) -> None:
    with pytest.raises(ValueError) as e:
        fn(0, runs)
    assert _starts(e, "runs") and "budget" in str(e.value), str(e.value)


# --------------------------------------------------------------------------- W4: the chapter 01 studies name runs
@pytest.mark.parametrize("name", ["study", "weight_study", "membership_study", "alpha_study", "claim_values",
                                  "evidence", "faulty_member_share", "healthy_dropped_share",
                                  "not_neighbourhood_share"])
def test_w4_ofs_studies_name_runs(name: str) -> None:
    with pytest.raises(ValueError) as e:
        getattr(ofs, name)(0, 10**6)
    assert _starts(e, "runs") and "memory budget" in str(e.value), str(e.value)


# --------------------------------------------------------------------------- C, DB2: one-run benchmark's standard error
def test_c_glue_offset_refuses_one_run_naming_results() -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    kw = dict(seeds=(9001,), samples=20, levels=(900.0,), fault_from=0, faults=(True,))
    with pytest.raises(ValueError) as e:
        ch2.glue_offset(lw.benchmark(runs=1, **kw))
    assert _starts(e, "results") and "2 runs" in str(e.value), str(e.value)
    g = ch2.glue_offset(lw.benchmark(runs=2, **kw))
    assert all(v == v for v in g.values())


def test_db2_table_benchmark_one_run_shows_no_standard_error() -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    for runs in (1, 2):
        res = lw.benchmark(seeds=(5, 6), runs=runs, samples=10)
        tab = ch2.table_benchmark(res, lw.seed_stability(res), samples=10)
        cells = tab.iloc[:, 0]
        assert all(c.endswith("± n/a") for c in cells) == (runs == 1), list(cells)
        assert not any(c.endswith("± 0.0000") for c in cells), list(cells)


# --------------------------------------------------------------------------- B: E2.6 of another setup than m
def test_b_glue_mechanism_refuses_e26_of_another_setup() -> None:
    from fusion.book.chapters.lecture_wavelets import mechanism as mech
    from fusion.book.chapters.lecture_wavelets import records as lwr
    m = lwr.study("m26", 2601, 100)
    mech.glue_mechanism(m, lwr.study("e26", 2601, 100))   # the chapter's pairing
    from fusion.book.chapters.lecture_wavelets import appendix as wa
    for other in (lwr.study("g1", 2601, 100), wa.length_study(64, runs=100)):   # equal gains; 64 samples
        for fn in (mech.table_sensitivity_display, mech.glue_mechanism):
            with pytest.raises(ValueError) as e:
                fn(m, other)
            assert _starts(e, "e26") and "another setup" in str(e.value), str(e.value)


# --------------------------------------------------------------------------- E: chapter-layer specs of what is read
def test_e1_registration_study_robust_entries_hold_the_methods_read() -> None:
    import dataclasses

    from fusion.book.chapters import time_registration_ledger as trl
    from fusion.scenarios import time_registration as sc
    st = trl.cached_study(0, 100)
    k0 = next(iter(st.robust))
    mc4 = sc.monte_carlo([m.value for m in sc.RegMethod][:4], 1.0, 4, 0)   # without the improved method
    with pytest.raises(ValueError) as e:
        dataclasses.replace(st, robust={**st.robust, k0: mc4})
    assert _starts(e, "RegistrationStudy.robust") and "reg_improved" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        dataclasses.replace(st, sigma=2.0)   # every run at sigma 1
    assert _starts(e, "RegistrationStudy.robust") and "sigma" in str(e.value), str(e.value)
    dataclasses.replace(st, robust=dict(st.robust))   # the study's own entries


@pytest.mark.parametrize("field", ["known", "estimated"])
def test_e2_plugin_exact_requires_every_crossing(field: str) -> None:
    import dataclasses

    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.chapters.lecture_correlated.ridge import _CROSSINGS
    from fusion.scenarios import ridge_sensors as rs
    x = ch.plugin_exact(rs.plugin_study(xs=(0.0, 0.5, 1.0, 3.0), runs=100, seed=4))
    for drop in _CROSSINGS:
        if field == "known":
            c0 = next(iter(x.known))
            value = {**x.known, c0: {k: v for k, v in x.known[c0].items() if k != drop}}
        else:
            value = {k: v for k, v in x.estimated.items() if k != drop}
        with pytest.raises(ValueError) as e:
            dataclasses.replace(x, **{field: value})
        assert _starts(e, f"PluginExact.{field}") and drop in str(e.value), str(e.value)


# --------------------------------------------------------------------------- F: texts of the study, not the default's
def test_f1_figure_21a_states_the_study_variance() -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    kw = dict(levels=(0.0, 100.0, 900.0), runs=20, k_max=100, ks=(10, 100), k_compare=100)
    for sigma, v in (((0.5, 1.0, 2.0, 4.0), 0.25), ((1.0, 1.0, 2.0, 4.0), 1.0)):
        ax = ch2.figure_21a(lw.awf_study(sigma=sigma, **kw)).axes[0]
        assert ax.get_ylabel() == f"estimate of σ₁² (σ₁² = {v:g})"
        assert ax.get_ylim() == pytest.approx((-10 * v, 12 * v))


@pytest.mark.parametrize("sensor", [0, 2])
def test_f2_figure_23_names_the_faulty_sensor(sensor: int) -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    f = ch2.figure_23(lw.consistency_study(runs=20, fault_sensor=sensor, curve_draws=200))
    texts = [f.axes[0].get_title(), f.axes[1].get_xlabel(), f.axes[1].get_ylabel()]
    assert all(f"sensor {sensor + 1}" in t for t in texts), texts
    assert not any(f"sensor {k}" in t for t in texts for k in {1, 2, 3, 4} - {sensor + 1}), texts


def test_f3_figure_25_states_the_study_sigma() -> None:
    from fusion.book.chapters import lecture_correlated as ch4
    from fusion.scenarios import lecture_correlated as lsc
    for sigma in (1.0, 2.0):
        s = lsc.ridge_study(sigma=sigma, draws=50)
        assert ch4.figure_25(s).axes[0].get_ylabel() == f"MSE (m = {s.m0}, σ = {sigma:g})"


def test_f4_table_regime_names_the_study_level() -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    kw = dict(samples=60, runs=20, change_at=30, period=40.0, window=10)
    for level in (100.0, 900.0):
        cols = list(ch2.table_regime(lw.regime_study(level=level, **kw)).columns)
        assert f"slow sine at {level:g}" in cols and sum(c.startswith("slow sine at") for c in cols) == 1, cols


# --------------------------------------------------------------------------- W1-W3: the caller's argument named
@pytest.mark.parametrize("fn", ["table_belief_limit", "table_belief_grids"])
def test_w1_w2_belief_tables_name_s(fn: str) -> None:
    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    s = lw.belief_parameter_study(params=(1.0, 2.0), grid=(1.0, 2.0), snapshots=100)
    with pytest.raises(ValueError) as e:
        getattr(ch2, fn)(s)
    assert _starts(e, "s") and "params" in str(e.value), str(e.value)


def test_w3_log_range_bounded_by_name() -> None:
    from hypothesis import given, settings, strategies as st

    from fusion.book.chapters import lecture_weighting as ch2
    from fusion.scenarios import lecture_weighting as lw
    from fusion.scenarios.lecture_weighting.learning import MAX_LOG_RANGE

    @settings(max_examples=15, deadline=None)
    @given(st.floats(min_value=MAX_LOG_RANGE, max_value=1e6, exclude_min=True))
    def beyond(a: float) -> None:
        with pytest.raises(ValueError) as e:
            ch2.spread_check((1.0, a), 20, 2204)
        assert _starts(e, "log_ranges[1]"), str(e.value)
        with pytest.raises(ValueError) as e:
            lw.learned_limit_check(draws=20, log_range=a)
        assert _starts(e, "log_range"), str(e.value)

    beyond()
    ch2.spread_check((MAX_LOG_RANGE,), 20, 2204)   # the bound itself: every variance within the numeric range


# --------------------------------------------------------------------------- DB3: fair_numbers lists points in order
def test_db3_fair_numbers_do_not_depend_on_the_sweep_order() -> None:
    kw = dict(counts=(0, 1, 5), spreads=(1, 16), opposite=(2, 6))
    a = ofs_fair.fair_numbers(ofs_fair.fair_study(0, 100, 10, sizes=(0, 4, 8), **kw))
    b = ofs_fair.fair_numbers(ofs_fair.fair_study(0, 100, 10, sizes=(8, 4, 0), **{k: v[::-1] for k, v in kw.items()}))
    assert a == b, {k: (a[k], b[k]) for k in a if a[k] != b[k]}


# --------------------------------------------------------------------------- DB7: one "written as" rule
def test_db7_table_shift_weight_takes_a_grid_point_as_written() -> None:
    import numpy as np
    from hypothesis import given, settings, strategies as st

    from fusion.book.chapters import lecture_weighting as ch2
    d = ch2.shift_weight_draws(draws=5)

    @settings(max_examples=25, deadline=None)
    @given(st.integers(0, 200), st.sampled_from(["float32", "product"]))
    def on_grid(k: int, how: str) -> None:
        a = np.float32(k / 10) if how == "float32" else k * 0.1
        tab = ch2.table_shift_weight(d, (a,))
        assert tab.index.tolist() == [f"{k / 10:g}"]

    on_grid()
    for a in (np.float32(0.35), 0.3 + 1e-6):   # between grid points: refused by name
        with pytest.raises(ValueError) as e:
            ch2.table_shift_weight(d, (a,))
        assert _starts(e, "at[0]"), str(e.value)


# --------------------------------------------------------------------------- DB4: chapter 03's studies of other seeds
def test_db4_chapter03_studies_of_other_seeds_are_read_each_on_its_own() -> None:
    from fusion.book.chapters.lecture_wavelets import records as lwr
    st = {k: lwr.study(k, 2601, 100) for k in lwr.STUDIES}
    mixed = {**st, "e26": lwr.study("e26", 2602, 100)}
    lwr.ledger_values(mixed)   # documented: accepted
    def seeds_of(ev: object) -> set:
        parts = getattr(ev, "parts", None)
        return set().union(*(seeds_of(p) for _, p in parts)) if parts else {getattr(ev, "seed", None)}

    seeds = set().union(*(seeds_of(ev) for rec in lwr.evidence(mixed).values() for ev in rec.values()))
    assert {2601, 2602} <= seeds, seeds   # each reading at its own study's seed


# --------------------------------------------------------------------------- DB5, DB8: chapter 07's instants
def test_db5_db8_noise_gain_by_instant_documented_behaviour() -> None:
    import numpy as np

    from fusion.book.chapters import time_registration_ledger as trl
    from fusion.scenarios import time_registration as sc
    t1, t2 = (np.asarray(t, dtype=float) for t in sc.instants())
    a = trl.noise_gain_by_instant(t1, t2)
    b = trl.noise_gain_by_instant(t1 - 30.0, t2 - 30.0)   # DB5: before the start, the same gains
    np.testing.assert_allclose(b.to_numpy(dtype=float), a.to_numpy(dtype=float), rtol=1e-9, atol=1e-9)
    t2n = t2.copy()
    j = int(np.searchsorted(t1, t2[0]))
    t2n[0] = t1[j] * (1 + 1e-15) if t1[j] != 0 else t1[j] + 1e-15   # DB8: a few ulps from a sample
    c = trl.noise_gain_by_instant(t1, t2n)
    assert not c["sample time"].iloc[0] and c["g two-point"].iloc[0] == pytest.approx(1.0, abs=1e-9)


# --------------------------------------------------------------------------- DB6: the work budget applied
def test_db6_time_registration_studies_within_the_work_budget() -> None:
    from fusion.book.chapters import time_registration_ledger as trl
    from fusion.scenarios import time_registration as sc
    t1, t2 = sc.instants()
    with pytest.raises(ValueError) as e:
        trl.study(t1, t2, 1.0, 10**6, 0)   # minutes before (10.4 CPU-s at 1e5 runs)
    assert _starts(e, "runs") and "work budget" in str(e.value), str(e.value)
    names = [m.value for m in sc.RegMethod]
    with pytest.raises(ValueError) as e:
        sc.monte_carlo(names, 1.0, 5 * 10**6, 0)
    assert _starts(e, "runs, names") and "work budget" in str(e.value), str(e.value)
