"""Fuzz 39a (entry budgets): a caller's entry refuses exactly what its callees' inner limits would, naming the
caller's arguments, before any work (C2, D1); a chunk loop is counted (C3); simultaneous temporaries share the
memory budget (D2); ``ofs_audit.explain`` sizes ``order`` before converting it (E1); the wavelet's constant-residual
level on long signals (E2); unique case labels (E3)."""

from __future__ import annotations

import time

import numpy as np
import pytest

from fusion._limits import MAX_INPUT_ELEMENTS


def _refused_fast(f, *args, match: str, **kw) -> None:
    t = time.process_time()
    with pytest.raises(ValueError, match=match):
        f(*args, **kw)
    assert time.process_time() - t < 1.0


def test_correlated_study_refuses_a_stacked_z_beyond_the_gls_input_at_entry():
    """C2: z is (2N, runs); 480 x 70,000 was refused by gls after the draws, naming every argument."""
    from fusion.scenarios import lecture_correlated as lc

    sig = tuple(1.0 + 0.001 * np.arange(240))
    runs = MAX_INPUT_ELEMENTS // 480 + 1
    assert lc._stacked_shape(240, runs) == (480, runs)
    _refused_fast(lc.correlated_study, sigma=sig, runs=runs, sigma_env=0.5, match=r"^sigma and runs ask .*input budget")


def test_correlated_study_entry_edge_is_the_gls_input_edge():
    """C2, the bound inside: the largest runs the entry accepts is the largest z gls accepts (checked by the rule)."""
    from fusion._counts import input_allocation
    from fusion.scenarios import lecture_correlated as lc

    runs = MAX_INPUT_ELEMENTS // 480
    input_allocation(lc._stacked_shape(240, runs), "sigma and runs")  # accepted
    with pytest.raises(ValueError):
        input_allocation(lc._stacked_shape(240, runs + 1), "sigma and runs")


_OFS = {"mean": {"method": "mean"}, "ofs": {"method": "optimal_fusion_set"}}


def test_thermocouples_monte_carlo_refuses_fuse_epochs_limits_at_entry():
    """D1: the n_runs * n_samples epochs beyond fuse_epochs's input budget or its kernel's work budget are refused
    before the draws, naming the caller's arguments (they were refused inside fuse_epochs naming every argument)."""
    from fusion.scenarios import thermocouples as th

    _refused_fast(th.monte_carlo, 1, 40_000, _OFS, match=r"^n_runs, n_samples, n_sensors and methods ask .*input budget")
    _refused_fast(th.monte_carlo, 1, 5_001, _OFS, match=r"^n_runs, n_samples, n_sensors and methods \(10 readings")


def test_thermocouples_monte_carlo_edge_is_fuse_epochs_edge():
    """D1, the bound inside: 5,000 runs of 100 epochs of 10 readings pass the same rule fuse_epochs applies."""
    from fusion.readings._row_blocks import epochs_limit

    epochs_limit(5_000 * 100, 10, "optimal_fusion_set", "n_runs")  # accepted
    with pytest.raises(ValueError, match="n_runs"):
        epochs_limit(5_001 * 100, 10, "optimal_fusion_set", "n_runs")


@pytest.mark.parametrize("study", ["tail_study", "lumv_study"])
def test_chunk_beyond_the_variance_estimates_input_is_refused_at_entry(study):
    """D1: a chunk of (chunk, k, n) readings beyond wt.variance_estimates' input budget is refused at entry, naming
    runs and chunk (it was refused inside, after the chunk's draws)."""
    from fusion.scenarios.lecture_weighting import estimators as es

    _refused_fast(getattr(es, study), sigma=(1.0, 2.0, 3.0, 4.0), k=2, runs=10**7, chunk=10**7,
                  match=r"^runs, chunk, k and sigma ask .*input budget")


@pytest.mark.parametrize("study, inside, outside", [("tail_study", 249_000, 251_000), ("lumv_study", 39_900, 40_100)])
def test_chunk_of_one_counts_its_python_steps(study, inside, outside):
    """C3: chunk = 1 makes a Python step a run (tail_study, ~30 us) or a pair (lumv_study, ~480 us); the loop is
    counted: just outside the edge is refused quickly naming chunk, just inside passes the same rule (its run,
    7-11 CPU-s measured, is not repeated here)."""
    from fusion.scenarios.lecture_weighting import estimators as es

    _refused_fast(getattr(es, study), sigma=(1.0, 2.0), k=2, runs=outside, chunk=1, match=r"^runs, chunk, k and sigma")
    step, items, per = (4_000, inside, 4) if study == "tail_study" else (50_000, inside // 2, 96)
    es._chunk_loop(items, 1, items * per, step)  # accepted
    with pytest.raises(ValueError, match="chunk"):
        es._chunk_loop(items + 1000, 1, (items + 1000) * per, step)


def _probe_calls():
    from fusion.book.chapters.lecture_correlated import appendix
    from fusion.scenarios import ridge_sensors as rs
    from fusion.scenarios.lecture_weighting import estimators as es, learning as le

    s4 = (0.5, 1.0, 2.0, 4.0)
    return {  # each array 4e7 entries: inside the memory budget (2**28), beyond the callee's input budget (2**25)
        "ar1_study": ("runs, k and sigma", lambda: es.ar1_study(sigma=s4, k=2, runs=5_000_000)),
        "plugin_study": ("m and runs", lambda: rs.plugin_study(xs=(1.0,), m=5, runs=8_000_000)),
        "learning_study": ("runs, epochs and r_sets",
                           lambda: le.learning_study(r_sets=((1.0, 4.0),), epochs=2, runs=10_000_000, last=2)),
        "learned_limit_check": ("ns and draws", lambda: le.learned_limit_check(ns=(8,), draws=5_000_000)),
        "table_james_stein": ("ds and runs", lambda: appendix.table_james_stein(ds=(10,), ratios=(1.0,),
                                                                                runs=4_000_000)),
    }


@pytest.mark.parametrize("name", ["ar1_study", "plugin_study", "learning_study", "learned_limit_check",
                                  "table_james_stein"])
def test_drawn_readings_beyond_a_callees_input_budget_are_refused_at_entry(name):
    """D1 (the class, found by probing every entry with an ``allocation`` check): these drew 4e7 readings (1-3
    CPU-s) and were refused by their callee's input budget, naming the callee's argument or every argument."""
    names, call = _probe_calls()[name]
    _refused_fast(call, match=rf"^{names} ask for an array of 4e\+07 elements .*input budget")


def test_is_objective_counts_its_two_simultaneous_arrays():
    """D2: is_objective holds two (R, E) arrays at once (tracemalloc: 2.08); R x E = 1.5e8 (2**21 x 72) passed the memory rule
    checked on one array (2**28) and held two of 1.2 GiB. Now refused by name; just inside (R x E = 2**21 x 42: three
    arrays, 2.08 rounded up, review 18) passes
    the same rule."""
    from fusion._counts import allocation
    from fusion.estimates.chernoff.mixture import is_objective

    R = 2**21
    L, lg = np.zeros((R, 1)), np.zeros(R)
    _refused_fast(is_objective, L, lg, np.ones((72, 1)), match=r"^L and eps ask .*3 arrays of")
    allocation((R, 42), "L and eps", arrays=3)  # accepted: 2**28 elements in all (3 arrays: 2.08 rounded up)
    with pytest.raises(ValueError, match="L and eps"):
        allocation((R, 43), "L and eps", arrays=3)


@pytest.mark.parametrize("order", [lambda: list(range(2**22)), lambda: [list(range(6))] * (2**22 // 6),
                                   lambda: [list(range(2**22))]])
def test_explain_sizes_order_before_converting_it(order):
    """E1: an order of 2**25 entries was converted (1.7-2.2 CPU-s) before its shape check (here 2**22); now counted
    from its lengths first and it is refused by name at once."""
    from fusion.book.chapters import ofs_audit as oa

    given = order()
    _refused_fast(oa.explain, oa.corrections()[0], "correct", order=given,
                  match=r"^order must have shape \(6,\) or \(1, 6\) .*got (at least )?\S+ entries")


def test_explain_order_of_six_still_accepted():
    """E1, the bound inside: one order of the six observations, as a row or a single-row list, is read."""
    from fusion.book.chapters import ofs_audit as oa

    c = oa.corrections()[0]
    a = oa.explain(c, "correct", order=[5, 4, 3, 2, 1, 0])
    b = oa.explain(c, "correct", order=[[5, 4, 3, 2, 1, 0]])
    assert a.equals(b)


@pytest.mark.parametrize("reader", ["table_coupling", "figure_coupling"])
def test_a_case_key_reading_as_another_cases_label_is_refused(reader):
    """E3: a caller's case key equal to another case's registered label gave two rows (curves) one label."""
    import matplotlib.pyplot as plt

    from fusion.book.chapters.lecture_correlated import correlated as ch
    from fusion.book.style import METHOD_LABELS
    from fusion.scenarios import correlated_sensors as cs

    key = cs.CouplingCase.UNEQUAL
    case = cs.SCENARIOS[key]
    study = cs.coupling_study({key: case, METHOD_LABELS[key]: case}, runs=100)
    with pytest.raises(ValueError, match=r"^s has the cases .* with one label"):
        getattr(ch, reader)(study)
    ok = getattr(ch, reader)(cs.coupling_study({key: case, "my case": case}, runs=100))  # distinct labels: read
    if reader == "table_coupling":
        assert list(ok.index) == [METHOD_LABELS[key], "my case"]
    plt.close("all")


def test_a_case_key_that_is_a_method_key_is_its_own_label():
    """E3: a case key that is another method's key in METHOD_LABELS ("gls") is labelled as given, not as GLS."""
    from fusion.book.chapters.lecture_correlated import correlated as ch

    assert ch._case_label("gls") == "gls"


def test_constant_residual_round_off_holds_up_to_the_input_limit():
    """E2: the "batch" rule calls a residual constant when its variance is at most (8 eps max|z|)^2 (plus the
    cancellation term). numpy's pairwise mean of a constant was measured at most 2.75 eps off (sqrt(var) / (eps c),
    300 values of c at N = 10**6; 0.1, 1/3, 1e5 + 0.1 and others up to N = 2**25, the input limit): within the
    level, so a long constant residual is still refused and none is exempted by its length."""
    from fusion.readings.wavelet import _ROUND_OFF_UNITS, fuse_denoised

    eps = np.finfo(float).eps
    for c in (0.1, 1 / 3, 1e5 + 0.1):
        z = np.full(MAX_INPUT_ELEMENTS // 4, c)  # 2**23 here (the measurement ran to 2**25)
        assert np.sqrt(z.var()) <= _ROUND_OFF_UNITS * eps * c
    N = 2**19
    t = np.linspace(0.0, 1.0, N)
    Y = np.stack([1.0 + 0.5 * np.sin(2 * np.pi * t), 2.0 + 0.1 * t])
    X = Y + np.array([[1e5 + 0.1], [0.0]]) + np.array([[0.0], [0.01]]) * np.random.default_rng(1).normal(size=N)
    with pytest.raises(ValueError, match=r"sensor\(s\) \[0\] have zero residual variance"):
        fuse_denoised(X, Y)


@pytest.mark.parametrize("name, inside, outside", [("split_ci_exactness", 4_347, 4_350),
                                                   ("shift_weight_draws", 552, 560)])
def test_chapter_counts_reweighted_at_their_measured_edge(name, inside, outside):
    """E4: at their old edges split_ci_exactness (98,000 steps) ran 68 CPU-s and shift_weight_draws (4,851 draws)
    83 CPU-s; re-weighted from the measurement (0.70 ms a step, 85 us a draw and shift) the edge is ~10 CPU-s (split
    CI's step re-measured at 1.15 ms and weighed twice by book audit 76: 4,347 steps). Just outside is refused at once
    by the count's name; just inside passes the same rule (its run is not repeated)."""
    from fusion._limits import loop_work
    from fusion.book.chapters.ci import printed
    from fusion.book.chapters.lecture_weighting import belief

    if name == "split_ci_exactness":
        Q, R1, _ = printed.printed_covariances()
        _refused_fast(printed.split_ci_exactness, Q, R1, 1.0, outside, match=r"^n_steps ask")
        loop_work((inside,), 0, "n_steps", step=printed._SPLIT_CI_STEP)
    else:
        _refused_fast(belief.shift_weight_draws, draws=outside, match=r"^draws and sigma ask")
        loop_work((inside, 201), 4, "draws and sigma", step=belief._SHIFT_DRAW_STEP)


def test_ls_special_cases_counts_its_scalar_steps_as_measured():
    """E4: its recursive filter's Python steps are scalar arithmetic, 0.29 us each: 980,000 steps (the old edge, a
    LOOP_STEP each) ran 0.28 CPU-s, so valid requests of 1-10 million readings (0.3-3 CPU-s) were refused. At 100
    units a step the edge (9.9e6 steps) ran 3.1 CPU-s; just outside is refused at once, just inside passes the rule."""
    from fusion._limits import loop_work
    from fusion.book.chapters.lecture_correlated import propositions as pr

    _refused_fast(pr.ls_special_cases, np.random.default_rng(0), 10**7, match=r"^m ask")
    loop_work((9_900_000,), 1, "m", step=100)
    assert set(pr.ls_special_cases(np.random.default_rng(0), 2 * 10**6)) == {"mean", "weighted mean",
                                                                             "recursive filter"}  # ~0.6 CPU-s


def test_check_grid_refuses_beyond_its_callees_input_and_weighs_a_reading_as_measured():
    """D1/E4: check_grid's readings beyond the fusions' input budget were refused inside (130,666 runs, 1.7 CPU-s,
    naming X); and a counted reading costs 470-580 ns (its input edge, 67,108 runs, ran over 240 CPU-s at 1 unit):
    now 50 units, the edge 2,666 runs of the default grid. Just outside is refused at once; just inside passes."""
    from fusion._limits import work
    from fusion.book.chapters.lecture_weighting import consistency as c

    _refused_fast(c.check_grid, runs=67_109, match=r"^runs, samples and sigma ask .*input budget")
    _refused_fast(c.check_grid, runs=2_700, match=r"^biases, eps_factors, runs, samples and sigma ask")
    work((5, 3, 2_666, 100, 5), "runs", weight=50)
