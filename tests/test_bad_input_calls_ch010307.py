"""Every public function of chapters 01, 03 and 07 refuses bad input by name (issue 35).

One valid call of each public function of the optimal-fusion-set chapter (``ofs``, ``ofs_audit``, ``ofs_fair``), the
wavelet lecture (``lecture_wavelets``) and the time-registration chapter (``time_registration``,
``time_registration_ledger``), with the mutations each argument must refuse, swept by the main registry's
:func:`refusal_problems`: every mutated call raises ValueError or TypeError naming the argument. Arguments are
mutated by their documented meaning: numbers by range, arrays by the array kinds, keys, methods and readings by an
unknown value, results by a result of another type of the group (or None), tables by a table without a column or
with a NaN cell, mappings by a mapping without a key the function reads. Objects are built once, small.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import json
import sys
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))
from test_bad_input import (A, ARR, BATCH, COUNT, NONNEG, OBJ, POS, REAL, UNIT,  # noqa: E402
                            group_tests, public_callables)

PREFIXES = ("fusion.book.chapters.ofs.", "fusion.book.chapters.ofs_audit.", "fusion.book.chapters.ofs_fair.",
            "fusion.book.chapters.lecture_wavelets.", "fusion.book.chapters.time_registration.",
            "fusion.book.chapters.time_registration_ledger.")

CALLABLES = {k: f for k, f in public_callables().items() if k.startswith(PREFIXES) and not inspect.isclass(f)}



def _corrections_listed(**kwargs: Any) -> Any:
    """:func:`~fusion.book.chapters.ofs_audit.corrections` without its first entry, "no correction", whose value is NaN
    by its documentation (the sweep asks a finite valid result; the refusals are the function's own)."""
    from fusion.book.chapters import ofs_audit

    return ofs_audit.corrections(**kwargs)[1:]


#: The callable swept for each function: the function itself, or the view of its result without a documented NaN.
SWEPT = {**CALLABLES, "fusion.book.chapters.ofs_audit.corrections": _corrections_listed}

#: function -> why it has no entry (none: every function of the group has a valid call cheap enough to sweep).
EXCLUDED: dict[str, str] = {}

SEED = ("neg", "frac", "str", ("bool", True))          # a seed: an int >= 0
RUNS = COUNT + (("bool", True),)                       # a count: an int >= 1, not a bool
#: a run count that sets the draws: beyond the memory or work budget, refused by the caller's name before any draw
#: (fuzz 26d D3, W4, DB6: the callee's n_runs named, 7.45 GiB drawn, or minutes run)
RUNS_DRAWN = RUNS + (("beyond the budgets", 10**6),)
NONE = ("None", None)
KEY = ("unknown",) + OBJ                              # a key, method, reading or option: a string of a known set


def res(*others: Any) -> tuple:
    """Mutations of a result argument: a string, None, and results of other types (each an explicit pair)."""
    return OBJ + (NONE,) + tuple((f"other {type(o).__name__}", o) for o in others)


def frame(df: pd.DataFrame, col: Any = None, nan_at: tuple[Any, Any] | None = None) -> tuple:
    """Mutations of a table: a string, None, empty, the table without a column it reads (``col``, default its first)
    and with a missing cell where it reads one (``nan_at`` = (row, column), default the first row of ``col``); its
    first row twice and the column ``col`` twice (fuzz 24d T: counted twice, or numpy's errors from inside)."""
    col = df.columns[0] if col is None else col
    row, ncol = (df.index[0], col) if nan_at is None else nan_at
    nan = df.copy()
    j = nan.columns.get_loc(ncol)
    if not pd.api.types.is_float_dtype(nan.iloc[:, j]):
        nan[ncol] = nan[ncol].astype(object)
    nan.iat[nan.index.get_loc(row), j] = np.nan
    return OBJ + (NONE, ("no column", df.drop(columns=[col])), ("empty", df.iloc[:0]),
                  ("row twice", pd.concat([df.iloc[:1], df])), ("column twice", pd.concat([df, df[[col]]], axis=1)),
                  ("nan cell", nan))  # the NaN cell last: entries take it as frame(...)[-1]


def mapping(m: dict, key: Any = None) -> tuple:
    """Mutations of a mapping: a string, None, the mapping without a key (``key``, default its first), empty."""
    key = next(iter(m)) if key is None else key
    return OBJ + (NONE, ("no key", {k: v for k, v in m.items() if k != key}), ("empty", {}))


# --------------------------------------------------------------------------------------------------------------
# objects, built once at the smallest valid size
# --------------------------------------------------------------------------------------------------------------


@functools.cache
def O() -> dict[str, Any]:  # noqa: N802 - the objects
    from fusion.book.chapters import ofs, ofs_audit as oa, ofs_fair as of
    from fusion.book.chapters import time_registration as tr, time_registration_ledger as trl
    from fusion.book.chapters.lecture_wavelets import appendix as wa, records as lwr
    from fusion.book.claims import claims_dir, load as load_claims
    from fusion.book.ledger import Comparison, Ledger
    from fusion.scenarios import thermocouples
    from fusion.scenarios import time_registration as sc

    o: dict[str, Any] = {}
    a = np.arange(100.0) + 1
    o["cmp"] = Comparison(a, a + 1, "A", "B", "less", "m")
    o["hs"], o["eq"] = ofs.study(0, 2), ofs.study(1, 2, "equal")
    o["ws"] = ofs.weight_study(0, 2)
    o["ms"] = ofs.membership_study(0, 2)
    o["tabs"] = ofs.tables()
    o["joint"] = ofs.joint()
    o["fair"] = of.fair_study(0, 100, 2, sizes=(0, 1), counts=(0, 1), spreads=(1, 2), opposite=())  # R4: 100 runs
    o["ledger"] = Ledger("yang2012optimal")
    o["ledger_tr"] = Ledger("shi2023time")
    o["t1"] = ofs.corrected_table1()
    o["corr"] = oa.corrections()[0]
    z = thermocouples.simulate(np.random.default_rng(0), n_samples=20)
    o["z"] = z
    o["z3"] = 900 + np.random.default_rng(0).normal(size=(3, 20, 5))
    o["err"] = thermocouples.absolute_errors(z, ofs.METHODS)
    o["judged"] = {("yang-fig4-unaffected", "equal-noise"): o["cmp"], ("yang-weights-reasonable", "primary"): o["cmp"],
                   ("yang-weights-reasonable", "failure"): o["cmp"], ("yang-membership-free", "scale"): o["cmp"]}
    o["sig"] = {"hs": thermocouples.DEFAULT_SIGMAS, "eq": 1.0}
    o["studies"] = {"hs": o["hs"], "eq": o["eq"]}
    o["mc"] = ofs.mc_table(o["studies"], o["sig"])
    o["mc_swapped"] = ofs.mc_table({"hs": o["eq"], "eq": o["hs"]},   # the studies (and their SDs) under each other's label
                                   {"hs": o["sig"]["eq"], "eq": o["sig"]["hs"]})
    o["fair_few"] = of.fair_study(0, 2, 2, sizes=(0, 1), counts=(0, 1), spreads=(1, 2), opposite=())
    o["shapes"], o["shapes_few"] = of.fault_shapes_study(0, 100), of.fault_shapes_study(0, 3)  # R4: 100 runs
    for k in lwr.STUDIES:  # each study at fewer runs than rule R4's 100
        o[f"{k}_few"] = lwr.study(k, 2601, 3)
    cf = load_claims(claims_dir() / "yang2012optimal.yaml")
    # the headline record and one table record: the evidence of every record at 100 runs costs a CPU-second
    o["claims"] = dataclasses.replace(cf, records=tuple(r for r in cf.records
                                                        if r.id in ("yang-fig4-vs-mean", "yang-table2-ofs")))
    o["claims_tr"] = load_claims(claims_dir() / "shi2023time.yaml")
    o["ledger_json"] = json.loads((Path(__file__).parents[1] / "book" / "ledger" / "yang2012optimal.json")
                                  .read_text(encoding="utf-8"))
    # chapter 03
    for k in lwr.STUDIES:
        o[k] = lwr.study(k, 2601, 100)  # rule R4: the glue compares 100 runs
    o["len64"] = wa.length_study(64, runs=100)
    o["len1024"] = wa.length_study(1024, runs=100)
    o["len128"] = wa.length_study(128, runs=100)
    o["len64_few"] = wa.length_study(64, runs=3)
    from fusion.scenarios import wavelet_sensors as ws  # studies of three sensors (valid; no sensor 4: fuzz 26d A10)

    three = dict(gains=(1.0, 1.5, 0.8), sigma=(0.05, 0.1, 0.2))
    o["m3"], o["v3"] = ws.mechanism_study(runs=100, **three), ws.variance_study(runs=100, **three)
    # chapter 07
    o["T1"], o["T2"] = sc.instants()
    o["mc7"] = sc.monte_carlo(list(sc.METHODS), 1.0, 4, 0)
    o["mc7_4"] = sc.monte_carlo([m.value for m in sc.RegMethod][:4], 1.0, 4, 0)
    o["exact"] = {n: sc.expected(n, 1.0) for n in sc.METHODS}
    o["closed"] = tr.closed_form_table(1.0, 1.0)
    o["crossings"] = tr.crossing_table(o["closed"])
    o["st7"] = trl.cached_study(0, 100)  # the runs ledger_evidence's valid call asks (R4): computed once
    o["bench"] = tr.benchmark_table(o["mc7"], o["exact"])
    return o


@functools.cache
def registry() -> dict[str, dict[str, A]]:  # noqa: C901 - one entry per function
    """Function name -> its valid call, argument -> A(value, mutations)."""
    from fusion.book.chapters import ofs, ofs_audit as oa, ofs_fair as of
    from fusion.book.chapters import time_registration as tr, time_registration_ledger as trl
    from fusion.book.chapters.lecture_wavelets import (appendix as wa, e26, mechanism as mech, records as lwr,
                                                        signals, variance, verdicts)
    from fusion.book.ledger import Conjunction
    from fusion.scenarios import time_registration as sc
    from fusion.scenarios.time_registration import RegMethod
    from fusion.scenarios.wavelet_sensors import Signal

    o = O()
    r: dict[str, dict[str, A]] = {}

    def add(fn: Any, **spec: A) -> None:
        r[f"{fn.__module__}.{fn.__qualname__}"] = spec

    # ---------------------------------------------------------------- chapter 01: ofs
    T1 = o["t1"]
    NO_LESS = ("nan", "inf", "empty", "more", "str")  # arrays whose one-lower shape is documented as one item
    add(ofs.alpha_key, alpha=A(0.25, POS))
    add(ofs.alpha_methods, alphas=A((0.1, 1.0), ARR + (("repeated", (1.0, 1.0)),)))
    add(ofs.alpha_study, seed=A(0, SEED), runs=A(2, RUNS_DRAWN))
    add(ofs.claim_values, seed=A(0, SEED), runs=A(100, RUNS_DRAWN))
    # the two studies swapped are refused by the noise levels a PairedStudy records (issue 35, swaps)
    add(ofs.closing_numbers, study_hs=A(o["hs"], res(o["ws"]) + (("swapped", o["eq"]),)),
        study_eq=A(o["eq"], res(o["ws"]) + (("swapped", o["hs"]),)),
        weights=A(o["ws"], res(o["hs"])), judged=A(o["judged"], mapping(o["judged"])), relative_margin=A(0.05, UNIT))
    add(ofs.comparison_numbers, comparison=A(o["cmp"], res(o["hs"])), key=A("k", (("notstr", 3.0),)),
        fields=A(("a", "b"), (("unknown field", ("nope",)), ("notstr", (3.0,)))))
    add(ofs.corrected_table1)
    add(ofs.eq9_readings, z=A(o["z"], ARR), weight_epochs=A(10, RUNS))
    add(ofs.evidence, seed=A(0, SEED), runs=A(100, RUNS_DRAWN),
        claims=A(o["claims"], OBJ + (("other source", o["claims_tr"]), ("other type", o["ledger"]))))
    add(ofs.fair, seed=A(0, SEED), runs=A(2, RUNS_DRAWN))
    add(ofs.fair_weights, seed=A(0, SEED), runs=A(2, RUNS_DRAWN))
    add(ofs.family_mae, z=A(o["z3"], ARR), families=A({"x": "laplace"}, mapping({"x": "laplace"})
                                                       + (("unknown family", {"x": "nope"}),)),
        scale=A(2.0, POS), window=A((5, 15), OBJ + (("reversed", (15, 5)), ("beyond", (5, 99)))), truth=A(900.0, REAL))
    # one epoch, shape (n_sensors,), is valid (documented): no "less"
    add(ofs.family_values, z=A(o["z3"][0], NO_LESS), family=A("gauss", KEY), scale=A(2.0, POS))
    add(ofs.faulty_member_share, seed=A(0, SEED), runs=A(2, RUNS_DRAWN), noise=A("equal", KEY), failure=A("fixed", KEY))
    add(ofs.figure_errors,
        errors=A(o["err"], OBJ + (NONE, ("empty", {}), ("unknown key", {"nope": [1.0, 2.0]}),
        ("2-D", {"mean": [[1.0, 1.0]]}))))
    add(ofs.figure_mc, table=A(o["mc"], frame(o["mc"])))
    add(ofs.figure_readings, readings=A(o["z"], ARR), highlight=A((1, 2), (("beyond", (99,)), ("str", "abc"))),
        window=A((5, 15), OBJ + (("reversed", (15, 5)), ("beyond", (5, 99)))), truth=A(900.0, REAL))
    add(ofs.figure_scale, scales=A(np.array([1.0, 2.0]), ARR), sweep=A({"a": np.array([1.0, 2.0])},
                                                                        mapping({"a": 1}) + (("short", {"a": [1.0]}),)),
        default=A(2.0, POS))
    add(ofs.healthy_dropped_share, seed=A(0, SEED), runs=A(2, RUNS_DRAWN), noise=A("equal", KEY))
    add(ofs.joint)
    add(ofs.ledger_numbers, ledger=A(o["ledger"], res(o["hs"]) + (("other source", o["ledger_tr"]),)),
        prefix=A("ofs_", (("notstr", 3.0),)),
        fields=A(None, (("str", "abc"), ("unknown record", {"nope": ("status",)}))))
    add(ofs.mc_numbers, mc=A(o["mc"], frame(o["mc"]) + (("other studies' table", o["mc_swapped"]),)),
        studies=A(o["studies"], mapping(o["studies"])),
        sigmas=A(o["sig"], mapping(o["sig"])), n_runs=A(2, RUNS + (("other", 3),)))
    add(ofs.mc_table,
        studies=A(o["studies"], mapping(o["studies"]) + (("other type", {"hs": o["ws"], "eq": o["eq"]}),)),
        sigmas=A(o["sig"], mapping(o["sig"]) + (("negative", {"hs": -o["sig"]["hs"], "eq": 1.0}),
                                                ("the SDs swapped", {"hs": o["sig"]["eq"], "eq": o["sig"]["hs"]}))))
    add(ofs.membership_study, seed=A(0, SEED), runs=A(2, RUNS_DRAWN))
    add(ofs.not_neighbourhood_share, seed=A(0, SEED), runs=A(2, RUNS_DRAWN), noise=A("equal", KEY))
    add(ofs.observation_numbers, tabs=A(o["tabs"], res(o["joint"])))
    add(ofs.reproduce_tables, alpha_range=A((1e-3, 1e2), ARR + (("reversed", (1e2, 1e-3)), ("negative", (-1.0, 1.0)))))
    add(ofs.study, seed=A(0, SEED), runs=A(2, RUNS_DRAWN), noise=A("equal", KEY), failure=A("fixed", KEY),
        include_self=A(True, OBJ + (("int", 1),)))
    add(ofs.support_bound_check, seed=A(0, SEED), n=A(1000, RUNS), alpha=A(0.25, POS))
    add(ofs.support_table)
    # a scalar is one scale (documented): no "less"
    add(ofs.table1_by_scale, scales=A(np.array([1.0, 2.0]), NO_LESS + (("zero", np.array([0.0, 1.0])),)))
    add(ofs.table1_totals, t1=A(T1, ARR), alpha=A(0.25, POS), guard=A(False, OBJ + (("int", 1),)),
        rule=A("averages", KEY))
    add(ofs.table_numbers, tabs=A(o["tabs"], res(o["joint"])))
    add(ofs.tables)
    add(ofs.unit_dependence, z=A(o["z"], ARR))
    add(ofs.verdict_table, ledger=A(o["ledger"], res(o["hs"]) + (("other source", o["ledger_tr"]),)))
    add(ofs.weight_ablation, z=A(o["z3"], ARR), window=A((5, 15), OBJ + (("reversed", (15, 5)), ("beyond", (5, 99)))),
        truth=A(900.0, REAL))
    add(ofs.weight_study, seed=A(0, SEED), runs=A(2, RUNS_DRAWN), include_self=A(True, OBJ + (("int", 1),)))

    # ---------------------------------------------------------------- chapter 01: ofs_audit
    order = np.arange(6)
    add(oa.corrections, t1=A(T1, ARR), window=A(20.0, POS), slips_only=A(False, OBJ + (("int", 1),)))
    add(oa.describe, c=A(o["corr"], res(o["joint"])))
    add(oa.explain, correction=A(o["corr"], res(o["joint"])), program=A("correct", KEY),
        rule=A("averages, d_i < d̄ (the text)", KEY),
        order=A(order, ARR + (("float", order + 0.5), ("short", order[:3]))), truth=A(900.0, REAL))
    add(oa.explanation_numbers, joint=A(o["joint"], res(o["tabs"])))
    add(oa.full_explanation, result=A(o["joint"], res(o["tabs"])))
    add(oa.joint_audit, window=A(1.0, POS), order_search=A("mean-consistent", KEY))
    add(oa.published_values)
    add(oa.run_program, t1=A(T1.T, ARR), program=A("correct", KEY), rule=A("averages, d_i < d̄ (the text)", KEY),
        order=A(order, ARR + (("float", order + 0.5), ("short", order[:3]))))
    mean, ofs_ = T1.mean(axis=0)[None], np.median(T1, axis=0)[None]
    # shape (n_obs,) is one hypothesis (documented): no "less"
    add(oa.score, mean=A(mean, NO_LESS + (("len", mean[:, :-1]),)), ofs=A(ofs_, NO_LESS + (("len", ofs_[:, :-1]),)),
        truth=A(900.0, REAL))
    # s and x have any leading axes (documented shape (..., n)): no "more" nor "less"
    add(oa.set_members, s=A(T1.T, ("nan", "inf", "empty", "str", ("one reading", T1.T[:, :1]))),
        rule=A("averages, d_i < d̄ (the text)", KEY))
    add(oa.summary, result=A(o["joint"], res(o["tabs"])))
    add(oa.support_values, t1=A(T1.T, ARR), kernel=A("Gaussian exp(-α d²)", KEY), aggregation=A("row sums", KEY),
        alphas=A(np.array([0.1, 1.0]), ARR))
    add(oa.support_variants, alphas=A(np.array([0.1, 1.0]), ARR))
    add(oa.three_reading_set, x=A(T1.T, ("nan", "inf", "empty", "str", ("two readings", T1.T[:, :2]))))

    # ---------------------------------------------------------------- chapter 01: ofs_fair
    add(of.fair_errors, z=A(o["z3"], ARR), sigma=A(np.ones(5), ARR + (("len", np.ones(4)), ("negative", -np.ones(5)))),
        truth=A(900.0, REAL),
        methods=A(("mean", "median"), OBJ + (("unknown", ("nope",)), ("repeated", ("mean", "mean")),
                                                                     ("empty", ()))))
    add(of.fair_numbers, study=A(o["fair"], res(o["hs"]) + (("few runs", o["fair_few"]),)))
    add(of.fair_study, seed=A(0, SEED), n_runs=A(2, RUNS_DRAWN), n_samples=A(2, RUNS),
        sizes=A((0, 1), OBJ + (("repeated", (1, 1)),)),
        counts=A((0, 1), OBJ + (("negative", (-1,)),)), spreads=A((1, 2), OBJ + (("zero", (0,)),)),
        n_sensors=A(10, RUNS),
        truth=A(900.0, REAL))
    add(of.figure_fair, study=A(o["fair"], res(o["hs"])))
    add(of.fault_shapes_study, seed=A(0, SEED), n_runs=A(2, RUNS_DRAWN), sigma=A(1.0, POS + (("len", np.ones(4)),)),
        truth=A(900.0, REAL))
    add(of.fault_shapes_table, study=A(o["shapes"], OBJ + (NONE, ("empty", {}), ("few runs", o["shapes_few"]),
                                                             ("a method less", {k: {m: v for m, v in e.items()
                                                                                    if m != "mean"}
                                                                                for k, e in o["shapes"].items()}))),
        seed=A(None, SEED))
    add(of.information, method=A("mean", KEY))
    add(of.margin_sensitivity, ledger=A(o["ledger_json"], mapping(o["ledger_json"], "claims")), low=A(0.025, NONNEG),
        high=A(0.1, NONNEG + (("below low", 0.01),)))
    add(of.verdicts, study=A(o["fair"], res(o["hs"]) + (("few runs", o["fair_few"]),)),
        reference=A("optimal_fusion_set", KEY))

    # ---------------------------------------------------------------- chapter 03: lecture_wavelets
    E, SG, M, V = o["e26"], o["sg"], o["m26"], o["v26"]
    E26 = OBJ + (("other type", M), ("few runs", o["e26_few"]))  # an optional E2.6 given

    # a study of the key at fewer runs than rule R4's 100: refused where the function compares runs (its glue, its
    # verdicts), valid where it shows means or draws a figure
    def few(key: str) -> tuple:
        return (("few runs", o[f"{key}_few"]),)
    cj = verdicts.sign_conjunction(np.ones((100, 4)), np.ones((100, 4)) + 0.1, "A", "B", 0)
    st = {k: o[k] for k in lwr.STUDIES}
    # a reading's settings: None and {} are the primary reading (documented, fusion.book.chapters.lecture.reading_key)
    SETTINGS = OBJ + (("unknown reading", {"reading": "nope"}), ("unknown setting", {"reading": "primary", "x": 1}),
                      ("reading not a str", {"reading": 5}))
    tl = wa.table_lengths({64: o["len64"], 1024: o["len1024"]})
    nan_gain = frame(tl, nan_at=(64, wa.GAIN_ERROR_4))[-1][1]
    add(wa.glue_lengths,
        tab=A(tl, frame(tl, "lec-wavelet-better") + (("no row 1024", tl.iloc[:1]), ("nan gain", nan_gain))))
    ev_small = {"r": {"primary": cj}}
    tt = wa.table_typical(ev_small)
    add(wa.glue_typical, tab=A(tt, frame(tt, wa.BY_MEAN)))
    add(wa.length_study, length=A(64, RUNS + (("below 16", 15),)), seed=A(2601, SEED), runs=A(3, RUNS))
    add(wa.table_lengths, studies=A({64: o["len64"]}, mapping({64: 1}) + (("other length", {64: o["len128"]}),
                                                                          ("other type", {64: M}),
                                                                          ("few runs", {64: o["len64_few"]}))))
    add(wa.table_typical, ev=A(ev_small, mapping(ev_small) + (("reading of an int", {"r": {"primary": 5}}),)))
    add(wa.typical_run, ev=A(cj, res(M)))
    add(e26.figure_26, e=A(E, res(M)), sensor=A(3, ("neg", "frac", "str", ("beyond", 4))),
        shown=A(3, RUNS + (("beyond", 10**6),)))
    add(e26.glue_26, e=A(E, res(M) + few("e26")), spike=A(0.04, NONNEG), first=A(None, (("zero", 0), ("str", "abc"))))
    add(e26.glue_equal_gains, e1=A(o["g1"], res(M) + (("other study", o["len64"]),) + few("g1")))
    from fusion.book.benchmarks import load_benchmark
    add(e26.glue_runs_benchmark, b=A(load_benchmark("wavelet_runs"), res(M)))
    add(e26.glue_seeds, e26=A(E, res(M) + few("e26")), block=A(100, RUNS + (("below 100", 7), ("beyond", 101))),
        key=A("wsd", (("notstr", 3.0),)))
    aa = np.ones((100, 4))
    a1 = np.linspace(1.0, 2.0, 100)
    add(e26.mean_only_status, a=A(a1, ARR + (("len", a1[:-1]),)), b=A(a1 + 0.1, ARR + (("len", a1[:-1]),)),
        relative_margin=A(0.05, NONNEG))
    add(e26.table_26_display, e=A(E, res(M)))
    add(e26.table_seeds, e26=A(E, res(M) + few("e26")), block=A(100, RUNS + (("below 100", 7), ("beyond", 101))),
        ss=A(None, OBJ + (("int", 5),)),
        sensors=A((2, 3), OBJ + (("beyond", (99,)), ("repeated", (1, 1)))))
    add(mech.figure_mechanism, m=A(M, res(E)), shown=A(16, RUNS + (("beyond", 10**6),)))
    add(mech.glue_mechanism, m=A(M, res(E) + few("m26")), e26=A(E, E26))
    add(mech.table_mechanism, m=A(M, res(E)),
        labels=A((0, 6), OBJ + (("beyond", (0, 99)), ("negative", (-1,)), ("empty", ()))))
    # a valid study of three sensors: no sensor 4 to show (fuzz 26d, class A: refused naming m)
    M3 = (("three sensors", o["m3"]),)
    add(mech.table_sensitivity, m=A(M, res(E) + M3))
    add(mech.table_sensitivity_display, m=A(M, res(E) + few("m26") + M3), e26=A(E, E26), part=A("all", KEY))
    add(lwr.ev_wavelet_accurate, settings=A({"reading": "primary"}, SETTINGS),
        seed=A(2601, SEED), runs=A(100, RUNS))
    add(lwr.ev_wavelet_better, settings=A({"reading": "primary"}, SETTINGS),
        seed=A(2601, SEED), runs=A(100, RUNS))
    add(lwr.ev_wavelet_fusion_helps, settings=A({"reading": "primary"}, SETTINGS),
        seed=A(2601, SEED), runs=A(100, RUNS))
    add(lwr.ev_wavelet_weighting, settings=A({"reading": "primary"}, SETTINGS),
        seed=A(2601, SEED), runs=A(100, RUNS))
    add(lwr.evidence, st=A(st, mapping(st) + (("other type", {**st, "sg": M}),)), seed=A(None, SEED))
    add(lwr.ledger_values, st=A(st, mapping(st) + (("other type", {**st, "sg": M}),)))
    add(lwr.study, key=A("g1", KEY), seed=A(2601, SEED), runs=A(3, RUNS))
    add(signals.glue_signals, sg=A(SG, res(M) + few("sg")), e26=A(E, E26))
    add(signals.table_signals, sg=A(SG, res(M) + few("sg")), e26=A(E, E26), part=A("normalisers", KEY))
    add(variance.glue_variance, v=A(V, res(M) + few("v26") + (("three sensors", o["v3"]),)))
    add(variance.glue_weighting, v=A(V, res(M) + few("v26")), key=A("wwt", (("notstr", 3.0),)))
    add(variance.table_variance, v=A(V, res(M)))
    key = verdicts.PRIMARY
    add(verdicts.cell, sg=A(SG, res(M)), e26=A(E, OBJ + (("other type", M),)),
        key=A(key, OBJ + (("unknown", (key[0], "nope", "max")), ("short", key[:2]))))
    add(verdicts.sensor_conjunction, a=A(aa, ARR + (("len", aa[:-1]), ("one sensor", aa[:, :1]))), b=A(aa + 0.1, ARR),
        a_name=A("A", (("notstr", 3.0),)), b_name=A("B", (("notstr", 3.0),)), metric=A("m", (("notstr", 3.0),)),
        seed=A(0, SEED), claim=A("less", KEY))
    add(verdicts.sign_conjunction, a=A(aa, ARR + (("len", aa[:-1]), ("one sensor", aa[:, :1]))), b=A(aa + 0.1, ARR),
        a_name=A("A", (("notstr", 3.0),)), b_name=A("B", (("notstr", 3.0),)), seed=A(0, SEED))
    add(verdicts.status_text, c=A(cj, res(o["cmp"], M)))

    # ---------------------------------------------------------------- chapter 07: time_registration
    T1r, T2r = o["T1"], o["T2"]
    MET = (("unknown", ("nope",)), ("repeated", (RegMethod.TWO_POINT, RegMethod.TWO_POINT)), ("empty", ())) + OBJ
    SIGS = (("negative", (-1.0,)), ("nan", (float("nan"),)), ("repeated", (1.0, 1.0)), ("empty", ())) + OBJ
    times = ARR + (("unsorted", T1r[::-1]),)
    mc7, exact = o["mc7"], o["exact"]
    ex_m = mapping(exact, RegMethod.IMPROVED) + (("nan", {**exact, RegMethod.IMPROVED: float("nan")}),)
    add(tr.axes_tables, t1=A(T1r, times), t2=A(T2r, times))
    qls = ((tr.BenchClass.OFFLINE, RegMethod.QLS_NEXT), tr.EXACT_MSE)  # a cell benchmark_numbers glues
    add(tr.benchmark_numbers, bench=A(o["bench"], frame(o["bench"], tr.EXACT_MSE, qls)))
    add(tr.benchmark_table, mc=A(mc7, res(o["st7"]) + (("missing methods", o["mc7_4"]),)), exact=A(exact, ex_m))
    add(tr.closed_form_table, sigma_filter=A(1.0, POS), sigma=A(1.0, NONNEG))
    add(tr.crossing_table, closed=A(o["closed"], frame(o["closed"], "g")))
    add(tr.delay_break_even, sigma=A(1.0, POS), upper=A(0.05, POS))
    add(tr.delay_table,
        delays=A((0.0, 0.01), (("nan", (float("nan"),)), ("repeated", (0.0, 0.0)), ("empty", ())) + OBJ),
        sigmas=A((0.3, 1.0), SIGS))
    add(tr.exact_numbers, exact=A(exact, ex_m), sigma=A(1.0, POS), t2=A(T2r, times))
    add(tr.fig4_compatibility, sigmas=A((1.0,), SIGS), runs=A(20, RUNS), seed=A(0, SEED), axis_max=A(4.0, POS),
        block=A(20, RUNS))  # a block beyond the runs is valid: p ** block of independent runs
    add(tr.fig4_figure, mc=A(mc7, res(o["st7"]) + (("missing methods", o["mc7_4"]),)), exact=A(exact, ex_m),
        axis_max=A(4.0, POS))
    add(tr.fig4_reading_table, sigmas=A((1.0,), SIGS), runs=A(20, RUNS), seed=A(0, SEED), axis_max=A(4.0, POS),
        block=A(20, RUNS))  # a block beyond the runs is valid: p ** block of independent runs
    add(tr.fusion_table, fr=A(o["st7"].fusion, res(mc7)))
    add(tr.labelled, table=A(o["closed"], OBJ + (NONE,)), template=A("{}", (("no field", "x"), ("two fields", "{0}{1}"),
                                                                           ("notstr", 3.0))))
    add(tr.mc_table, mc=A(mc7, res(o["st7"])), exact=A(exact, ex_m))
    add(tr.named_crossings, crossings=A(o["crossings"], frame(o["crossings"], tr.BETTER_BELOW, (0, tr.SIGMA_STAR))),
        pairs=A(((RegMethod.THREE_POINT, RegMethod.TWO_POINT),), OBJ + (("unknown", (("nope", "x"),)),
        ("not pairs", (1.0,)))))
    add(tr.noise_free_table, t1=A(T1r, times), t2=A(T2r, times))
    add(tr.noise_level_table, mcs=A({1.0: mc7}, mapping({1.0: 1}) + (("missing methods", {1.0: o["mc7_4"]}),
                                                                    ("str key", {"a": mc7}),
                                                                    ("key not its sigma", {2.0: mc7}))),
        axis_max=A(4.0, POS), block=A(2, RUNS + (("beyond", 5),)))
    add(tr.period_change_table, sigma=A(1.0, POS))
    ratio = tr.ratio_sweep([3.0, 4.0], 1.0, [RegMethod.TWO_POINT])
    add(tr.ratio_figure, ratio=A(ratio, frame(ratio)))
    add(tr.ratio_sweep, periods=A((3.0, 4.0), SIGS), sigma=A(1.0, POS), names=A((RegMethod.TWO_POINT,), MET))
    add(tr.registration_figure, t1=A(T1r, times), t2=A(T2r, times), method=A(RegMethod.TWO_POINT, KEY),
        label=A("x", (("notstr", 3.0),)))
    add(tr.robustness_readings, sigma=A(1.0, POS), t2=A(T2r, times))
    add(tr.robustness_table, st=A(o["st7"], res(mc7)))
    sweep = tr.sigma_sweep([0.3, 1.0], [RegMethod.TWO_POINT])
    add(tr.sigma_figure, sweep=A(sweep, frame(sweep)))
    add(tr.sigma_sweep, sigmas=A((0.3, 1.0), SIGS), names=A((RegMethod.TWO_POINT,), MET))
    trans = tr.transient_table(60.0, 1.0)
    sq = "E[sq. error] (m²)"
    nan_t = trans.copy()
    nan_t.iat[0, list(trans.columns.get_level_values(1)).index(sq)] = np.nan
    add(tr.transient_end, table=A(trans, OBJ + (NONE, ("empty", trans.iloc[:0]), ("nan cell", nan_t),
                                                ("no E[sq. error]", trans.drop(columns=sq, level=1)))),
        tol=A(0.01, NONNEG), period=A(10.0, POS))
    add(tr.transient_table, horizon=A(60.0, POS), sigma=A(1.0, POS), names=A((RegMethod.IMPROVED,), MET))
    add(tr.tuning_by_noise, sigmas=A((1.0,), SIGS), runs=A(2, RUNS), seed=A(0, SEED))

    # ---------------------------------------------------------------- chapter 07: time_registration_ledger
    add(trl.blue_whole_record, sigma=A(1.0, POS))
    add(trl.cached_study, seed=A(0, SEED), runs=A(100, RUNS))  # o["st7"]: cached
    add(trl.cost_count, t1=A(T1r, times), t2=A(T2r, times))
    T2_6 = sc.instants(6.0)[1]
    add(trl.cost_values, t1=A(T1r, times), t2=A(T2r, times), t2_ratio=A(T2_6, times), sigma=A(1.0, POS))
    add(trl.exact_check, sigma=A(1.0, POS))
    add(trl.figs23_fits, a=A(1.0, REAL), end=A(30.0, POS), direction=A("fast onto slow", KEY))
    gv = {"reg_gain_three": 0.7, "reg_gain_two": 0.5}
    add(trl.gain_values, values=A(gv, mapping(gv) + (("nan", {**gv, "reg_gain_two": float("nan")}),)),
        closed=A(o["closed"], frame(o["closed"], "g", (trl.EXTRAP, "g"))))
    add(trl.keep, store=A({}, (("str", "abc"), NONE)), values=A({"a": 1.0}, OBJ + (NONE, ("nan", {"a": float("nan")}),
                                                                             ("int key", {1: 1.0}))))
    be = {0.3: 0.01, 1.0: 0.02}
    add(trl.latency_values, be=A(be, mapping(be, 1.0) + (("nan", {1.0: float("nan")}),)),
        sigma=A(1.0, REAL + (("not a key", 2.0),)))
    add(trl.ledger_evidence, seed=A(0, SEED), runs=A(100, RUNS))
    from fusion.scenarios import time_registration as sc_

    # the exact E[MSE] at sigma = 1 (manoeuvre_values refuses numbers of another noise level: fuzz 33b D4)
    man = {0.0: {n: sc_.expected(n, 1.0, a_after=0.0)
                 for n in (RegMethod.IMPROVED, RegMethod.TWO_POINT, RegMethod.THREE_POINT)},
           -2.0: {RegMethod.IMPROVED: sc_.expected(RegMethod.IMPROVED, 1.0, a_after=-2.0)}}
    add(trl.manoeuvre_values,
        manoeuvre=A(man, mapping(man) + (("nan", {**man, -2.0: {RegMethod.IMPROVED: float("nan")}}),)),
        sigma=A(1.0, POS))
    add(trl.nees_table, sigma=A(1.0, POS), runs=A(2, RUNS), seed=A(0, SEED))
    add(trl.noise_gain_by_instant, t1=A(T1r, times), t2=A(T2r, times))
    add(trl.stress_table, sigma=A(1.0, POS), names=A((RegMethod.TWO_POINT,), MET))
    add(trl.structured_ops)
    add(trl.study, t1=A(T1r, times), t2=A(T2r, times), sigma=A(1.0, POS), runs=A(2, RUNS_DRAWN), seed=A(0, SEED))
    add(trl.unregistered_runs, m=A(o["mc7_4"], res(o["st7"])), t1=A(T1r, times), t2=A(T2r, times))
    return r


#: function -> why its sweep still finds unrefused bad input (a strict xfail: it fails loudly once fixed).
PENDING: dict[str, str] = {}

test_registry_covers_the_group, test_bad_input_is_refused = group_tests(SWEPT, registry, EXCLUDED, PENDING)
