"""Fuzz 24d, class S: the result classes of ``fusion.scenarios`` that chapters take refuse a tampered field when built.

``dataclasses.replace`` is a result's public constructor (``fusion._results``; the chapter layer's classes had their
specs in issue 35 class E, ``tests/test_bad_input_results_chapters.py``). The scenario studies the chapters 01-04 and
07 consume (time registration's Monte Carlo and fusion runs, the thermocouples' paired study, the wavelet, ridge,
correlated and lecture-weighting studies) accepted NaN, negative MSEs, zero counts, truncated arrays and dropped keys,
and the chapter functions then crashed (IndexError, KeyError, ZeroDivisionError) or showed NaN. Each class now
declares a ``__result_spec__``: the kinds of its fields, the lengths that must agree (``runs`` = the length of the
per-run arrays), the dicts that must hold the same keys, ranges (MSEs >= 0, counts >= 1, shares in [0, 1]).

The frozen result classes of ``fusion.scenarios`` are enumerated from the source (AST): one without a spec must be
listed in :data:`NOT_YET_SPECCED` (the classes no chapter function of this fuzz consumes, left for a later round), so
a new class without a spec fails, and a listed class that gains one must leave the list.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import fusion
from fusion import _results as R
from test_bad_input_results_chapters import _mutations, _shared_dims
from _helpers import parsed

SCENARIOS = Path(fusion.__file__).resolve().parent / "scenarios"

#: Frozen result classes of fusion.scenarios without a spec yet (none is consumed by chapters 01-04 or 07's functions
#: through a field the fuzz 24d found unchecked); the list may only shrink.
NOT_YET_SPECCED = {
    # settings, not results: their own __post_init__ (which replace runs too) refuses every field by the argument's
    # name (``^position must be numeric``, test_bad_input_classes) and converts any 2-sequence or array of
    # coordinates; validated_post_init would rename those public input messages and refuse those layouts
    "fusion_networks.NetworkNode", "fusion_networks.NetworkScenario", "range_bearing_scenario.RangeBearingScenario",
}


def _frozen_classes() -> dict[str, tuple[str, str]]:
    """Every public frozen dataclass of fusion.scenarios: "module.Class" (relative) -> (import path, class name)."""
    out: dict[str, tuple[str, str]] = {}
    for path in sorted(SCENARIOS.rglob("*.py")):
        rel = path.relative_to(SCENARIOS).with_suffix("")
        parts = [p for p in rel.parts if p != "__init__"]
        for node in parsed(path).body:
            if (isinstance(node, ast.ClassDef) and not node.name.startswith("_")
                    and any("dataclass" in ast.unparse(d) and "frozen=True" in ast.unparse(d)
                            for d in node.decorator_list)):
                out[".".join([*parts, node.name])] = (".".join(["fusion.scenarios", *parts]), node.name)
    return out


CLASSES = _frozen_classes()


def _cls(key: str) -> type:
    module, name = CLASSES[key]
    return getattr(importlib.import_module(module), name)


#: Scenario classes specced before this round, tested with the results of their own layers (issue 35).
EARLIER = {"infrared_radar.CartesianTracks", "infrared_radar.IrRadarRuns", "infrared_radar.Truth",
           "lecture_weighting.belief.BeliefParameterStudy", "range_bearing_scenario.TrackingRun",
           "two_sensor.case.Scenario"}


def test_every_frozen_scenario_result_declares_a_spec_or_is_listed() -> None:
    assert len(CLASSES) >= 40, sorted(CLASSES)  # the enumeration works (a broken parser cannot pass)
    without = {key for key in CLASSES if getattr(_cls(key), "__result_spec__", None) is None}
    assert not without - NOT_YET_SPECCED, sorted(without - NOT_YET_SPECCED)  # a new class needs a spec
    assert not NOT_YET_SPECCED - without, sorted(NOT_YET_SPECCED - without)  # a specced class leaves the list
    for key in set(CLASSES) - without - EARLIER:
        assert _cls(key).__post_init__ in (R.validated_post_init, R.shared_post_init), key


def _ws() -> Any:
    return importlib.import_module("fusion.scenarios.wavelet_sensors")


def _lw() -> Any:
    return importlib.import_module("fusion.scenarios.lecture_weighting")


def _tr() -> Any:
    return importlib.import_module("fusion.scenarios.time_registration")


def _learning() -> Any:
    """E2.2 at a small size: a setting of two sensors (no corrected learning: NaN) and one of three."""
    return _lw().learning_study(r_sets=((1.0, 4.0), (1.0, 4.0, 9.0)), epochs=50, runs=10, last=10)


def _constant_level_runs() -> Any:
    """The base of the constant-level studies (no producer builds it alone): a tail study's settings."""
    tail = _lw().tail_study(runs=200, k=5, chunk=100)
    cls = _cls("lecture_weighting.estimators.ConstantLevelRuns")
    return cls(**{f.name: getattr(tail, f.name) for f in dataclasses.fields(cls)})


def _sc(module: str) -> Any:
    """The scenario module ``fusion.scenarios.<module>``, imported when a factory runs."""
    return importlib.import_module(f"fusion.scenarios.{module}")


def _tiny_rb(**kwargs: Any) -> Any:
    """Chapter 06's tracking scenario over 3 frames (``kwargs``: fewer particles for a run)."""
    return _sc("range_bearing").RangeBearingScenario(frames=3, **kwargs)


def _ts_covariances() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """R1, R2 (m²) and Q of a two-sensor study (a constant-velocity target's process noise)."""
    return np.eye(2) * 2500.0, np.eye(2) * 900.0, np.diag([0.0, 1.0, 0.0, 1.0])


#: A real instance of each specced class, from its producer at a small size.
FACTORIES: dict[str, Callable[[], Any]] = {
    "time_registration.MonteCarlo": lambda: _tr().monte_carlo(list(_tr().METHODS), 1.0, 4, 0),
    "time_registration.FusionRuns": lambda: _tr().fusion_runs([m.value for m in _tr().RegMethod][:3], 1.0, 3, 0),
    "thermocouples.PairedStudy": lambda: importlib.import_module("fusion.scenarios.thermocouples").paired_study(
        1, 2, {"mean": {"method": "mean"}, "set": {"method": "optimal_fusion_set"}}),
    "wavelet_sensors.SignalStudy": lambda: _ws().signal_study(
        signals=(_ws().Signal.TWO_TONES,), modes=("hard",), normalisers=("max", "median"), length=64, runs=2, level=2),
    "wavelet_sensors.MechanismStudy": lambda: _ws().mechanism_study(length=256, runs=2, configs=_ws().CONFIGS[:2]),
    "wavelet_sensors.VarianceStudy": lambda: _ws().variance_study(length=128, runs=2, window=16),
    "lecture_correlated.CorrelatedStudy": lambda: importlib.import_module(
        "fusion.scenarios.lecture_correlated").correlated_study(runs=5),
    "correlated_sensors.EstimatedCovarianceStudy": lambda: importlib.import_module(
        "fusion.scenarios.correlated_sensors").estimated_covariance_study(ns=(10, 30), reps=3),
    "lecture_correlated.RidgeStudy": lambda: importlib.import_module(
        "fusion.scenarios.lecture_correlated").ridge_study(ms=(1, 5), draws=20),
    "correlated_sensors.CouplingStudy": lambda: importlib.import_module(
        "fusion.scenarios.correlated_sensors").coupling_study(runs=5),
    "ridge_sensors.PluginStudy": lambda: importlib.import_module("fusion.scenarios.ridge_sensors").plugin_study(runs=5),
    "ridge_sensors.VectorStudy": lambda: importlib.import_module("fusion.scenarios.ridge_sensors").vector_study(runs=2),
    "lecture_weighting.belief.BeliefStudy": lambda: _lw().belief_study(snapshots=10),
    "lecture_weighting.estimators.AwfStudy": lambda: _lw().awf_study(levels=(0.0, 100.0, 900.0), runs=4),
    "lecture_weighting.estimators.AR1Study": lambda: _lw().ar1_study(k=10, runs=100),
    "lecture_weighting.consistency.ConsistencyStudy": lambda: _lw().consistency_study(runs=3),
    # lecture weighting, the rest of its results (spec26b): a study's rows and diagnostics from their study
    "lecture_weighting.belief.PerronStats": lambda: next(iter(_lw().belief_study(snapshots=10).perron.values())),
    "lecture_weighting.consistency.FaultDiagnostics": lambda: next(iter(_lw().consistency_study(runs=3).diag.values())),
    "lecture_weighting.estimators.ConstantLevelRuns": lambda: _constant_level_runs(),
    "lecture_weighting.estimators.TailStudy": lambda: _lw().tail_study(runs=200, k=5, chunk=100),
    "lecture_weighting.estimators.EstimatorRow": lambda: _lw().awf_study(levels=(0.0, 900.0), runs=4).rows[0],
    "lecture_weighting.estimators.LumvStudy": lambda: _lw().lumv_study(runs=8, k=5),
    "lecture_weighting.estimators.SymmetryStudy": lambda: _lw().symmetry_study(runs=5, k=5),
    "lecture_weighting.learning.LearningRow": lambda: _learning().rows[0],
    "lecture_weighting.learning.LearningStudy": lambda: _learning(),
    "lecture_weighting.learning.LearnedLimitCheck": lambda: _lw().learned_limit_check(ns=(3, 4), draws=100),
    "lecture_weighting.readings_benchmark.SeedStability": lambda: _lw().seed_stability(
        _lw().benchmark(seeds=(1, 2), runs=10, samples=60)),
    "lecture_weighting.regime.RegimeStudy": lambda: _lw().regime_study(samples=40, runs=3, change_at=20, window=10),
    "lecture_weighting.regime.VarianceChangeStudy": lambda: _lw().variance_change_study(samples=40, runs=3,
                                                                                        change_at=20),
    # spec26a: chapters 05 and 06's scenario results and the wavelet seed study
    "fusion_networks.NetworkStudy": lambda: _sc("fusion_networks").run_network_study(
        _sc("fusion_networks").NetworkScenario("tiny", _sc("fusion_networks").premise_scenarios()["non_gaussian"].nodes,
                                               n_particles=30, n_samples=30, n_components=2, em_iterations=2, stages=1),
        1, 2),
    "range_bearing_bounds.LinearisedErrors": lambda: _sc("range_bearing").linearised_errors(_tiny_rb()),
    "range_bearing_scenario.TrackingTimings": lambda: _sc("range_bearing").run_tracking(
        _tiny_rb(n_particles=60, n_samples=60, n_central=100, n_components=2, em_iterations=2),
        np.random.SeedSequence(1)).timings,
    "range_bearing_scenario.SimulatedTarget": lambda: _sc("range_bearing").simulate_target(
        _tiny_rb(), np.random.default_rng(0)),
    "two_mixtures.ToyMixtures": lambda: _sc("two_mixtures").toy_mixtures(),
    "two_mixtures.GridLogNormaliser": lambda: _sc("two_mixtures").grid_log_normaliser(
        list(vars(_sc("two_mixtures").toy_mixtures()).values()), [[0.5, 0.5], [0.2, 0.8]], n=21, return_density=True),
    "two_sensor.architecture.ArchitectureStudy": lambda: _sc("two_sensor").architecture_study(
        np.random.default_rng(0), *_ts_covariances(), runs=2, nees_runs=2, T=5.0, printed_omegas=(0.5,),
        placement_omegas=(0.5,)),
    "two_sensor.architecture.QScaling": lambda: _sc("two_sensor").q_scaling_study(
        np.random.default_rng(0), *_ts_covariances(), scales=(0.5, 1.0), runs=2, nees_runs=2, T=5.0),
    "two_sensor.case.Trajectory": lambda: _sc("two_sensor").trajectory(5.0),
    "two_sensor.study.FusionStudy": lambda: _sc("two_sensor").fusion_study(_sc("two_sensor").two_sensor_scenario(
        *_ts_covariances(), np.random.default_rng(0), runs=2, T=5.0)),
    "two_sensor.study.NeesStudy": lambda: _sc("two_sensor").nees_study(
        np.random.default_rng(0), _ts_covariances()[2], *_ts_covariances()[:2], (300.0, 0.0, 0.0, 50.0), 30, 2),
    "two_sensor.weights.FruitFlySeeds": lambda: _sc("two_sensor").fruit_fly_over_seeds(
        np.diag([4.0, 1.0, 4.0, 1.0]), np.diag([1.0, 3.0, 1.0, 3.0]), (0, 1, 2), n_grid=11, population=5,
        iterations=5),
    "wavelet_sensors.SeedStudy": lambda: _ws().seed_study(seeds=(0, 1), runs=2, length=64, level=2),
}

SPECCED = sorted(key for key in CLASSES if getattr(_cls(key), "__result_spec__", None) is not None)
_INSTANCES: dict[str, Any] = {}


def _instance(key: str) -> Any:
    if key not in _INSTANCES:
        _INSTANCES[key] = FACTORIES[key]()
    return _INSTANCES[key]


def test_every_specced_class_has_a_factory() -> None:
    assert set(SPECCED) - EARLIER <= set(FACTORIES), sorted(set(SPECCED) - EARLIER - set(FACTORIES))


@pytest.mark.parametrize("key", sorted(FACTORIES))
def test_a_produced_result_satisfies_its_spec(key: str) -> None:
    """The producer's own result is valid: built through the spec, rebuilt by ``replace``, its arrays read-only."""
    obj = _instance(key)
    again = dataclasses.replace(obj)
    for f in dataclasses.fields(again):
        v = getattr(again, f.name)
        if isinstance(v, np.ndarray):
            assert not v.flags.writeable, (key, f.name)


def _count_mutations(fs: Any, value: Any) -> list[tuple[str, Any, type]]:
    """A count that is an array length (``integer(dim=...)``): another count is refused."""
    if isinstance(fs, R.ValueSpec) and fs.kind == "integer" and fs.args.get("dim"):
        return [("count not the arrays' length", int(value) + 1, ValueError)]
    return []


def _dropped_keys(spec: R.ResultSpec, obj: Any, field: str) -> list[tuple[str, Any, type]]:
    """A field of a :func:`fusion._results.same_keys` relation without its first key is refused."""
    out = []
    for relation in spec.relations:
        if field in getattr(relation, "fields", ()):
            value = getattr(obj, field)
            if len(value) > 1:
                first = next(iter(value))
                fewer = ({k: v for k, v in value.items() if k != first} if hasattr(value, "items")
                         else tuple(v for v in value if v != first))
                out.append(("a key dropped", fewer, ValueError))
    return out


CASES = [(key, field) for key in sorted(FACTORIES) for field in _cls(key).__result_spec__.fields]


@pytest.mark.parametrize(("key", "field"), CASES, ids=[f"{k}.{f}" for k, f in CASES])
def test_a_tampered_field_is_refused_naming_class_and_field(key: str, field: str) -> None:
    obj = _instance(key)
    spec = type(obj).__result_spec__
    name = type(obj).__name__
    value = getattr(obj, field)
    mutations = (_mutations(spec.fields[field], value, field in _shared_dims(spec))
                 + _count_mutations(spec.fields[field], value) + _dropped_keys(spec, obj, field))
    assert mutations, (key, field)
    for what, bad, exc in mutations:
        with pytest.raises(exc, match=re.escape(f"{name}.{field}")):
            dataclasses.replace(obj, **{field: bad})
            pytest.fail(f"{name}.{field} accepted {what}")


# The fuzz's own reproducers (S1-S20 of /work/tmp/fuzz24d/repro.py), one per class: each was accepted or crashed.
def test_fuzz24d_reproducers_are_refused_by_name() -> None:
    mc = _instance("time_registration.MonteCarlo")
    two = _tr().RegMethod.TWO_POINT
    for bad, field in [({"per_run": {**mc.per_run, two: np.array([np.nan, 1.0, 1.0, 1.0])}}, "per_run"),
                       ({"runs": -1}, "runs"), ({"sigma": np.nan}, "sigma"), ({"sigma": -1.0}, "sigma"),
                       ({"runs": 0}, "runs")]:
        with pytest.raises(ValueError, match=f"MonteCarlo.{field}"):
            dataclasses.replace(mc, **bad)
    fr = _instance("time_registration.FusionRuns")
    with pytest.raises(ValueError, match="FusionRuns.alone"):
        dataclasses.replace(fr, alone=-np.abs(fr.alone) - 1)
    eq = _instance("thermocouples.PairedStudy")
    with pytest.raises(ValueError, match="PairedStudy.failed"):
        dataclasses.replace(eq, failed={k: v for k, v in eq.failed.items() if k != "set"})
    sg = _instance("wavelet_sensors.SignalStudy")
    with pytest.raises(ValueError, match="SignalStudy.sigma"):
        dataclasses.replace(sg, sigma=sg.sigma[:-1])
    with pytest.raises(ValueError, match="SignalStudy.cases"):
        dataclasses.replace(sg, cases=dict(list(sg.cases.items())[1:]))
    m = _instance("wavelet_sensors.MechanismStudy")
    with pytest.raises(ValueError, match="MechanismStudy.err"):
        dataclasses.replace(m, err=dict(list(m.err.items())[1:]))
    with pytest.raises(ValueError, match="CorrelatedStudy.runs"):
        dataclasses.replace(_instance("lecture_correlated.CorrelatedStudy"), runs=0)
    with pytest.raises(ValueError, match="EstimatedCovarianceStudy.misstate"):
        dataclasses.replace(_instance("correlated_sensors.EstimatedCovarianceStudy"), misstate=np.inf)
    with pytest.raises(ValueError, match="AR1Study.k"):
        dataclasses.replace(_instance("lecture_weighting.estimators.AR1Study"), k=0)
    s23 = _instance("lecture_weighting.consistency.ConsistencyStudy")
    with pytest.raises(ValueError, match="ConsistencyStudy.pdet"):
        dataclasses.replace(s23, pdet=s23.pdet[:-1])
    with pytest.raises(ValueError, match="ConsistencyStudy.window"):
        dataclasses.replace(s23, window=(0, s23.samples + 1))


@settings(max_examples=25, deadline=None)
@given(st.integers(-3, 12), st.sampled_from(["per_run", "sigma", "seed"]), st.sampled_from([np.nan, np.inf, -1.0, 0.0]))
def test_monte_carlo_counts_and_values(runs: int, field: str, value: float) -> None:
    """Any count but the per-run arrays' length is refused (naming runs), any non-finite or negative value too."""
    mc = _instance("time_registration.MonteCarlo")
    if runs != mc.runs:
        with pytest.raises(ValueError, match="MonteCarlo.runs"):
            dataclasses.replace(mc, runs=runs)
    bad: Any = value
    if field == "per_run":
        bad = {k: np.where(np.arange(v.size) == 0, value, v) for k, v in mc.per_run.items()}
    if field == "seed":
        bad = int(value) if np.isfinite(value) else value
    if field == "per_run" and value == 0.0 or field == "seed" and value == 0.0:
        dataclasses.replace(mc, **{field: bad})  # a zero MSE and seed 0 are valid
        return
    with pytest.raises((ValueError, TypeError), match=f"MonteCarlo.{field}"):
        dataclasses.replace(mc, **{field: bad})


def test_lecture_weighting_relations_refuse_by_name() -> None:
    """The cross-field rules of the lecture-weighting results (spec26b): each refused naming the field, and the values
    their docstrings allow (NaN where undefined, a zero weight computed as -1e-15) accepted."""
    lu = _instance("lecture_weighting.estimators.LumvStudy")
    with pytest.raises(ValueError, match="LumvStudy.runs"):  # pairs one short, consistently: runs is not 2 x pairs
        dataclasses.replace(lu, pairs=lu.pairs - 1, pair_mean={k: v[:-1] for k, v in lu.pair_mean.items()},
                            pair_sq={k: v[:-1] for k, v in lu.pair_sq.items()})
    row = _instance("lecture_weighting.learning.LearningRow")
    assert np.isnan(row.corrected_mc)  # two sensors: no corrected learning, NaN as documented
    with pytest.raises(ValueError, match="LearningRow.corrected_mc"):
        dataclasses.replace(row, corrected_mc=np.inf)
    ls = _instance("lecture_weighting.learning.LearningStudy")
    n, (R, mean) = next(iter(ls.learned.items()))
    for bad in [(R, np.where(np.arange(mean.size).reshape(mean.shape) == 0, np.nan, mean)), (R[:-1], mean),
                (R, mean[:, :-1]), (-R, mean)]:
        with pytest.raises(ValueError, match=re.escape(f"LearningStudy.learned[{n}]")):
            dataclasses.replace(ls, learned={**ls.learned, n: bad})
    with pytest.raises(ValueError, match="LearningStudy.bias"):
        dataclasses.replace(ls, bias={**ls.bias, "(1, 2)": next(iter(ls.bias.values()))})
    with pytest.raises(ValueError, match="LearningStudy.last"):
        dataclasses.replace(ls, last=mean.shape[0] + 1)
    llc = _instance("lecture_weighting.learning.LearnedLimitCheck")
    for bad, field in [({"sets": llc.sets + 1}, "sets"), ({"above_best": llc.above_best_any + 1}, "above_best"),
                       ({"above_mean": llc.sets + 1}, "above_mean")]:
        with pytest.raises(ValueError, match=f"LearnedLimitCheck.{field}"):
            dataclasses.replace(llc, **bad)
    st_ = _instance("lecture_weighting.readings_benchmark.SeedStability")
    key = next(iter(st_.ranks))
    for bad, field in [({"ranks": {**st_.ranks, key: st_.ranks[key] + len(st_.methods)}}, "ranks"),
                       ({"methods": st_.methods[:-1]}, "ranks"), ({"n_stable": len(st_.scenarios) + 1}, "n_stable"),
                       ({"n_rev": st_.n_sig * (len(st_.seeds) - 1) + 1}, "n_rev")]:
        with pytest.raises(ValueError, match=re.escape(f"SeedStability.{field}")):
            dataclasses.replace(st_, **bad)
    rs = _instance("lecture_weighting.regime.RegimeStudy")
    scen = rs.scenarios[0]
    for bad, field in [({"change_at": rs.samples}, "change_at"), ({"forgetting": 1.0}, "forgetting"),
                       ({"curve": {**rs.curve, scen: dict(list(rs.curve[scen].items())[1:])}}, "curve"),
                       ({"n_nonpositive": {**rs.n_nonpositive, "elsewhere": 0}}, "n_nonpositive")]:
        with pytest.raises(ValueError, match=re.escape(f"RegimeStudy.{field}")):
            dataclasses.replace(rs, **bad)
    vc = _instance("lecture_weighting.regime.VarianceChangeStudy")
    change = vc.changes[0]
    with pytest.raises(ValueError, match=re.escape("VarianceChangeStudy.sq")):
        dataclasses.replace(vc, sq={**vc.sq, change: dict(list(vc.sq[change].items())[1:])})
    ps = _instance("lecture_weighting.belief.PerronStats")
    assert dataclasses.replace(ps, min_weight=-1e-15).min_weight == -1e-15  # an exact zero, computed
    with pytest.raises(ValueError, match="PerronStats.min_weight"):
        dataclasses.replace(ps, min_weight=1.5)
def test_spec26a_relations_and_integer_seeds() -> None:
    """The cross-field checks of spec26a's classes, and seeds kept as integers (a float copy would round 2**53 + 1)."""
    ff = _instance("two_sensor.weights.FruitFlySeeds")
    assert ff.seeds.dtype.kind == "i" and not ff.seeds.flags.writeable
    big = dataclasses.replace(ff, seeds=np.array([2**53 + 1, 2**64, 3], dtype=object))
    assert big.seeds[0] == 2**53 + 1
    for bad, exc in [(ff.seeds[:-1], ValueError), (ff.seeds - 5, ValueError), (ff.seeds.astype(float), TypeError)]:
        with pytest.raises(exc, match="FruitFlySeeds.seeds"):
            dataclasses.replace(ff, seeds=bad)
    st = _instance("fusion_networks.NetworkStudy")
    with pytest.raises(ValueError, match="NetworkStudy.truth"):
        dataclasses.replace(st, truth=np.asarray(st.truth) + 1.0)
    with pytest.raises(ValueError, match="NetworkStudy.covariances"):
        dataclasses.replace(st, covariances={**st.covariances, "ci_gaussian": -st.covariances["ci_gaussian"]})
    fs = _instance("two_sensor.study.FusionStudy")
    with pytest.raises(ValueError, match="FusionStudy.est"):
        dataclasses.replace(fs, est={**fs.est, "unknown": fs.est["ci_closed_form"]},
                            rmse={**fs.rmse, "unknown": fs.rmse["ci_closed_form"]})
    ns = _instance("two_sensor.study.NeesStudy")
    with pytest.raises(ValueError, match="NeesStudy.est"):
        dataclasses.replace(ns, est={k: v for k, v in ns.est.items() if k != "truth"})
    arch = _instance("two_sensor.architecture.ArchitectureStudy")
    with pytest.raises(ValueError, match="ArchitectureStudy.local_gain"):
        dataclasses.replace(arch, local_gain={**arch.local_gain, ("x", "y"): 1.0})
    target = _instance("range_bearing_scenario.SimulatedTarget")
    z = np.array(target.z)
    z[0, 0, 1] = 4.0
    with pytest.raises(ValueError, match="SimulatedTarget.z"):
        dataclasses.replace(target, z=z)
    seeds = _instance("wavelet_sensors.SeedStudy")
    first = next(iter(seeds.cases))
    case = {**seeds.cases[first], "weights": np.asarray(seeds.cases[first]["weights"])[:, :-1]}
    with pytest.raises(ValueError, match="SeedStudy.cases"):
        dataclasses.replace(seeds, cases={**seeds.cases, first: case})
    toy = _instance("two_mixtures.ToyMixtures")
    with pytest.raises(ValueError, match="ToyMixtures.b"):
        dataclasses.replace(toy, b=type(toy.b)(np.ones(1), np.zeros((1, 3)), np.eye(3)[None]))
