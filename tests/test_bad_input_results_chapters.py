"""Issue 35, class E: the chapter layer's result dataclasses refuse a bad field when built (``fusion._results``).

``dataclasses.replace`` is a result's public constructor: a tampered result (NaN, a negative count, a truncated
array, a wrong type) must be refused there, by a ValueError/TypeError naming ``Class.field``, not reach the chapter
function that takes it. The classes are enumerated from the source (AST): every frozen dataclass of
``fusion/book/chapters`` must declare a ``__result_spec__``, whether a public function takes it as an argument
(annotation or numpydoc type: *consumed*) or not (every result is rebuilt by ``dataclasses.replace`` and read by
the notebooks); each field of a real instance of every class is then replaced by the bad values of its spec's kind.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import importlib
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

import fusion
from fusion import _results as R
from _helpers import parsed

CHAPTERS = Path(fusion.__file__).resolve().parent / "book" / "chapters"


def _module(path: Path) -> str:
    rel = path.relative_to(CHAPTERS.parent.parent.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _dataclasses() -> dict[str, tuple[str, ast.ClassDef]]:
    """Every dataclass of the chapter layer: name -> (module, class node)."""
    out: dict[str, tuple[str, ast.ClassDef]] = {}
    for path in sorted(CHAPTERS.rglob("*.py")):
        for node in parsed(path).body:
            if isinstance(node, ast.ClassDef) and any("dataclass" in ast.unparse(d) for d in node.decorator_list):
                out[node.name] = (_module(path), node)
    return out


DATACLASSES = _dataclasses()


@functools.cache
def _consumers() -> dict[str, list[str]]:
    """Consumed class -> the public functions (module.function(argument)) of the package that take it.

    (Walks every module of the package: computed when a test asks, not at collection, which every worker repeats.)
    """
    names = set(DATACLASSES)
    found: dict[str, list[str]] = {}
    root = CHAPTERS.parent.parent
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(parsed(path)):
            if not isinstance(node, ast.FunctionDef) or node.name.startswith("_"):
                continue
            args = {a.arg: a for a in node.args.args + node.args.kwonlyargs}
            hits: dict[str, set[str]] = {}
            for arg, a in args.items():
                if a.annotation is not None:
                    hits.setdefault(arg, set()).update(set(re.findall(r"\w+", ast.unparse(a.annotation))) & names)
            for m in re.finditer(r"^\s*([\w, ]+) : (.*)$", ast.get_docstring(node) or "", re.M):
                for arg in (x.strip() for x in m.group(1).split(",")):
                    if arg in args:
                        hits.setdefault(arg, set()).update(set(re.findall(r"\w+", m.group(2))) & names)
            for arg, classes in hits.items():
                for cls in classes:
                    found.setdefault(cls, []).append(f"{path.stem}.{node.name}({arg})")
    return found


def _cls(name: str) -> type:
    module, _ = DATACLASSES[name]
    return getattr(importlib.import_module(module), name)


def _rng() -> np.random.Generator:
    return np.random.default_rng(0)


def _ofs() -> Any:
    from fusion.book.chapters import ofs

    return ofs


#: A real instance of each class with a spec, built small (the producers' own code).
FACTORIES: dict[str, Callable[[], Any]] = {
    "WeightStudy": lambda: _ofs().weight_study(0, 2),
    "FaultyMembership": lambda: _ofs().faulty_member_share(0, 2),
    "TableReproduction": lambda: _ofs().tables(),
    "AuditResult": lambda: _ofs().joint(),
    "Correction": lambda: importlib.import_module("fusion.book.chapters.ofs_audit").corrections()[5],
    "FairStudy": lambda: importlib.import_module("fusion.book.chapters.ofs_fair").fair_study(
        0, n_runs=3, n_samples=5, sizes=(0, 2), counts=(1,), spreads=(1,), opposite=(2,)),
    "GaussianChecks": lambda: importlib.import_module("fusion.book.chapters.chernoff").checks_study(1),
    "ToyStudy": lambda: importlib.import_module("fusion.book.chapters.chernoff.mixture").toy_study(_rng(), r=200),
    "FrameClouds": lambda: _frame_clouds(),
    "ShiftWeightDraws": lambda: importlib.import_module(
        "fusion.book.chapters.lecture_weighting.belief").shift_weight_draws(draws=5),
    "PluginExact": lambda: _lecture_correlated().x25,
    "Studies": lambda: _lecture_correlated(),
    "RegistrationStudy": lambda: _registration(),
    "TimingBenchmark": lambda: _ci().timing_benchmark(),
    "PrintedWeightFacts": lambda: _ci().printed_weight_facts(_two_scenarios(), 2, np.arange(2)),
    "WeightPair": lambda: _ci().weight_pair(_R, _R / 9, _Q, 2, seed=1, search_seed=2, fruit_fly_seeds=[3], runs=2,
                                           T=5.0),
    "IrReadings": lambda: _ci().ir_readings(0.1, 1, 3, duration=3.0),
    "LedgerStudies": lambda: _ledger_studies(),
    "PairedInputs": lambda: _part("PairedInputs"),
    "IrInputs": lambda: _part("IrInputs"),
    "LedgerInputs": lambda: _ledger(),
    # the classes no public function takes (issue 35 class E, second round): the smallest valid studies
    "DesignStudy": lambda: importlib.import_module("fusion.book.chapters.chernoff.guard").design_study(
        dataclasses.replace(_range_bearing(), n_particles=200), 6, runs=2, n_initial=300, workers=1),
    "IsVarianceStudy": lambda: importlib.import_module("fusion.book.chapters.chernoff.importance").is_variance_study(
        _rng(), R=5, replicates=20),
    "SigmaProblem": lambda: _instance("SigmaFirstOrderStudy").toy,
    "SigmaFirstOrderStudy": lambda: _chf("chernoff_first_order").sigma_first_order_study(_rng(), runs=2),
    "SwarmStudy": lambda: _chf("chernoff_scaling").swarm_study(3, ns=(2, 3), runs=2, r=20),
    "ScalingStudy": lambda: _chf("chernoff_scaling").scaling_study(4, rs=(20, 40), runs=2),
    "SnisDelta": lambda: next(iter(_instance("SnisBiasStudy").delta.values())),
    "ToyReference": lambda: _chf("chernoff_steps").toy_reference(),
    "SnisBiasStudy": lambda: _chf("chernoff_steps").snis_bias_study(_rng(), rs=(5, 10), total=2000),
    "DefensiveStudy": lambda: _chf("chernoff_steps").defensive_study(_rng(), runs=3, r=50),
    "ChosenBiasStudy": lambda: _chf("chernoff_steps").chosen_bias_study(_rng(), rs=(20, 40), total=2000),
    "ArchInputs": lambda: _part("ArchInputs"),
    "PeriodRuns": lambda: next(iter(_instance("LedgerStudies").fig6_periods.values())),
    "PairedClaimInputs": lambda: _part("PairedClaimInputs"),
    # the chapter's own (cached, computed by the notebook anyway: _ledger_studies says why)
    "PairedStudies": lambda: importlib.import_module("fusion.book.chapters.ci.studies").paired_study(),
    "NeesPerStep": lambda: _ci().nees_per_step(_rng(), *_ci().printed_covariances(), np.zeros(4), 25, 2),
    "SplitExactness": lambda: _ci().split_ci_exactness(*_ci().printed_covariances()[:2], 1.0, 25),
    "LegClaimInputs": lambda: _instance("StraightLeg").claim_inputs(),
    "StraightLeg": lambda: _straight_leg(),
    "WeightClaimInputs": lambda: _ci().weight_claim_inputs(   # the second pair at ANISO_R (fuzz 24c MM)
        _instance("WeightPair"), _ci().weight_pair(*_ci().ANISO_R, _Q, 2, seed=4, search_seed=2, fruit_fly_seeds=[3],
                                                   runs=2, T=5.0), np.array([3.0, 1.0, 2.0])),
    "Cell": lambda: _cell(),
    "LumvReading": lambda: _lumv_reading(),
    "MembershipStudy": lambda: _ofs().membership_study(0, 2),
    "RobustnessReading": lambda: _robustness_reading(),
}


def _chf(module: str) -> Any:
    return importlib.import_module(f"fusion.book.chapters.{module}")


def _range_bearing() -> Any:
    from fusion.scenarios.range_bearing import RangeBearingScenario

    return RangeBearingScenario()


def _straight_leg() -> Any:
    """The straight-leg floors beside a small fusion study at T = 2 s (the chapter tests' scenario, 2 runs)."""
    from fusion.scenarios import two_sensor

    sc = two_sensor.two_sensor_scenario(_R, _R, _Q, np.random.default_rng(0), runs=2, T=2.0)
    w = np.full(sc.t.size, 0.5)
    return _ci().straight_leg(two_sensor.fusion_study(sc, w, w, published_omega=0.5), 2.0, 150.0)


def _cell() -> Any:
    from fusion.book.chapters.lecture_wavelets import verdicts
    from fusion.scenarios import wavelet_sensors as ws

    sg = ws.signal_study(length=64, runs=2, level=2, signals=(ws.Signal.TWO_TONES,), modes=("hard",),
                         normalisers=("max",))
    return verdicts.cell(sg, None, next(iter(sg.cases)))


def _lumv_reading() -> Any:
    """A reading whose mean and MSE exist (the oracle's: every field a bool)."""
    from fusion.book.chapters.lecture_weighting import estimators
    from fusion.scenarios.lecture_weighting import estimators as sc

    return next(iter(estimators.lumv_readings(sc.lumv_study(runs=40, chunk=20)).values()))


def _robustness_reading() -> Any:
    from fusion.book.chapters import time_registration_robustness as trr
    from fusion.scenarios import time_registration as sc

    return trr.robustness_readings(5.0, sc.instants()[1])[0]


def _ledger_studies() -> Any:
    """The chapter's own ledger studies, at the notebook's seed and run count (:data:`LEDGER_RUNS`).

    A tampered-field test needs any valid instance, not a given run count: these are the studies chapter 05's
    notebook and ``tests/test_ci_book_chapter.py`` compute in every run anyway, so the run's study cache serves
    them. At ``runs=3`` they were a computation of their own (about 12 CPU-s, nearly all of it the architecture
    studies' per-step covariance recursion, which does not shrink with the runs)."""
    return _ci().ledger_studies()


def _part(name: str) -> Any:
    """A part of the chapter's ledger studies, from the same values (:func:`ledger_studies` shares them)."""
    cls, whole = getattr(_ci(), name), _instance("LedgerStudies")
    return cls(**{f.name: getattr(whole, f.name) for f in dataclasses.fields(cls)})


def _ledger() -> Any:
    """A LedgerInputs of the chapter tests' synthetic entries (tests/test_ci_book_chapter.py), through ledger_inputs."""
    from fusion.scenarios import two_sensor
    from test_ci_book_chapter import _ledger_inputs

    sc = two_sensor.two_sensor_scenario(_R, _R, _Q, np.random.default_rng(0), runs=3, T=5.0)
    w = np.full(sc.t.size, 0.5)
    return _ci().ledger_inputs(**_ledger_inputs(two_sensor.fusion_study(sc, w, w, published_omega=0.5), -1.0))

_R, _Q = np.diag([150.0**2, 150.0**2]), np.diag([100.0] * 4)


def _ci() -> Any:
    return importlib.import_module("fusion.book.chapters.ci")


def _two_scenarios() -> tuple[Any, Any]:
    from fusion.scenarios import two_sensor

    return (two_sensor.two_sensor_scenario(_R, _R, _Q, np.random.default_rng(2), runs=2, T=5.0),
            two_sensor.two_sensor_scenario(*_ci().ANISO_R, _Q, np.random.default_rng(3), runs=2, T=5.0))


def _lecture_correlated() -> Any:
    return importlib.import_module("fusion.book.chapters.lecture_correlated.records").cached_studies(runs=20)


def _registration() -> Any:
    from fusion.book.chapters.time_registration_ledger import studies
    from fusion.scenarios import time_registration as sc

    t1, t2 = sc.instants()
    return studies.study(t1, t2, studies.PRIMARY_SIGMA, 3, 1)


def _frame_clouds() -> Any:
    from fusion.book.chapters import chernoff_scaling as cs
    from fusion.scenarios.range_bearing import RangeBearingScenario

    return cs.frame_clouds(RangeBearingScenario(), seed=0, runs=1, run=0, frame=1)


SPECCED = sorted(name for name in DATACLASSES if getattr(_cls(name), "__result_spec__", None) is not None)


def test_the_enumeration_finds_the_consumed_classes() -> None:
    """The AST enumeration is not empty and finds the classes issue 35 named (so a broken parser cannot pass)."""
    assert len(DATACLASSES) >= 40
    assert {"TableReproduction", "AuditResult", "FairStudy", "WeightStudy", "Correction"} <= set(_consumers())
    assert len(_consumers()) >= 15


def test_every_chapter_dataclass_declares_a_spec() -> None:
    """Every dataclass of the chapter layer, consumed or not (a consumed one is named with its consumers)."""
    missing = sorted(c for c in DATACLASSES if c not in SPECCED)
    assert not missing, {c: _consumers().get(c, "not consumed") for c in missing}


def test_every_specced_class_has_a_factory_and_validates_when_built() -> None:
    assert set(SPECCED) <= set(FACTORIES), sorted(set(SPECCED) - set(FACTORIES))
    for name in SPECCED:   # the shared rule, or a __post_init__ that runs it first (__wrapped__: PairedStudies)
        post = _cls(name).__post_init__
        assert getattr(post, "__wrapped__", post) in (R.validated_post_init, R.shared_post_init), name


def _mutations(fs: Any, value: Any, shared: bool) -> list[tuple[str, Any, type]]:
    """Bad values of a field of spec ``fs`` (currently ``value``): (what, value, expected exception)."""
    wrong = [("wrong type", "x", TypeError)]
    if isinstance(fs, R.ArraySpec):
        out = list(wrong)
        arr = np.array(value, dtype=float)
        if arr.size:
            bad = arr.copy()
            bad.flat[0] = np.inf if fs.nan else np.nan
            out.append(("not finite", bad, ValueError))
        if arr.ndim and arr.shape[0] > 1 and (isinstance(fs.dims[0], int) or shared):
            out.append(("truncated", arr[:-1], ValueError))
        if fs.bounds is not None and arr.size:
            bad = arr.copy()
            bad.flat[0] = fs.bounds[0] - 1.0 if np.isfinite(fs.bounds[0]) else fs.bounds[1] + 1.0
            out.append(("out of bounds", bad, ValueError))
        return out
    if isinstance(fs, R.NumbersSpec) and fs.keys is None:
        out = [("wrong type", "x", TypeError), ("bool", True, TypeError),
               ("not finite", float("inf") if fs.nan else float("nan"), ValueError)]  # NaN allowed where nan=True
        if fs.nonnegative or fs.positive:
            out.append(("negative", -1.0, ValueError))
        return out
    if isinstance(fs, R.NestedSpec):
        return wrong
    if isinstance(fs, R.ValueSpec):
        kind, args = fs.kind, fs.args
        if kind == "integer":
            out = [("wrong type", "x", TypeError), ("float", 1.5, TypeError), ("bool", True, TypeError)]
            if args["minimum"] is not None:
                out.append(("negative count", args["minimum"] - 5, ValueError))
            return out
        if kind == "mask":
            out = [("wrong type", "x", TypeError), ("not bool", np.asarray(value, dtype=float), TypeError)]
            if np.ndim(value) and np.shape(value)[0] > 1 and (isinstance(args["dims"][0], int) or shared):
                out.append(("truncated", np.asarray(value)[:-1], ValueError))
            return out
        if kind in ("flag", "text"):
            return [("wrong type", 5, TypeError)] + ([("not a choice", "?", ValueError)] if args.get("choices") else [])
        if kind == "table":
            return wrong + ([("no columns", pd.DataFrame(), ValueError)] if args["columns"] else [])
        if kind == "instance":
            return [] if str in args["classes"] else wrong
        if kind == "tuple":
            out = [("wrong type", "x", TypeError)]
            if ("items" in args or args["count"] is not None) and len(value):
                out.append(("truncated", tuple(value)[:-1], ValueError))
            item = args.get("item") or args["items"][0]
            if isinstance(item, R.NumbersSpec) and len(value):
                out.append(("NaN", (float("nan"), *tuple(value)[1:]), ValueError))
            return out
        if kind == "dict":
            out = [("wrong type", "x", TypeError)]
            inner = args["value"]
            if len(value):
                k0 = next(iter(value))
                for what, bad, exc in _mutations(inner, value[k0], shared=False):
                    out.append((f"item {what}", {**dict(value), k0: bad}, exc))
            return out
    return wrong


def _shared_dims(spec: R.ResultSpec) -> set[str]:
    """Field names whose first array dimension is bound by another field too (a truncation must be refused)."""
    seen: dict[Any, list[str]] = {}
    for name, fs in spec.fields.items():
        dims: tuple[Any, ...] = ()
        if isinstance(fs, R.ArraySpec):
            dims = fs.dims
        elif isinstance(fs, R.ValueSpec) and fs.kind == "table" and fs.args["rows"] is not None:
            dims = (fs.args["rows"],)
        elif isinstance(fs, R.ValueSpec) and fs.kind == "mask":
            dims = fs.args["dims"]
        for d in dims:
            if isinstance(d, str):
                seen.setdefault(d, []).append(name)
    out = set()
    for name, fs in spec.fields.items():
        dims = fs.dims if isinstance(fs, R.ArraySpec) else (
            fs.args["dims"] if isinstance(fs, R.ValueSpec) and fs.kind == "mask" else ())
        if dims and isinstance(dims[0], str) and len(seen[dims[0]]) > 1:
            out.add(name)
    return out


CASES = [(name, field) for name in SPECCED for field in _cls(name).__result_spec__.fields]
_INSTANCES: dict[str, Any] = {}


def _instance(name: str) -> Any:
    if name not in _INSTANCES:
        _INSTANCES[name] = FACTORIES[name]()
    return _INSTANCES[name]


@pytest.mark.parametrize(("name", "field"), CASES, ids=[f"{n}.{f}" for n, f in CASES])
def test_a_tampered_field_is_refused_naming_class_and_field(name: str, field: str) -> None:
    obj = _instance(name)
    spec = type(obj).__result_spec__
    mutations = _mutations(spec.fields[field], getattr(obj, field), field in _shared_dims(spec))
    assert mutations, (name, field)
    for what, bad, exc in mutations:
        with pytest.raises(exc, match=re.escape(f"{name}.{field}")):
            dataclasses.replace(obj, **{field: bad})
            pytest.fail(f"{name}.{field} accepted {what}")


@pytest.mark.parametrize("name", SPECCED)
def test_a_real_instance_rebuilds_and_is_read_only(name: str) -> None:
    """The producers' own results satisfy their spec (``replace`` rebuilds them), and the rebuilt arrays are
    read-only (caches may hand the object out again): copies, or for a bundle (``shared_post_init``) the same arrays."""
    obj = _instance(name)
    again = dataclasses.replace(obj)
    shared = type(obj).__post_init__ is R.shared_post_init
    for f in dataclasses.fields(again):
        v = getattr(again, f.name)
        if isinstance(v, np.ndarray):
            assert not v.flags.writeable, (name, f.name)
            assert np.shares_memory(v, getattr(obj, f.name)) == shared, (name, f.name)


def test_the_spec_kinds_of_the_chapter_layer() -> None:
    """The kinds added for the chapter layer (fusion._results): integer, flag, text, table, instance, tuple, dict,
    bounds; each refuses its bad values naming the field, and a container's item by its key or index."""

    @dataclasses.dataclass(frozen=True)
    class Toy:
        n: int
        ok: bool
        kind: str
        t: pd.DataFrame
        pair: tuple
        errs: dict
        p: float
        opt: Any = None

        __result_spec__ = R.ResultSpec({
            "n": R.integer(1), "ok": R.flag(), "kind": R.text("a", "b"), "t": R.table("x", rows="k"),
            "pair": R.tuple_of(R.number(), R.integer(0)), "errs": R.dict_of(R.array("k", bounds=(0.0, 1.0))),
            "p": R.number(bounds=(0.0, 1.0)), "opt": R.instance(pd.DataFrame, optional=True)})
        __post_init__ = R.validated_post_init

    good = dict(n=2, ok=True, kind="a", t=pd.DataFrame({"x": [1, 2]}), pair=[0.5, 3], errs={"m": [0.1, 0.2]}, p=0.5)
    toy = Toy(**good)
    assert toy.pair == (0.5, 3) and toy.errs["m"].tolist() == [0.1, 0.2] and not toy.errs["m"].flags.writeable
    bad: list[tuple[dict[str, Any], type, str]] = [
        ({"n": 0}, ValueError, "Toy.n"), ({"n": 2.0}, TypeError, "Toy.n"), ({"ok": 1}, TypeError, "Toy.ok"),
        ({"kind": "c"}, ValueError, "Toy.kind"), ({"t": pd.DataFrame({"y": [1, 2]})}, ValueError, "Toy.t"),
        ({"t": pd.DataFrame({"x": [1]})}, ValueError, "Toy.errs['m']"), ({"pair": (0.5,)}, ValueError, "Toy.pair"),
        ({"pair": (np.nan, 3)}, ValueError, "Toy.pair[0]"), ({"pair": (0.5, -1)}, ValueError, "Toy.pair[1]"),
        ({"errs": {"m": [0.1, 2.0]}}, ValueError, "Toy.errs['m']"), ({"errs": {1: [0.1, 0.2]}}, TypeError, "Toy.errs"),
        ({"errs": {}}, ValueError, "Toy.errs"), ({"p": 1.5}, ValueError, "Toy.p"), ({"opt": 3}, TypeError, "Toy.opt"),
    ]
    for change, exc, label in bad:
        with pytest.raises(exc, match=re.escape(label)):
            Toy(**{**good, **change})
