"""Chapter 05's public functions refuse bad input: one valid call each, mutated one argument at a time (issue 35).

The registry below holds a valid call of every public function of ``fusion.book.chapters.ci`` (classes excluded: the
result classes are covered by tests/test_bad_input_results_chapters.py), each argument with the mutations its
documented meaning must refuse, swept by :func:`test_bad_input.refusal_problems` (a ValueError/TypeError naming the
argument). Objects are built once, at the smallest size valid input allows: the two-sensor case at T = 8 s with 2
runs, the infrared + radar case at 3 runs of 3 s, the chapter tests' synthetic ledger entries (100 runs, rule R4).
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
from typing import Any

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from test_bad_input import (A, ARR, COUNT, NONNEG, OBJ, OPT, POS, REAL, UNIT, public_callables,  # noqa: E402
                            group_tests)

PREFIXES = ("fusion.book.chapters.ci.",)

CALLABLES = {k: v for k, v in public_callables().items() if k.startswith(PREFIXES) and not inspect.isclass(v)}

#: Functions without a registry entry: valid calls that are long studies (CPU-s measured in one process) or need
#: rule R4's 100 runs of one. Their arguments' mutations are swept without the valid call by the all-defaults
#: property test (tests/test_bad_input_chapters_b.py), each refused at the entry.
EXCLUDED: dict[str, str] = {
    "arch_study": "every architecture of both pairs: 2.9 CPU-s at 3 runs",
    "paired_study": "the paired studies of three pairs with FOA's per-step weights: 2.5 CPU-s at 3 runs",
    "ledger_studies": "every Monte-Carlo study of the ledger: more than 5 CPU-s at 3 runs",
    "ir_reading_study": "the infrared + radar readings over 10 s: 1.5 CPU-s at 3 runs",
    "step_weights": "FOA at each of the 261 steps: 0.8 CPU-s",
    # the seeded studies below are in the SLOW list of tests/test_bad_input_chapters_b.py too: 0.3 CPU-s each at the
    # smallest valid size (FOA over 100 seeds, 50 runs, three periods), which this file's budget (10 CPU-s) lacks
    "unequal_pair": "the unequal pair's 50 runs and FOA over 100 seeds: 0.3 CPU-s",
    "aniso_pair": "the anisotropic pair's runs and FOA over 100 seeds: 0.3 CPU-s at 3 runs",
    "fig6_periods": "fresh runs at each of Fig. 6's periods: 0.3 CPU-s at 3 runs",
    "figure_rows": "no argument; its result holds the documented NaN of the curves the source quotes no RMSE for",
    "record_evidence": "a stochastic record's evidence needs rule R4's 100 runs of the paired or IR studies (minutes)",
    "ev_fig4_convex_part": "rule R4: 100 runs of the architecture and paired studies (minutes)",
    "ev_fig7_improved_vs_ci": "rule R4: 100 runs of the architecture and paired studies (minutes)",
    "ev_fig6_foa_vs_grid": "rule R4: 100 runs of the paired studies (minutes)",
    "ev_fig10_x_below_y": "rule R4: 100 runs of the infrared + radar readings (minutes)",
    "ev_fig10_convex_errors": "rule R4: 100 runs of the infrared + radar readings (minutes)",
    "ev_fig10_fuzzy_errors": "rule R4: 100 runs of the infrared + radar readings (minutes)",
}
EXCLUDED = {"fusion.book.chapters.ci." + k: v for k, v in EXCLUDED.items()}

#: Sampling period (s) of the small two-sensor cases: 33 steps over the source's path.
TS = 8.0

SEED_M = ("neg", "frac", "str", ("bool", True))           # a seed: an int >= 0
COUNT_M = COUNT + (("bool", True),)
MAP_M = OBJ + (("empty", {}), ("none", None))            # a mapping made by another function
FRAME_M = OBJ + (("empty frame", pd.DataFrame()), ("none", None))


def _ci() -> Any:
    from fusion.book.chapters import ci

    return ci


@functools.cache
def _objects() -> dict[str, Any]:
    """Every object the valid calls read, built once and small."""
    from fusion.estimates.ci import ci_objective
    from fusion.filtering import kalman as tr
    from fusion.scenarios import two_sensor
    from test_ci_book_chapter import _arch_study, _ir_readings, _ledger_inputs, _small_readings

    ci = _ci()
    Q, R1, R2 = ci.printed_covariances()
    sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(0), runs=2, T=TS)
    sc_o = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(1), runs=2, T=TS)
    sc_an = two_sensor.two_sensor_scenario(*ci.ANISO_R, Q, np.random.default_rng(3), runs=2, T=TS)
    w = np.full(sc.t.size, 0.5)
    study = two_sensor.fusion_study(sc, w, w, published_omega=0.5)
    study_o = two_sensor.fusion_study(sc_o, w, w, published_omega=0.5)
    leg = ci.straight_leg(study, TS, 150.0)
    wp = ci.weight_pair(R1, R1 / 9, Q, 2, seed=1, search_seed=2, fruit_fly_seeds=[3], runs=2, T=TS)
    wp_an = ci.weight_pair(*ci.ANISO_R, Q, 2, seed=4, search_seed=2, fruit_fly_seeds=[3], runs=2, T=TS)
    wp_an_k3 = ci.weight_pair(*ci.ANISO_R, Q, 3, seed=4, search_seed=2, fruit_fly_seeds=[3], runs=2, T=TS)
    a, b = sc.tracks
    flat = ci_objective(np.linspace(0, 1, 11), a.gains.P[2], b.gains.P[2])
    arch = {ci.IDENTICAL_LABEL: _arch_study(0), ci.ANISO_LABEL: _arch_study(1, placement=False)}
    arch_o = {ci.IDENTICAL_LABEL: _arch_study(2, lit_feedback=60.0), ci.ANISO_LABEL: _arch_study(3, placement=False)}
    parts = _ledger_inputs(study, -1.0)
    r = ci.ledger_inputs(**parts)
    paired_in = ci.PairedInputs(**{f.name: getattr(r, f.name) for f in dataclasses.fields(ci.PairedInputs)})
    ir_in = ci.IrInputs(**{f.name: getattr(r, f.name) for f in dataclasses.fields(ci.IrInputs)})
    readings = _ir_readings()
    small = _small_readings()   # ir_readings(0.1, 1, 3, duration=3.0), shared with the synthetic readings
    sim = small.sims["x"]
    from fusion.scenarios import infrared_radar as ir
    ir_rmse = ir.rmse_by_rule(sim)
    bound = ir.many_scan_bound(sim.path, 1e-4, 0.02, 5.0)
    variants = two_sensor.rmse_variants(study.est[two_sensor.StudyMethod.SPLIT_CI], sc.truth, study.steady)
    variants_all = two_sensor.rmse_variants(study.est[two_sensor.StudyMethod.SPLIT_CI], sc.truth,
                                            np.ones(sc.t.size, dtype=bool))
    nees_st = two_sensor.nees_study(np.random.default_rng(2), Q, R1, R2, sc.truth[0], sc.t.size, 5, T=TS)
    nees_steps = {s: ci.nees_per_step(np.random.default_rng(1), Q, R1, R2, sc.truth[0], sc.t.size, 5, T=TS,
                                      random_velocity=s) for s in (False, True)}
    exact = ci.split_ci_exactness(Q, R1, TS, sc.t.size)
    # the rows path_numbers reads, each a copy of the exact row at T = 1 s (T = 0.02 s alone costs seconds)
    row = two_sensor.path_by_period([1.0], 150.0, 10.0, (two_sensor.Q_READINGS[0],))[(1.0, two_sensor.Q_READINGS[0])]
    path_rows = {(T, q): dict(row) for T in (1.0, 0.1, 0.02) for q in (two_sensor.Q_READINGS[0], two_sensor.Q_READINGS[2])}
    pcrb = ci.pcrb_table([1.0, 0.02, 0.001], 150.0, 10.0)
    bench = ci.timing_benchmark()
    F = tr.cv_model(TS).F
    return dict(Q=Q, R1=R1, R2=R2, sc=sc, sc_o=sc_o, sc_an=sc_an, w=w, study=study, study_o=study_o, leg=leg, wp=wp,
                wp_an=wp_an, wp_an_k3=wp_an_k3, flat=flat, arch=arch, arch_o=arch_o, parts=parts, r=r, paired_in=paired_in, ir_in=ir_in,
                readings=readings, small=small, sim=sim, ir_rmse=ir_rmse, bound=bound, variants=variants,
                variants_all=variants_all, nees_st=nees_st, nees_steps=nees_steps, exact=exact, path_rows=path_rows,
                pcrb=pcrb, bench=bench, F=F, a=a)


def _without(frame: pd.DataFrame, i: int = 0) -> pd.DataFrame:
    """The table without its ``i``-th column."""
    return frame.drop(columns=frame.columns[i])


def _nan_cell(frame: pd.DataFrame, col: Any = None, row: int = 0) -> pd.DataFrame:
    """The table with NaN in column ``col`` (default the first float column: one the function reads), row ``row``."""
    out = frame.copy()
    if col is None:
        col = next(c for c in out.columns if pd.api.types.is_float_dtype(out[c]))
    out.iloc[row, list(out.columns).index(col)] = np.nan
    return out


def _nan_last(arr: np.ndarray) -> np.ndarray:
    """The array with NaN in its last entry (a scan that is read; the first may be undefined)."""
    out = np.array(arr, dtype=float)
    out.flat[-1] = np.nan
    return out


def _negated(value: Any) -> Any:
    """``value`` with every float negated (a mapping's entries, a table's numeric columns, an array): an RMSE, a NEES,
    a bound, a time that cannot be negative (fuzz 24c, NEG)."""
    if isinstance(value, pd.DataFrame):
        out = value.copy()
        num = out.select_dtypes("number").columns
        out[num] = -out[num]
        return out
    if isinstance(value, dict) or hasattr(value, "items"):
        return {k: _negated(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return tuple(_negated(v) for v in value)
    if isinstance(value, (float, np.floating)) or (isinstance(value, np.ndarray) and value.dtype.kind == "f"):
        return -value
    return value


def _neg(value: Any) -> tuple[tuple[str, Any]]:
    """The mutation "negated" of a value that cannot be negative."""
    return (("negated", _negated(value)),)


def _drop_key(mapping: Any, key: Any = None) -> dict:
    """The mapping without ``key`` (default its first key): one the function reads."""
    d = dict(mapping)
    d.pop(next(iter(d)) if key is None else key)
    return d


@functools.cache
def registry() -> dict[str, dict[str, A]]:
    """Valid calls: function name -> its arguments, each with the mutations to refuse."""
    from fusion.scenarios import two_sensor

    ci = _ci()
    o = _objects()
    M = two_sensor.StudyMethod
    R: dict[str, dict[str, A]] = {}
    c = "fusion.book.chapters.ci."
    Q, R1, R2, sc, study = o["Q"], o["R1"], o["R2"], o["sc"], o["study"]
    sc_x = ("another scenario", o["sc_o"])
    study_x = ("another scenario's study", o["study_o"])
    wrong_type = ("another type", o["leg"])
    r, wp, leg = o["r"], o["wp"], o["leg"]
    p = o["parts"]   # the synthetic ledger entries (tests/test_ci_book_chapter.py)

    # ---------------------------------------------------------------- seeded studies
    R[c + "source_scenario"] = dict(seed=A(2024, SEED_M))
    R[c + "study_seed"] = dict(seed=A(2024, SEED_M), study=A("infrared + radar", OPT + (("int", 5),)))
    R[c + "claim_file"] = {}
    R[c + "ir_ratio_band"] = {}
    R[c + "margin_numbers"] = {}
    R[c + "printed_covariances"] = {}
    R[c + "timing_benchmark"] = dict(results=A(None, (("int", 5), ("unknown key", {"no-such-key": 1.0}))))
    R[c + "published_numbers"] = dict(period=A(1.0, POS), runs=A(50, COUNT_M))

    # ---------------------------------------------------------------- text
    R[c + "excess_text"] = dict(excess=A(0.5, REAL))
    # NaN and the infinities are valid: documented as "—", "∞" and "-∞" (fusion.book.tables.NONFINITE_RULE)
    R[c + "readable"] = dict(x=A(0.123, OBJ), digits=A(2, ("neg", "frac", "str", ("bool", True))))
    R[c + "paired_text"] = dict(a=A(np.linspace(1.0, 2.0, 5), ARR + ("len",)), b=A(np.linspace(1.1, 2.2, 5), ARR + ("len",)),
                                digits=A(2, ("neg", "frac", "str", ("bool", True))))
    R[c + "rule_label"] = dict(rule=A(two_sensor.NeesRule.SPLIT.value, OPT + (("int", 5),)))

    # ---------------------------------------------------------------- the tracking case
    R[c + "fig3"] = dict(sc=A(sc, OBJ + (wrong_type,)), run=A(0, ("neg", "frac", "str", ("big", 99), ("bool", True))))
    R[c + "rmse_table"] = dict(study=A(study, OBJ + (wrong_type,)), sc=A(sc, OBJ + (sc_x,)))
    R[c + "slip_table"] = dict(study=A(study, OBJ + (wrong_type,)), sc=A(sc, OBJ + (sc_x,)))
    R[c + "baseline_slip_numbers"] = dict(sc=A(sc, OBJ + (sc_x, wrong_type)), study=A(study, OBJ + (study_x,)))
    R[c + "straight_leg"] = dict(study=A(study, OBJ + (wrong_type,)), T=A(TS, POS), sigma=A(150.0, POS))
    R[c + "rmse_figure"] = dict(study=A(study, OBJ + (wrong_type,)), on_leg=A(leg.on_leg, ARR + ("len",)),
                                floor=A(leg.causal, ARR + ("len",) + _neg(leg.causal)))
    R[c + "rmse_numbers"] = dict(study=A(study, OBJ + (wrong_type,)), leg_floor=A(leg.floor, ARR + ("len",) + _neg(leg.floor)),
                                 legs_steady=A(leg.steady, ("empty", "str", "len", "more")),
                                 leg_rmse=A(leg.rmse, MAP_M + _neg(leg.rmse)),   # every entry read: a key less is valid
                                 leg_causal=A(leg.causal, ARR + ("len",) + _neg(leg.causal)))
    R[c + "weight_numbers"] = dict(sc=A(sc, OBJ + (sc_x,)), study=A(study, OBJ + (study_x,)),
                                   w_fruit_fly=A(o["w"], ARR + ("len", "above")), w_grid=A(o["w"], ARR + ("len", "above")),
                                   rng=A(np.random.default_rng(0), OBJ), steps=A((10, 20, 30), (("big", (10, 20, 10**6)), ("frac", (1.5,)), "str", ("empty", ()))),
                                   split_step=A(20, ("neg", "frac", "str", ("big", 10**6))))
    R[c + "slip_all"] = dict(study=A(study, OBJ + (wrong_type,)), names=A((M.CI, M.SPLIT_CI), (("unknown", ("no-such-method",)), "str", ("empty", ()))))
    R[c + "slip_at_weights"] = dict(sc=A(sc, OBJ + (sc_x,)), study=A(study, OBJ + (study_x,)),
                                    omegas=A((0.0018, 0.0033), (("above", (1.5,)), ("nan", (np.nan,)), "str", ("empty", ()))))
    R[c + "fuzzy_levels"] = dict(sc=A(sc, OBJ + (wrong_type,)), levels=A(np.array([0.001, 0.05]), ("nan", "inf", "empty", "more", "str", "above")),   # a scalar is one level
                                 t_steady=A(20.0, NONNEG + (("after the track", 1e6),)))
    va, vall = o["variants"], o["variants_all"]
    R[c + "variant_numbers"] = dict(variants=A(va, MAP_M + (("a key less", _drop_key(va, two_sensor.study.RUN_AVERAGED)),) + _neg(va)))
    R[c + "variants_table"] = dict(variants=A(va, MAP_M + _neg(va)), variants_all=A(vall, MAP_M + (("a key less", _drop_key(vall)),) + _neg(vall)))
    slip = ci.slip_table(study, sc)
    col_all = next(c for c in slip.columns if c.startswith("√Σe²/n, n = all"))
    in_fig6 = slip.index.get_level_values(0).str.startswith("Fig. 6")
    R[c + "slip_numbers"] = dict(variants=A(va, MAP_M + _neg(va)), variants_all=A(vall, MAP_M + _neg(vall)),
                                 slip=A(slip, FRAME_M + (("a column less", slip.drop(columns=[col_all])), ("nan cell", _nan_cell(slip, col_all)),
                                                         ("no Fig. 6 rows", slip[~in_fig6]), ("only Fig. 6 rows", slip[in_fig6])) + _neg(slip)),
                                 n_all=A(sc.t.size, COUNT_M))
    R[c + "slip_band"] = dict(variants_all=A(vall, MAP_M), n_all=A(sc.t.size, COUNT_M))
    sw = ci.slip_at_weights(sc, study)
    sa = ci.slip_all(study)
    R[c + "slip_pair_band"] = dict(slip_weights=A(sw, MAP_M), slip_all=A(sa, MAP_M), n_all=A(sc.t.size, COUNT_M))

    # ---------------------------------------------------------------- the CI weight
    R[c + "weight_pair"] = dict(R1=A(R1, ARR + ("indef",)), R2=A(R1 / 9, ARR + ("indef",)), Q=A(Q, ARR),
                                k=A(2, ("neg", "frac", "str", ("big", 10**6))), seed=A(1, SEED_M), search_seed=A(2, SEED_M),
                                fruit_fly_seeds=A([3], ("str", ("empty", []), ("neg", [-1]), ("frac", [1.5]), ("repeat", [3, 3]),
                                                                 ("huge", list(range(10**5))))),
                                runs=A(2, COUNT_M), T=A(TS, POS))
    R[c + "weight_search"] = dict(P1=A(wp.P1, ARR + ("indef", "lensq")), P2=A(wp.P2, ARR + ("indef",)),
                                  rng=A(np.random.default_rng(0), OBJ))
    R[c + "fruit_fly_table"] = dict(res=A(wp.res, MAP_M))   # every entry read: a key less is a valid table
    R[c + "weight_search_numbers"] = dict(res=A(wp.res, MAP_M), flat=A(o["flat"], ARR), fruit_fly_seeds=A(wp.fruit_fly_seeds, OBJ + (wrong_type,)),
                                          suffix=A("", (("int", 5),)), omit=A((), (("unknown", ("no-such-key",)), ("int", 5))))
    R[c + "weight_claim_inputs"] = dict(asym=A(wp, OBJ + (wrong_type, ("the anisotropic pair", o["wp_an"]))),
                                        aniso=A(o["wp_an"], OBJ + (wrong_type, ("the unequal pair", wp),
                                                                   ("searched at another step", o["wp_an_k3"]))),
                                        flat=A(o["flat"], ARR))
    m = o["bench"].measurements
    an = (o["wp_an"].P1, o["wp_an"].P2, o["wp_an"].res, o["wp_an"].fruit_fly_seeds)
    R[c + "fig5"] = dict(P1=A(wp.P1, ARR + ("indef", "lensq")), P2=A(wp.P2, ARR + ("indef",)), res=A(wp.res, MAP_M),
                         m=A(m, MAP_M + (("a key less", _drop_key(m, "foa_vectorised")),) + _neg(m)),
                         seeds=A(wp.fruit_fly_seeds, OBJ + (wrong_type,)),
                         aniso=A(an, ("str", ("three items", an[:3]), ("seeds of another type", an[:3] + (5,)))))
    R[c + "fig5_hypotheses"] = dict(P1=A(wp.P1, ARR + ("indef", "lensq")), P2=A(wp.P2, ARR + ("indef",)),
                                    fruit_fly_seeds=A(wp.fruit_fly_seeds, OBJ + (wrong_type,)), seed=A(5, SEED_M),
                                    short_budget=A(3, COUNT_M), n_open=A(3, COUNT_M + (("huge", 10**7),)),
                                    flat_pair=A((wp.P1, wp.P1), ("str", ("one", (wp.P1,)), ("indef", (wp.P1, -wp.P1)))))
    hyp = ci.fig5_hypotheses(wp.P1, wp.P2, wp.fruit_fly_seeds, 5, short_budget=3, n_open=3, flat_pair=(wp.P1, wp.P1))
    R[c + "fig5_hypothesis_numbers"] = dict(table=A(hyp, FRAME_M + (("a column less", _without(hyp)), ("nan cell", _nan_cell(hyp, "ω found", 1)))),
                                            evaluations=A(6000, COUNT_M))
    R[c + "printed_weight_facts"] = dict(scenarios=A((sc, o["sc_an"]), ("str", ("empty", ()), ("another type", (leg,)),
                                                                    ("one scenario twice", (sc, sc)),
                                                                    ("the same pair on other runs", (sc, o["sc_o"])))),
                                         k=A(2, ("neg", "frac", "str", ("big", 10**6))), seeds=A(np.arange(2), ("str", ("empty", []), ("neg", [-1]), ("frac", [1.5]))),
                                         n_grid=A(11, COUNT_M))
    printed = ci.printed_weight_facts((sc, o["sc_an"]), 2, np.arange(2), n_grid=11)
    R[c + "printed_numbers"] = dict(printed=A(printed, OBJ + (wrong_type, ("none", None))))
    R[c + "split_fruit_fly_gap"] = dict(sc=A(sc, OBJ + (wrong_type,)), k=A(2, ("neg", "frac", "str", ("big", 10**6))),
                                        rng=A(np.random.default_rng(0), OBJ))
    R[c + "fruit_fly_step_study"] = dict(seeds=A(2, COUNT_M), target=A(0.8, UNIT), seed=A(0, SEED_M))
    R[c + "fruit_fly_step_targets"] = dict(seed=A(0, SEED_M), targets=A((0.5,), (("above", (1.5,)), ("nan", (np.nan,)), "str", ("empty", ()),
                                                                          ("repeat", (0.5, 0.5)))),
                                           seeds=A(2, COUNT_M))
    ffs = p["fruit_fly_step_study"]   # fruit_fly_step_study(seeds=3) of the synthetic ledger entries
    R[c + "fruit_fly_step_values"] = dict(table=A(ffs, FRAME_M + (("a column less", _without(ffs)), ("nan cell", _nan_cell(ffs)))))
    R[c + "timing_table"] = dict(m=A(m, MAP_M + (("a key less", _drop_key(m)),) + _neg(m)))
    R[c + "timing_numbers"] = dict(bench=A(o["bench"], OBJ + (wrong_type, ("none", None))))

    # ---------------------------------------------------------------- bounds and the path
    R[c + "pcrb_table"] = dict(periods=A([1.0, 0.1], ARR + ("neg",)), sigma=A(150.0, POS), delta0=A(10.0, POS))
    R[c + "pcrb_numbers"] = dict(pcrb=A(o["pcrb"], FRAME_M + (("a column less", _without(o["pcrb"])),
                                                              ("a row twice", pd.concat([o["pcrb"], o["pcrb"].iloc[:1]]))) + _neg(o["pcrb"])),
                                 q_printed=A(two_sensor.Q_READINGS[0], OPT + (("int", 5),)))
    R[c + "path_noise_limit"] = dict(sigma=A(150.0, POS), delta0=A(10.0, POS))
    rows = o["path_rows"]
    R[c + "path_numbers"] = dict(rows=A(rows, MAP_M + (("a key less", _drop_key(rows)),) + _neg(rows)))
    R[c + "path_period_table"] = dict(rows=A(rows, MAP_M + _neg(rows)))

    # ---------------------------------------------------------------- consistency
    nees = o["nees_st"].mean_nees
    est = o["nees_st"].est
    R[c + "nees_table"] = dict(nees=A(nees, MAP_M + _neg(nees)))   # every entry read: a key less is a valid table
    R[c + "nees_numbers"] = dict(nees=A(nees, MAP_M + _neg(nees)), nees_runs=A(5, COUNT_M))
    R[c + "nees_band"] = dict(runs=A(5, COUNT_M), n=A(4, COUNT_M))
    R[c + "nees_step_band"] = dict(runs=A(5, COUNT_M), n=A(4, COUNT_M))
    R[c + "model_rmse"] = dict(nees_est=A(est, MAP_M + (("a key less", _drop_key(est, "truth")),)),
                               steady=A(o["study"].steady, ("empty", "str", "len", ("none selected", np.zeros(sc.t.size, bool)))),
                               rule=A(two_sensor.NeesRule.SPLIT, OPT + (("int", 5),)))
    R[c + "nees_per_step"] = dict(rng=A(np.random.default_rng(1), OBJ), Q=A(Q, ARR + ("indef",)), R1=A(R1, ARR + ("indef",)),
                                  R2=A(R2, ARR + ("indef",)), x_start=A(sc.truth[0], ARR + ("len",)),
                                  n_steps=A(sc.t.size, COUNT_M), runs=A(5, COUNT_M), T=A(TS, POS),
                                  velocity_sigma=A(100.0, NONNEG), random_velocity=A(False, (("int", 1), "str")))
    st, exact = o["nees_steps"], o["exact"]
    st_short = {k: v[:5] for k, v in st[True].items()}
    swap_t, swap_r = (("the random start (swapped)", st[True]),), (("the true start (swapped)", st[False]),)
    R[c + "nees_start_table"] = dict(true_start=A(st[False], MAP_M + (("a key less", _drop_key(st[False])),) + _neg(st[False])
                                                  + swap_t),
                                     random_start=A(st[True], MAP_M + (("fewer steps", st_short),) + swap_r),
                                     runs=A(5, COUNT_M), T=A(TS, POS), t_steady=A(20.0, NONNEG + (("after the track", 1e6),)))
    R[c + "nees_start_numbers"] = dict(true_start=A(st[False], MAP_M + _neg(st[False]) + swap_t),
                                       random_start=A(st[True], MAP_M + (("fewer steps", st_short),) + swap_r),
                                       runs=A(5, COUNT_M), exact=A(exact, MAP_M + (("a key less", _drop_key(exact)),) + _neg(exact)),
                                       T=A(TS, POS), t_steady=A(20.0, NONNEG + (("after the track", 1e6),)))
    R[c + "split_ci_exactness"] = dict(Q=A(Q, ARR + ("indef",)), R=A(R1, ARR + ("indef",)), T=A(TS, POS),
                                       n_steps=A(sc.t.size, COUNT_M + (("one step", 1),)), velocity_sigma=A(100.0, NONNEG),
                                       t_steady=A(20.0, NONNEG + (("after the track", 1e6),)))
    R[c + "ml_vs_product"] = dict(x1=A(np.array([1.0, 2.0]), ARR + ("len",)), P1=A(np.array([[2.0, 0.3], [0.3, 1.0]]), ARR + ("indef", "lensq")),
                                  x2=A(np.array([0.5, 1.0]), ARR), P2=A(np.array([[1.0, -0.2], [-0.2, 3.0]]), ARR + ("indef",)))

    # ---------------------------------------------------------------- the printed equations
    Pi = np.eye(4) * 100.0 + o["a"].gains.P[2]
    R[c + "printed_equation_checks"] = dict(P1=A(wp.P1, ARR + ("indef", "lensq")), P2=A(wp.P2, ARR + ("indef",)),
                                            Pi=A(Pi, ARR + ("lensq",)), F=A(o["F"], ARR + ("lensq",)),
                                            x=A((1000.0, 20.0, 5000.0, 40.0), ARR + ("len",)))
    eqs = ci.printed_equation_checks(wp.P1, wp.P2, Pi, o["F"])
    R[c + "printed_equation_numbers"] = dict(checks=A(eqs, MAP_M + (("a key less", _drop_key(eqs)),) + _neg(eqs)))

    # ---------------------------------------------------------------- architecture
    arch, arch_o = o["arch"], o["arch_o"]
    table = ci.architecture_table(arch)
    R[c + "architecture_table"] = dict(studies=A(arch, MAP_M + (("another type", {"x": leg}),)))
    R[c + "architecture_figure"] = dict(studies=A(arch, MAP_M + (("another type", {"x": leg}),)))
    ai_an = list(arch.values())
    R[c + "architecture_numbers"] = dict(arch=A(arch, MAP_M + (("one study", dict(list(arch.items())[:1])),
                                                               ("studies swapped", dict(zip(arch, ai_an[::-1]))),
                                                               ("one study twice", dict(zip(arch, ai_an[:1] * 2))))),
                                         arch_table=A(table, FRAME_M + (("another study's table", ci.architecture_table(arch_o)),
                                                                        ("a column less", _without(table)))),
                                         arch_runs=A(100, COUNT_M + (("other runs", 50),)),
                                         k_steady=A(241, COUNT_M + (("big", 10**6),)))
    key = next(iter(arch[ci.IDENTICAL_LABEL].run_rmse))
    R[c + "architecture_row"] = dict(key=A(key, ("str", ("unknown", ("no-such", "arch")), ("none", None))))
    ai = arch[ci.IDENTICAL_LABEL]
    qs = r.q_scaling
    ai_x = ("the other pair's study", arch[ci.ANISO_LABEL])   # other runs: qs is drawn on the runs of ai
    R[c + "q_scaling_table"] = dict(qs=A(qs, OBJ + (wrong_type, ("none", None))), ai=A(ai, OBJ + (wrong_type, ai_x)))
    R[c + "q_numbers"] = dict(qs=A(qs, OBJ + (wrong_type, ("none", None))), ai=A(ai, OBJ + (wrong_type, ai_x)))
    R[c + "architecture_studies"] = dict(R1=A(R1, ARR + ("indef",)), R2=A(R2, ARR + ("indef",)), Q=A(Q, ARR),
                                         seeds=A((1, 2), ("str", ("empty", ()), ("neg", (-1, 2)), ("frac", (1.5, 2)))),
                                         w_pub=A(0.0018, UNIT), runs=A(2, COUNT_M), nees_runs=A(2, COUNT_M), T=A(8.0, POS),
                                         fixed_omegas=A((0.5,), (("above", (1.5,)), "str", ("nan", (np.nan,)), ("repeats w_pub", (0.0018,)))))

    # ---------------------------------------------------------------- paired studies
    R[c + "paired_numbers"] = dict(paired=A(p["paired"], MAP_M + (("a key less", _drop_key(p["paired"])),) + _neg(p["paired"])),
                                   paired_u=A(p["paired_unequal"], MAP_M), paired_random=A(p["paired_random"], ARR + ("len",)),
                                   ai=A(ai, OBJ + (wrong_type, ai_x)), ml_gap=A(1e-13, NONNEG), rmse_avg=A(50.0, POS),
                                   paired_runs=A(100, COUNT_M + (("other runs", 50),)),
                                   paired_a=A(p["paired_aniso"], MAP_M), omega_u=A(np.full(5, 0.3), ARR + ("above",)),
                                   paired_fig6=A(p["paired_fig6"], MAP_M[:2] + _neg(p["paired_fig6"])))
    R[c + "paired_studies"] = dict(R1=A(R1, ARR + ("indef",)), R2=A(R2, ARR + ("indef",)), Q=A(Q, ARR),
                                   weights=A((o["w"], o["w"]), ("str", ("len", (o["w"][:-1], o["w"][:-1])))),
                                   unequal=A(wp, OBJ + (wrong_type, ("the anisotropic pair", o["wp_an"]))),
                                   aniso=A(o["wp_an"], OBJ + (wrong_type, ("the unequal pair", wp))),
                                   runs=A(2, COUNT_M), seeds=A((1, 2, 3), ("str", ("empty", ()), ("neg", (-1, 2, 3)))),
                                   weight_seed=A(4, SEED_M), fig6_omegas=A((0.0018, 0.0033), (("above", (1.5,)), "str")),
                                   T=A(TS, POS))

    # ---------------------------------------------------------------- infrared + radar
    rd, small, sim = o["readings"], o["small"], o["sim"]
    rd_x = ("another type", leg)
    R[c + "ir_bound_table"] = dict(readings=A(rd, OBJ + (rd_x, ("none", None))))
    R[c + "ir_paired"] = dict(readings=A(rd, OBJ + (rd_x,)))
    R[c + "ir_ratio_table"] = dict(readings=A(rd, OBJ + (rd_x,)))
    R[c + "ir_sigma_band"] = dict(readings=A(rd, OBJ + (rd_x,)), scan=A(tuple(sorted(rd.sigma_rms)), (("nan", (np.nan,)), ("neg", (-1.0,)), "str")))   # empty: documented (NaN, NaN)
    R[c + "ir_sigma_rms"] = dict(readings=A(rd, OBJ + (rd_x,)), sigma_acc=A(next(iter(rd.sigma_rms)), POS))   # any positive σa is a reading
    run_rmse = next(iter(rd.run_rmse.values()))[ci.IR_IMP]
    R[c + "ir_ratio"] = dict(run_rmse=A(run_rmse, ARR + ("lencol",)), seed=A(1, SEED_M))
    R[c + "ir_rms"] = dict(run_rmse=A(run_rmse, ARR + ("lencol",)))
    R[c + "ir_readings"] = dict(T=A(0.1, POS), seed=A(1, SEED_M), runs=A(2, COUNT_M), duration=A(2.0, POS),
                                t_min=A(0.0, ("neg", "nan_s", "str", ("after the track", 5.0))),
                                scaled_axes=A(("x",), (("unknown", ("no-such",)), "str")))   # () is valid: no axis scaled
    R[c + "ir_study"] = dict(T=A(0.1, POS), seed=A(1, SEED_M), runs=A(3, COUNT_M), duration=A(3.0, POS),
                             azimuth_from=A("x", OPT + (("int", 5),)))
    ir_rmse = o["ir_rmse"]
    R[c + "ir_table"] = dict(rmse=A(ir_rmse, MAP_M + _neg(ir_rmse)), t=A(sim.t, ARR + ("len", ("reversed", sim.t[::-1].copy()))),   # every entry read: a key less is a valid table
                             t_min=A(1.0, ("neg", "nan_s", "str", ("after the track", 99.0))))
    ir_tab = ci.ir_table(ir_rmse, sim.t, 1.0)
    R[c + "ir_numbers"] = dict(ir_table=A(ir_tab, FRAME_M + (("a column less", _without(ir_tab)), ("nan cell", _nan_cell(ir_tab))) + _neg(ir_tab)),
                               t_ir=A(0.1, POS), duration=A(3.0, POS))
    R[c + "ir_figure"] = dict(t=A(sim.t, ARR + ("len", ("reversed", sim.t[::-1].copy()))), rmse=A(ir_rmse, MAP_M + (("a key less", _drop_key(ir_rmse, ci.IR_SHOWN[0])),) + _neg(ir_rmse)),
                              bound=A(o["bound"], ("inf", "empty", "more", "less", "str", "len", ("nan drawn", _nan_last(o["bound"]))) + _neg(o["bound"])),
                              t_min=A(1.0, ("neg", "nan_s", "str", ("after the track", 99.0))))
    R[c + "fig11"] = dict(sim=A(sim, OBJ + (wrong_type,)), run=A(0, ("neg", "frac", "str", ("big", 99), ("bool", True))),
                          t_min=A(1.0, ("neg", "nan_s", "str", ("after the track", 99.0))))
    R[c + "ir_reading_numbers"] = dict(readings=A(small, OBJ + (rd_x,)), sim=A(sim, OBJ + (wrong_type, ("another simulation", o["small"].sims.get("y", sim)))),
                                       rmse=A(ir_rmse, MAP_M))
    means = {k: float(v) for k, v in next(iter(r.ir_means.values())).items()}
    R[c + "ir_flown_numbers"] = dict(seed=A(1, SEED_M), runs=A(3, COUNT_M), chapter_means=A(means, MAP_M + (("a key less", _drop_key(means)),)),
                                     distance=A(1000.0, POS), t_min=A(2.0, ("neg", "nan_s", "str")))
    R[c + "sensitivity_table"] = dict(periods=A((0.1, 0.5), ("str", ("empty", ()), ("neg", (-1.0,)), ("nan", (np.nan,)))), seed=A(1, SEED_M),
                                      runs=A(2, COUNT_M), duration=A(3.0, POS), t_min=A(1.0, ("neg", "nan_s", "str", ("after the track", 99.0))),
                                      known=A({0.1: means}, ("str", ("a list", [(0.1, means)]), ("a period not a number", {"a": means}),
                                                             ("a NaN period", {np.nan: means}), ("means not a mapping", {0.1: None}),
                                                             ("a mean less", {0.1: _drop_key(means, "azimuth (mrad)")}),
                                                             ("a NaN mean", {0.1: {k: np.nan for k in means}})) + _neg({0.1: means})))
    sens_table, _ = ci.sensitivity_table((0.1, 0.5), 1, 2, duration=3.0, t_min=1.0)
    R[c + "sensitivity_numbers"] = dict(sens_table=A(sens_table, FRAME_M + (("a column less", _without(sens_table)), ("nan cell", _nan_cell(sens_table, "azimuth (mrad)"))) + _neg(sens_table)))

    # ---------------------------------------------------------------- the ledger
    ledger_x = (("another type", leg), ("none", None), ("paired inputs", o["paired_in"]))
    for name in ("ev_equations", "ev_fig4_fig7", "ev_fig5", "ev_fig8", "ev_foa_step", "ev_headline", "ev_ir_values",
                 "ev_misc", "ev_times", "evidence", "ledger_values"):
        R[c + name] = dict(r=A(r, OBJ + ledger_x))
    R[c + "ev_fig6"] = dict(r=A(o["paired_in"], OBJ + (("another type", leg), ("none", None), ("IR inputs", o["ir_in"]))))
    R[c + "ev_ir_baselines"] = dict(r=A(o["ir_in"], OBJ + (("another type", leg), ("none", None), ("paired inputs", o["paired_in"]))))
    values = ci.ledger_values(r)
    edited = {**values, "ci_lg_leg_best": values["ci_lg_leg_best"] + 1.0}   # a value r does not give
    R[c + "ledger"] = dict(r=A(r, OBJ + ledger_x), values=A(values, MAP_M + (("a key less", _drop_key(values)),
                                                                             ("a value edited", edited))))
    # every entry refuses None (a string too where a study, mapping or count is read; bench_date is text)
    R[c + "ledger_inputs"] = {k: A(v, (("none", None),) + (OBJ if k in ("study", "arch", "paired", "ir_readings", "bench")
                                                         else ())) for k, v in p.items()}
    R[c + "ledger_inputs"]["nees_runs"] = A(p["nees_runs"], COUNT_M + (("none", None),))
    R[c + "ledger_inputs"]["arch"] = A(p["arch"], (("none", None),) + OBJ + (("studies swapped", p["arch"][::-1]),
                                                                            ("one study twice", p["arch"][:1] * 2)))
    for k, other in (("fruit_fly_step_study", "fruit_fly_step_targets"), ("fruit_fly_step_targets", "fruit_fly_step_study")):
        R[c + "ledger_inputs"][k] = A(p[k], (("none", None), (f"the {other} table", p[other])))
    return R


#: Functions whose sweep still finds unrefused bad input: a strict xfail each, with the reason.
PENDING: dict[str, str] = {}

test_registry_covers_the_group, test_bad_input_is_refused = group_tests(CALLABLES, registry, EXCLUDED, PENDING)
