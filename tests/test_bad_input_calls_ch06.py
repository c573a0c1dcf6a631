"""Every public function of chapter 06 (Chernoff fusion) refuses bad input: one valid call each, mutated (issue 35).

The chapter layer is left out of the main sweep (``tests/test_bad_input.py``, ``EXCLUDED_PREFIXES``); this file
holds one valid call of every public function of the chapter's modules, with the mutations each argument must
refuse, and sweeps them with the main sweep's :func:`refusal_problems`: every mutated call raises ValueError or
TypeError naming the argument. The valid calls run on small objects, built once: a six-frame tracking scenario of
three runs (its comparisons carry the chapter's reason for fewer runs), the designed networks at a few runs (the
functions that judge them take a ``reason``), the two-mixture example at 200 samples. Mutations per argument by its
meaning: numbers by range (plus a complex value and one beyond the package's magnitudes), run lists and studies by
another type, another scenario's runs and fewer runs where two are paired, tables and records by a missing row,
column or key and a NaN cell, keys and readings by an unknown value. Documented valid input (an empty run list where
the result is empty, a subset of the networks, any frame window) is not mutated; a comment says so where it applies.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import json
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

from test_bad_input import ARR, COUNT, NONNEG, OBJ, POS, UNIT, A, group_tests, public_callables

ROOT = Path(__file__).resolve().parents[1]

PREFIXES = ("fusion.book.chapters.chernoff.", "fusion.book.chapters.chernoff_scaling.",
            "fusion.book.chapters.chernoff_steps.", "fusion.book.chapters.chernoff_snis.",
            "fusion.book.chapters.chernoff_criteria.", "fusion.book.chapters.chernoff_first_order.")

CALLABLES = {k: f for k, f in public_callables().items() if k.startswith(PREFIXES) and not inspect.isclass(f)}

#: Function -> why it has no valid call here.
EXCLUDED: dict[str, str] = {
    "fusion.book.chapters.chernoff.chapter_evidence":
        "every record's evidence: its valid call runs every study of the chapter (the networks at the 100 runs "
        "rule R4 asks of ev_premise, the toy at 20,000 samples, the design study); the ev_* it calls are swept here "
        "but for the two below",
    "fusion.book.chapters.chernoff.claim_values":
        "the same studies as chapter_evidence (networks at 100 runs, the toy at 20,000 samples, the design study)",
    # fixed-size studies no argument shrinks, each about 1 CPU-s (a tenth of this file's budget); their arguments are
    # checked by rules swept here in other entries (check_seed, count, the readings' _settings, premise_study's
    # scenarios), and is_variance_study, which isv_study caches, is swept at a small size
    "fusion.book.chapters.chernoff.isv_study":
        "is_variance_study at its defaults (R = 100, 20,000 replicates) for a seed: about 1 CPU-s, no size argument",
    "fusion.book.chapters.chernoff.ev_is_variance": "reads isv_study (about 1 CPU-s, no size argument)",
    "fusion.book.chapters.chernoff.ev_premise":
        "its comparison takes no reason, so rule R4 asks 100 runs of each of the six networks premise_study runs: "
        "about 1.5 CPU-s at the smallest networks",
}

SEED = ("neg", "frac", "str", ("bool", True), ("None", None))
CNT = COUNT + (("bool", True), ("None", None))
RNG = ("str", ("None", None), ("a seed", 3))


def _other(x: Any, **kw: Any) -> Any:
    return dataclasses.replace(x, **kw)


@functools.cache
def _o() -> dict[str, Any]:
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters import chernoff_first_order as cfo
    from fusion.book.chapters import chernoff_scaling as csc
    from fusion.scenarios import range_bearing as dist
    from fusion.scenarios.fusion_networks import Network, premise_scenarios, redundancy_scenarios

    sc = dist.RangeBearingScenario(frames=6, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                   n_components=2, readings=True, prev_optimiser="newton")
    plain, guarded = chc.tracking_study(1, 3, sc)  # cached: the evidence functions read the same study
    sc2 = _other(sc, frames=5, readings=False)
    plain2 = dist.monte_carlo(sc2, 2, 2, workers=1)
    crb = chc.crb_position(sc, guarded)
    toy = chc.toy_study(np.random.default_rng(3), 200)
    small = {k: _other(x, n_particles=40, n_samples=40, n_components=2, em_iterations=2, stages=1)
             for k, x in (premise_scenarios() | redundancy_scenarios()).items()}
    nets = chc.premise_studies(3, 4, small)
    connected = {**small, Network.CHAIN: _other(small[Network.UNEQUAL], name="test: fully connected")}
    fc = csc.frame_clouds(sc, 1, 3, run=0, frame=1)
    gms = cfo.random_two_mixtures(np.random.default_rng(5))
    table = chc.method_table(guarded, crb, plain)
    # valid runs the chapter's tables cannot show (fuzz 26b FW, NS, VA): 4 frames (no frame of LATE), 4 nodes, no variants
    edge = {k: dist.monte_carlo(_other(sc, **kw), 3, 2, workers=1) for k, kw in
            (("frames4", dict(frames=4)), ("nodes4", dict(sensors=sc.sensors + ((500.0, 500.0),))),
             ("novariants", dict(variants=False)))}
    return dict(connected=connected, sc=sc, plain=plain, guarded=guarded, sc2=sc2, plain2=plain2, crb=crb, toy=toy,
                small=small, nets=nets, fc=fc, gms=gms, table=table, **edge)


def _runs(o: dict[str, Any], key: str = "guarded", other: bool = True, twice: bool = True, frames: bool = False,
          nodes: bool = False, variants: bool = False) -> A:
    """``frames``, ``nodes``, ``variants``: runs the function cannot show are refused (fuzz 26b FW, NS, VA: 4 frames
    where frames 5 on are averaged, 4 nodes where every node is shown, no variants where they are read; asked of the
    functions without ``sc``, where a run list of another scenario is not refused for ``sc`` first)."""
    muts: tuple = ("str", ("empty", []), ("None", None), ("list of str", ["abc"]))
    if twice:  # a run twice is no study (fuzz 24b PR2); per-run values (twice=False) give its entry twice
        muts += (("a run twice", [o[key][0], *o[key][:-1]]),)
    if other:
        muts += (("another scenario's runs", o["plain2"]),)
    for flag, edge, how in ((frames, "frames4", "runs of 4 frames"), (nodes, "nodes4", "runs of 4 nodes"),
                            (variants, "novariants", "runs without the variants")):
        if flag:
            muts += ((how, o[edge]),)
    return A(o[key], muts)


def _paired(o: dict[str, Any]) -> A:
    """``plain`` beside ``guarded``: the same runs without the guard; refused: fewer runs, another scenario's, a run
    twice, and runs of another seed (their truths differ: here the runs' truths moved, which is what tells them)."""
    p = o["plain"]
    return A(p, ("str", ("empty", []), ("fewer runs", p[:2]), ("another scenario's runs", o["plain2"]),
                 ("a run twice", [p[0], *p[:-1]]),
                 ("another seed's runs", [_other(r, truth=r.truth + 1.0) for r in p])))


def _sc(o: dict[str, Any], other: bool = True) -> A:
    return A(o["sc"], ("str", ("None", None), ("a network scenario", o["small"][next(iter(o["small"]))]))
             + ((("another scenario", o["sc2"]),) if other else ()))


def _studies(o: dict[str, Any]) -> A:
    nets = o["nets"]
    first = next(iter(nets))
    # a subset of the networks is valid (the functions show the networks given), so a missing one is not refused
    from fusion.scenarios.fusion_networks import Network

    one, many = Network.UNEQUAL, Network.FEEDBACK  # a one-exchange network and one of several frames
    return A(nets, ("str", ("empty", {}), ("None", None), ("a study not a NetworkStudy", {**nets, first: "abc"}),
                    ("an unknown network", {**nets, "moon": nets[first]}),
                    ("networks under each other's key", {**nets, one: nets[many], many: nets[one]})))


def N(value: Any, mutations: tuple) -> A:
    """A real number or array argument: its mutations, a complex value and one beyond the package's magnitudes."""
    return A(value, tuple(mutations) + (("complex", value + 1j), ("huge", value * 1e200 + 1e200)))


REASON = A("small test study", (("not a str", 3.0),))


@functools.cache
def registry() -> dict[str, dict[str, A]]:
    """Valid calls: function name -> its arguments, each with the mutations to refuse."""
    from fusion.book.chapters import chernoff as chc
    from fusion.book.ledger import Ledger

    o = _o()
    R: dict[str, dict[str, A]] = {}
    c = "fusion.book.chapters.chernoff."
    # ---- settings, scenario values
    R[c + "study_scenario"] = {}
    R[c + "pso_defaults"] = {}
    R[c + "guarded_scenario"] = dict(sc=A(o["sc"], ("str", ("None", None))))
    R[c + "scenario_values"] = dict(sc=A(o["sc"], ("str", ("None", None))), runs=A(3, CNT))
    R[c + "message_sizes"] = dict(sc=A(o["sc"], ("str", ("None", None))), d=A(4, CNT))
    R[c + "scenario_table"] = dict(sc=A(o["sc"], ("str", ("None", None))))
    # ---- tracking tables
    R[c + "crb_position"] = dict(sc=_sc(o), runs=_runs(o))
    R[c + "method_table"] = dict(runs=_runs(o, frames=True, nodes=True, variants=True), crb_pos=N(o["crb"], ARR + ("len", "neg_entry")),
                                 plain=_paired(o))
    t = o["table"]
    R[c + "table_values"] = dict(table=A(t, ("str", ("None", None), ("another table", _cost_table()), ("a row missing", t.iloc[1:]),
                                             ("a column missing", t.iloc[:, 1:]),
                                             ("a NaN cell", t.mask(t.notna() & (np.arange(t.shape[0])[:, None] == 0))),
                                             ("zero RMSEs", t * 0),  # fuzz 24b TV: an RMSE or a NEES is positive
                                             ("a negative RMSE", t.mask(t.notna() & (np.arange(t.shape[0])[:, None] == 1), -5.0)))))
    R[c + "rmse_figure"] = dict(runs=_runs(o, nodes=True), crb_pos=N(o["crb"], ARR + ("len", "neg_entry")))
    R[c + "per_run_mse"] = dict(runs=_runs(o, other=False, twice=False, frames=True), key=A("chernoff_pso", ("unknown", ("not a str", 3.0))))
    R[c + "per_run_nees"] = dict(runs=_runs(o, other=False, twice=False), key=A("chernoff_pso", ("unknown", ("no covariance", "mean_of_local_means"))),
                                 frames=A(chc.LATE, ("str", ("no frame", slice(10, None)), ("step 0", slice(None, None, 0)))))
    R[c + "gain_values"] = dict(runs=_runs(o, other=False, frames=True, variants=True))
    # no runs give an empty result (documented: "empty for no runs"), so an empty list is not refused
    empty_ok = A(o["plain"], ("str", ("None", None), ("list of str", ["abc"])))
    R[c + "collapsed"] = dict(runs=empty_ok, n_particles=A(60, COUNT + (("bool", True), ("other size", 61))))
    R[c + "central_collapsed"] = dict(runs=empty_ok, n_central=A(100, COUNT + (("bool", True), ("other size", 101))))
    R[c + "any_collapsed"] = dict(runs=_runs(o, "plain"), sc=_sc(o))
    R[c + "typical_run"] = dict(runs=_runs(o, "plain", other=False), n_particles=A(60, CNT + (("other size", 61),)),
                                n_central=A(100, COUNT + (("bool", True), ("other size", 101))))  # None: valid (optional)
    R[c + "collapse_values"] = dict(plain=_runs(o, "plain"), sc=_sc(o))
    R[c + "readings_values"] = dict(runs=_runs(o, variants=True))
    R[c + "equal_kl_g_values"] = dict(runs=_runs(o, variants=True))
    # ---- gaussian checks, mixture example, peers
    R[c + "random_spd"] = dict(rng=A(np.random.default_rng(0), RNG), n=A(3, CNT))
    R[c + "gaussian_checks"] = dict(rng=A(np.random.default_rng(0), RNG), cases=A(3, CNT),
                                    triples=A(2, CNT))
    R[c + "common_information_check"] = dict(rng=A(np.random.default_rng(0), RNG), cases=A(3, CNT))
    R[c + "checks_study"] = dict(seed=A(1, SEED))
    R[c + "common_study"] = dict(seed=A(1, SEED))
    R[c + "criteria_example"] = {}
    R[c + "nested_gaussian_weight"] = dict(k=N(np.array([2.0, 10.0]), ("nan", "inf", "empty", "str", ("one", np.array([1.0, 2.0])), ("below one", 0.5))))
    R[c + "nested_values"] = dict(ks=A((2.0, 10.0), ("str", ("empty", ()), ("one", (1.0, 2.0)), ("nan", (np.nan, 2.0)))))
    toy = o["toy"]
    toy_muts = ("str", ("None", None), ("another result", o["fc"]))
    R[c + "toy_study"] = dict(rng=A(np.random.default_rng(0), RNG), r=A(100, CNT),
                              base=A(toy, ("str", ("another result", o["fc"]))))
    R[c + "toy"] = dict(seed=A(1, SEED), r=A(100, CNT))
    R[c + "objective_figure"] = dict(toy=A(toy, toy_muts))
    R[c + "contour_figure"] = dict(toy=A(toy, toy_muts), rng=A(np.random.default_rng(0), RNG),
                                   n_particles=A(50, CNT))
    rec = json.loads(chc.STONESOUP_RECORD.read_text(encoding="utf-8"))
    rows = rec["rows"]
    R[c + "stonesoup_check"] = dict(record=A(rec, ("str", ("empty", {}), ("a key missing", {k: v for k, v in rec.items() if k != "rows"}),
                                                   ("no rows", {**rec, "rows": []}),
                                                   ("a row without a key", {**rec, "rows": [{k: v for k, v in rows[0].items() if k != next(iter(rows[0]))}]}),
                                                   ("a NaN mean", {**rec, "measurement": {**rec["measurement"], "mean": [float("nan")] * len(rec["measurement"]["mean"])}}),
                                                   # fuzz 24b SS: each named by its place in the record
                                                   ("no omega 0.8 row", {**rec, "rows": [r for r in rows if r["omega"] != 0.8]}),
                                                   ("rows an array", {**rec, "rows": np.array(rows)}),
                                                   ("version None", {**rec, "stonesoup_version": None}),
                                                   ("an indefinite covariance", {**rec, "measurement": {**rec["measurement"], "covariance": [[1.0, 2.0], [2.0, 1.0]]}}))))
    # ---- importance sampling
    R[c + "is_replicates"] = dict(seed=A(1, SEED), r=A(50, CNT), runs=A(3, CNT))
    R[c + "is_replicate_values"] = dict(seed=A(1, SEED), runs=A(3, CNT))
    R[c + "is_variance_study"] = dict(rng=A(np.random.default_rng(0), RNG), R=A(20, CNT),
                                      replicates=A(50, COUNT + (("bool", True), ("one", 1))))
    R[c + "guarded_runs"] = dict(runs=_runs(o, "plain"), sc=_sc(o), seed=A(1, SEED), workers=A(1, CNT))
    R[c + "guard_values"] = dict(guarded=_runs(o), sc=_sc(o))
    R[c + "guard_usability"] = dict(guarded=_runs(o), plain=_paired(o),
                                    sc=_sc(o), thresholds=A((0.01, 0.05), ("str", ("nan", (np.nan,)), ("negative", (-0.1,)), ("one", (1.0,)))))
    # no other thresholds is valid (documented: "empty: none"), so an empty tuple is not refused
    R[c + "design_study"] = dict(sc=A(o["sc"], ("str", ("None", None))), seed=A(1, SEED), runs=A(2, CNT),
                                 n_initial=A(200, COUNT + (("bool", True), ("beyond the memory budget", 10**7),
                                                             ("not above sc.n_particles", 60))),  # None: the default
                                 workers=A(1, CNT))
    R[c + "design"] = dict(seed=A(1, SEED), runs=A(2, CNT), sc=A(o["sc"], ("str",)))
    # ---- swarm, figures
    R[c + "eps_figure"] = dict(runs=_runs(o), sc=_sc(o), show=A(0, ("neg", "frac", "str", ("beyond", 3), ("bool", True))))
    R[c + "pso_figure"] = dict(runs=_runs(o, other=False, variants=True), frame=A(3, ("zero", "neg", "frac", "str", ("beyond", 7), ("bool", True))),
                               show=A(0, ("neg", "frac", "str", ("beyond", 3), ("bool", True))))
    R[c + "stopping_values"] = dict(runs=_runs(o), sc=_sc(o), xtols=A((0.001, 0.01), ("str", ("empty", ()), ("nan", (np.nan,)), ("zero", (0.0,)))))
    bench = ROOT / "benchmarks" / "results" / "chernoff.json"
    R[c + "benchmark_cost"] = dict(path=A(bench, (("not a path", 3.0), ("missing", ROOT / "no-such-file.json"),
                                                  ("not JSON", ROOT / "pyproject.toml"))))
    R[c + "consistency_figure"] = dict(runs=_runs(o), plain=_paired(o), sc=_sc(o))
    # ---- review
    R[c + "review_values"] = dict(runs=_runs(o), crb_pos=N(o["crb"], ARR + ("len", "neg_entry")), sc=_sc(o), seed=A(1, SEED))
    R[c + "double_count_values"] = dict(runs=_runs(o), sc=_sc(o))
    R[c + "diagnostics"] = dict(runs=_runs(o), sc=_sc(o), seed=A(1, SEED))
    R[c + "gm_yardstick"] = dict(rng=A(np.random.default_rng(0), RNG), runs=_runs(o), sc=_sc(o),
                                 sets=A(3, CNT + (("beyond the memory budget", 10**6),)))
    # ---- the designed networks
    # the chain network's exponents are NaN where a node hears no other (documented): the valid call runs a fully
    # connected network under its key, so that the result is finite
    R[c + "premise_studies"] = dict(seed=A(3, SEED), runs=A(2, CNT),
                                    scenarios=A(o["connected"], ("str", ("empty", {}), ("a scenario not a NetworkScenario", {**o["small"], next(iter(o["small"])): "abc"}))),
                                    more=A({next(iter(o["small"])): 3}, ("str", ("unknown network", {"moon": 3}), ("zero", {next(iter(o["small"])): 0}), ("below runs", {next(iter(o["small"])): 1}))))
    R[c + "premise_study"] = dict(seed=A(3, SEED), runs=A(2, CNT),
                                  scenarios=A(o["connected"], ("str", ("empty", {}), ("a network missing", {k: v for k, v in o["small"].items() if k != next(iter(o["small"]))}))))
    for fn in ("premise_table", "premise_figure", "premise_values", "premise_robust_values"):
        R[c + fn] = dict(studies=_studies(o), reason=REASON)
    R[c + "oracle_exponents"] = dict(st=A(o["nets"][next(iter(o["nets"]))], ("str", ("None", None), ("another result", o["toy"]), ("not an oracle network", o["nets"][chc.PREMISE_NETWORKS[2]]))),
                                     step=N(0.25, ("zero", "neg", "nan_s", "str", ("above one", 1.5), ("not 1/integer", 0.3))))
    # its comparison has no reason argument: rule R4's 100 runs (2 x 50) of the range-only network
    R[c + "premise_mixture_scaled"] = dict(seed=A(3, SEED), runs=A(2, CNT),
                                           factor=A(50, CNT + (("too few runs (R4, no reason)", 1),)))
    # ---- evidence functions
    sc = o["sc"]
    scA = A(sc, ("str",))
    # settings None is no settings, the one rule of every chapter's readers (fusion.book._reader_settings,
    # fix58b): not a mutation here
    R[c + "ev_tracking"] = dict(settings=A({"a": "chernoff_pso", "b": "chernoff_uniform"}, ("str", ("a list", []), ("a key missing", {"a": "chernoff_pso"}), ("unknown method", {"a": "chernoff_pso", "b": "nope"}),
                                                                                           ("a method against itself", {"a": "chernoff_pso", "b": "chernoff_pso"}),
                                                                                           ("NEES of a method without a covariance", {"a": "mean_of_local_means", "b": "chernoff_pso", "metric": "nees"}))),
                                seed=A(1, SEED), runs=A(3, CNT), sc=scA)
    R[c + "ev_pso"] = dict(settings=A({"check": "within-se"}, ("str", ("a list", []), ("unknown check", {"check": "vibes"}))),
                           seed=A(1, SEED), runs=A(3, CNT), sc=scA)
    for fn, st in (("ev_formulas", {}), ("ev_common_once", {}), ("ev_gaussian_ci", {"statement": "ci"}), ("ev_first_order", {}),
                   ("ev_peer", {})):
        R[c + fn] = dict(settings=A(st, ("str", ("a list", []), ("unknown key", {**st, "nope": 1}))), seed=A(1, SEED), runs=A(3, CNT))
    R[c + "ev_is"] = dict(settings=A({"r": 50}, ("str", ("a list", []), ("r zero", {"r": 0}), ("unknown key", {"r": 50, "nope": 1}))),
                          seed=A(1, SEED), runs=A(3, CNT))
    R[c + "ev_equal_kl"] = dict(settings=A({}, ("str", ("a list", []), ("unknown key", {"nope": 1}))), seed=A(1, SEED), runs=A(3, CNT), sc=scA)
    R[c + "ev_filter_design"] = dict(settings=A({"reading": "plain"}, ("str", ("a list", []), ("unknown reading", {"reading": "nope"}))),
                                     seed=A(1, SEED), runs=A(2, CNT), sc=scA)
    R[c + "referenced"] = dict(values=A({"chf_runs": 3, "nope": 1}, ("str", ("None", None), ("a list", []))))
    R[c + "ledger_values"] = dict(led=A(Ledger(chc.BIBKEY), ("str", ("None", None), ("another result", o["toy"]), ("another source's ledger", Ledger("lecture003")))))
    R[c + "tracking_study"] = dict(seed=A(1, SEED), runs=A(3, CNT), sc=A(o["sc"], ("str",)))
    # ---- chernoff_criteria
    from fusion.book.chapters import chernoff_criteria as ccr
    from fusion.scenarios.fusion_networks import Network

    cr = "fusion.book.chapters.chernoff_criteria."
    nets = o["nets"]
    one = nets[Network.UNEQUAL]
    multi = nets[Network.FEEDBACK]
    labels = dict(chc.PREMISE_LABELS)
    lab = A(labels, ("str", ("empty", {}), ("a label not a str", {**labels, Network.UNEQUAL: 3.0}),
                     ("two networks one label", {**labels, Network.NON_GAUSSIAN: labels[Network.UNEQUAL]}),
                     ("an empty label", {**labels, Network.CHAIN: " "}),
                     ("a label of no network", {**labels, "moon": "x"})))
    for fn in ("baseline_table", "criteria_table", "criteria_values"):
        R[cr + fn] = dict(studies=_studies(o), labels=lab, reason=REASON)
    stA = A(one, ("str", ("None", None), ("another result", o["toy"]), ("a multi-frame network", multi)))
    R[cr + "channel_filter"] = dict(study=stA)
    R[cr + "gaussian_exchange"] = dict(study=stA, rule=A("ci_gaussian", ("unknown", ("not a str", 3.0))))
    rg = np.random.default_rng(0)
    means = rg.normal(size=(2, 3, 2))
    covs = np.tile(np.eye(2), (2, 3, 1, 1)) * np.array([1.0, 2.0, 3.0])[None, :, None, None]
    R[cr + "exponent_rule"] = dict(rule=A("ci_det", ("unknown", ("not a str", 3.0))),
                                   means=N(means, ("nan", "inf", "empty", "less", "str", "len")),
                                   covs=N(covs, ("nan", "inf", "empty", "less", "str", "nonsym", "indef", "negdef", "sing")))
    est = np.asarray(one.estimates["exact_posterior"]) + 1.0
    # estimates are any positions of the study's shape: another study of that shape is not a mismatch
    R[cr + "network_mse"] = dict(study=A(one, ("str", ("None", None), ("another result", o["toy"]))),
                                 estimates=N(est, ("nan", "inf", "empty", "more", "less", "str", "len")))
    R[cr + "prior_means"] = dict(sc=A(o["small"][Network.UNEQUAL], ("str", ("None", None), ("a tracking scenario", o["sc"]))),
                                 seed=A(3, SEED), runs=A(4, CNT))
    R[cr + "appendix_referenced"] = dict(values=A({"chf_pr_runs": 4, "nope": 1}, ("str", ("None", None), ("a list", []))),
                                         notebook=A(ROOT / "notebooks" / "06_chernoff_fusion_appendix.ipynb",
                                                    (("not a path", 3.0), ("missing", ROOT / "no-such.ipynb"),
                                                     ("not a notebook", ROOT / "pyproject.toml"))))
    # ---- chernoff_first_order
    from fusion.book.chapters import chernoff_first_order as cfo  # noqa: F401

    fo = "fusion.book.chapters.chernoff_first_order."
    ga, gb = o["gms"]
    gm3 = _gm3()
    gmA = lambda g: A(g, ("str", ("None", None), ("another result", o["toy"]), ("a 3-D mixture", gm3)))  # noqa: E731
    R[fo + "random_two_mixtures"] = dict(rng=A(np.random.default_rng(0), RNG))
    R[fo + "sigma_first_order_problem"] = dict(a=gmA(ga), b=gmA(gb), n=A(41, ("zero", "neg", "frac", "str", ("one", 1), ("bool", True))))
    R[fo + "sigma_first_order_study"] = dict(rng=A(np.random.default_rng(0), RNG), runs=A(2, CNT + (("one", 1),)))
    R[fo + "sigma_point_first_order"] = dict(gms=A([ga, gb], ("str", ("empty", []), ("a non-mixture", [ga, "abc"]), ("dimensions differ", [ga, gm3]))),
                                             eps=N(np.array([0.4, 0.6]), ARR + ("len", "neg_entry", ("off the simplex", np.array([0.4, 0.4])))))
    # ---- chernoff_scaling
    sg = "fusion.book.chapters.chernoff_scaling."
    ns_bad = ("str", ("empty", ()), ("zero", (0, 3)), ("repeated", (3, 3)), ("frac", (2.5, 3)))
    R[sg + "box_corner"] = dict(eps=N(np.array([[0.5, 0.5, 0.0], [0.2, 0.3, 0.5]]), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                tol=N(1e-9, NONNEG + (("too big", 0.1),)))
    fc = o["fc"]
    R[sg + "clouds_figure"] = dict(fc=A(fc, ("str", ("None", None), ("another result", o["toy"]))))
    R[sg + "cost_table"] = dict(ns=A((2, 3), ns_bad), ss=A((1, 2), ("str", ("empty", ()), ("zero", (0, 1)), ("frac", (1.5,)))))
    R[sg + "density_evaluations"] = dict(n=A(3, CNT), s=A(2, CNT))
    R[sg + "frame_clouds"] = dict(sc=A(o["sc"], ("str", ("None", None))), seed=A(1, SEED), runs=A(3, CNT),
                                  run=A(0, ("neg", "frac", "str", ("beyond", 3), ("bool", True))),
                                  frame=A(1, ("neg", "frac", "str", ("beyond", 6), ("bool", True))))
    R[sg + "gaussian_problems"] = dict(rng=A(np.random.default_rng(0), RNG), runs=A(2, CNT),
                                       n=A(3, CNT), d=A(2, CNT))
    R[sg + "scaling_study"] = dict(seed=A(1, SEED), rs=A((20, 40), ("str", ("one size", (20,)), ("repeated", (20, 20)), ("below two", (1, 20)))),
                                   n=A(2, CNT + (("one", 1),)), runs=A(2, CNT + (("one", 1),)))
    R[sg + "swarm_study"] = dict(seed=A(1, SEED), ns=A((2, 3), ns_bad), runs=A(2, CNT + (("one", 1),)),
                                 r=A(20, CNT + (("one", 1),)))
    R[sg + "swarm_within_se"] = dict(seed=A(1, SEED), n=A(2, CNT + (("one", 1),)),
                                     runs=A(2, CNT + (("one", 1),)), r=A(20, CNT + (("one", 1),)))
    ns_bad = ns_bad[:2] + (("one node", (1, 3)),) + ns_bad[3:]  # the studies need two nodes at least
    R[sg + "within_se_counts"] = dict(seed=A(1, SEED), ns=A((2, 3), ns_bad), runs=A(2, CNT + (("one", 1),)))
    # ---- chernoff_steps
    from fusion.estimates.chernoff import first_order_fusion

    sp = "fusion.book.chapters.chernoff_steps."
    sh = "fusion.book.chapters.chernoff_snis."  # step H's studies, split off chernoff_steps
    rs_bad = ("str", ("empty", ()), ("repeated", (10, 10)), ("below two", (1, 10)), ("not dividing", (7, 10)),
              ("beyond half", (10, 2000)))
    R[sh + "snis_bias_study"] = dict(rng=A(np.random.default_rng(0), RNG), rs=A((5, 10), rs_bad), total=A(2000, CNT),
                                     far_omega=N(0.7, UNIT))
    R[sh + "chosen_bias_study"] = dict(rng=A(np.random.default_rng(0), RNG), rs=A((5, 10), rs_bad), total=A(2000, CNT))
    g = first_order_fusion([ga, gb], [0.5, 0.5]).mixture
    R[sp + "defensive_mixture"] = dict(proposal=A(g, ("str", ("None", None), ("a 3-D mixture", gm3))),
                                       local=A([ga, gb], ("str", ("empty", []), ("a non-mixture", [ga, "abc"]), ("dimensions differ", [ga, gm3]))),
                                       alpha=N(0.2, ("zero", "neg", "nan_s", "str", ("above one", 1.5))))
    R[sp + "defensive_study"] = dict(rng=A(np.random.default_rng(0), RNG), runs=A(2, CNT + (("one", 1),)),
                                     r=A(50, CNT), alpha=N(0.2, ("zero", "neg", "nan_s", "str", ("above one", 1.5))))
    a = np.array([1.0, 2.0, 1.5, 0.5, 1.2])
    R[sp + "paired_numbers"] = dict(a=N(a, ("nan", "inf", "empty", "more", "str", "len")), b=N(a + 0.3, ("nan", "inf", "empty", "more", "str")),
                                    prefix=A("chf_x", (("not a str", 3.0), ("not an identifier", "a b"))),
                                    decimals=A(4, ("neg", "frac", "str", ("bool", True))),
                                    relative_margin=N(0.05, POS))
    truths = _truths()
    R[sp + "study_truths"] = dict(sc=A(o["sc"], ("str", ("None", None))), seed=A(1, SEED), runs=A(3, CNT))
    # the bound uses sc's model and sensors along the truths given, whatever sc.frames: no scenario mismatch here; any
    # slice that selects a frame is a window (fusion._selections.frame_slice)
    R[sp + "single_sensor_crb"] = dict(sc=A(o["sc"], ("str", ("None", None))),
                                       truths=N(truths, ("nan", "inf", "empty", "more", "less", "str")),
                                       frames=A(slice(4, None), ("str", ("no frame", slice(10, None)), ("step 0", slice(None, None, 0)))))
    R[sp + "single_sensor_values"] = dict(sc=A(o["sc"], ("str", ("None", None))), seed=A(1, SEED), runs=A(3, CNT))
    xs = np.linspace(-6.0, 6.0, 61)
    pts = np.stack(np.meshgrid(xs, xs, indexing="ij"), axis=-1).reshape(-1, 2)
    lt = -0.5 * np.sum((pts - 0.5) ** 2, axis=1)
    cell = float((xs[1] - xs[0]) ** 2)
    lp = -0.5 * np.sum(pts ** 2, axis=1) / 2.0 - np.log(2 * np.pi * 2.0)
    R[sh + "snis_delta_terms"] = dict(points=N(pts, ("nan", "inf", "empty", "less", "str", "len")),
                                      log_target=N(lt, ("nan", "inf", "empty", "more", "str", "len")),
                                      log_proposal=N(lp, ("nan", "inf", "empty", "more", "str", "len")),
                                      cell=N(cell, POS + (("bool", True),)))
    R[sp + "toy_reference"] = {}
    return R


def _cost_table() -> pd.DataFrame:
    from fusion.book.chapters import chernoff_scaling as csc

    return csc.cost_table((2, 3), (1, 2))


def _gm3() -> Any:
    from fusion.estimates.mixtures import GaussianMixture

    return GaussianMixture(np.array([1.0]), np.zeros((1, 3)), np.eye(3)[None])


@functools.cache
def _truths() -> np.ndarray:
    from fusion.book.chapters import chernoff_steps as cst

    return cst.study_truths(_o()["sc"], 1, 3)


#: Functions whose sweep still finds unrefused bad input: a strict xfail, with the reason.
PENDING: dict[str, str] = {}

test_registry_covers_the_group, test_bad_input_is_refused = group_tests(CALLABLES, registry, EXCLUDED, PENDING)
