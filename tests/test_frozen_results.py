"""A frozen result cannot be changed after its checks (fuzz 19, class G and the main package's results).

One mechanism (``fusion._frozen``): arrays read-only copies, dicts read-only mappings, lists tuples, nested results
frozen by their own class, and DataFrame fields (the ``table`` kind of a ``fusion._results`` spec, and fields of a
``frozen_arrays`` class annotated as a DataFrame) stored as a private copy and handed out as a copy on each read
(``fusion._frozen.FrameField``), so that an in-place edit of a table read from the object never reaches it.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from collections.abc import Mapping

import numpy as np
import pandas as pd
import pytest

from fusion._frozen import FrameField, ReadOnlyMapping, frozen_arrays
from fusion._results import ResultSpec, table, validated_post_init


@dataclasses.dataclass(frozen=True)
class _Specced:
    """A validated result with a table field (the ``table`` spec kind) and a defaulted one."""

    frame: pd.DataFrame
    extra: pd.DataFrame | None = None

    __result_spec__ = ResultSpec({"frame": table("a")})
    __post_init__ = validated_post_init


@dataclasses.dataclass(frozen=True)
@frozen_arrays
class _Decorated:
    """A ``frozen_arrays`` result with an array, a dict, a list and a DataFrame field."""

    x: np.ndarray
    d: Mapping[str, float]
    items: tuple[int, ...]
    frame: pd.DataFrame


def _frame() -> pd.DataFrame:
    return pd.DataFrame({"a": [1.0, 2.0], "b": ["x", "y"]})


@pytest.mark.parametrize("build", [lambda df: _Specced(df), lambda df: _Decorated(np.ones(2), {}, [], df)],
                         ids=["table spec", "frozen_arrays"])
def test_a_table_field_is_a_private_copy_handed_out_as_copies(build) -> None:
    df = _frame()
    obj = build(df)
    assert isinstance(type(obj).__dict__["frame"], FrameField)
    del df["a"]                                          # the caller's frame is not the object's (G1)
    assert list(obj.frame.columns) == ["a", "b"]
    read = obj.frame
    del read["b"]                                        # an edit of a read is an edit of a copy (G2)
    read.iloc[0, 0] = -777.0                             # (G3)
    assert list(obj.frame.columns) == ["a", "b"] and obj.frame.iloc[0, 0] == 1.0
    assert obj.frame is not obj.frame
    for how, c in (("copy", copy.copy(obj)), ("deepcopy", copy.deepcopy(obj)),
                   ("pickle", pickle.loads(pickle.dumps(obj))), ("replace", dataclasses.replace(obj))):
        pd.testing.assert_frame_equal(c.frame, _frame().drop(columns=[]), obj=how)
        read = c.frame
        read.iloc[0, 0] = -1.0
        assert c.frame.iloc[0, 0] == 1.0, how
    with pytest.raises(dataclasses.FrozenInstanceError):
        obj.frame = df  # type: ignore[misc]


def test_a_table_field_keeps_its_default_and_its_checks() -> None:
    assert _Specced(_frame()).extra is None
    assert [f.default for f in dataclasses.fields(_Specced)] == [dataclasses.MISSING, None]
    with pytest.raises(ValueError, match=r"_Specced\.frame must have the columns"):
        _Specced(pd.DataFrame({"b": [1.0]}))
    with pytest.raises(TypeError, match=r"_Specced\.frame"):
        _Specced({"a": [1.0]})  # type: ignore[arg-type]


def test_a_frozen_arrays_result_freezes_its_containers() -> None:
    src = np.ones(3)
    obj = _Decorated(src, {"k": 1.0}, [1, 2], _frame())
    assert not obj.x.flags.writeable and src.flags.writeable
    assert isinstance(obj.d, ReadOnlyMapping) and obj.items == (1, 2)
    with pytest.raises(TypeError):
        obj.d["k"] = 2.0  # type: ignore[index]


def _same(a: object, b: object) -> bool:
    """Equal values (tables cell by cell, NaN equal to NaN)."""
    if isinstance(a, (pd.DataFrame, pd.Series)):
        return a.equals(b)
    return a == b or (a != a and b != b)


# -- fuzz 19 G1-G4: the chapter layer's results --------------------------------------------------------------------


def test_g1_a_table_given_to_replace_then_edited_does_not_reach_the_result() -> None:
    """G1: ``replace(joint(), table=df)``, then ``df.drop(columns=['program'], inplace=True)``: summary still works."""
    from fusion.book.chapters import ofs, ofs_audit

    j = ofs.joint()
    df = j.table.copy()
    j2 = dataclasses.replace(j, table=df)
    del df["program"]  # in place (the fuzzer's drop(columns=..., inplace=True))
    assert "program" in j2.table.columns
    assert _same(ofs_audit.summary(j2), ofs_audit.summary(j))


def test_g2_g3_edits_of_a_result_table_do_not_reach_the_result() -> None:
    """G2: ``j.full.drop(columns=['kind'], inplace=True)``; G3: ``t.table2.iloc[0, 0] = x`` (every table field)."""
    from fusion.book.chapters import ofs, ofs_audit

    j = ofs.joint()
    before = ofs_audit.full_explanation(j)
    del j.full["kind"]
    assert "kind" in j.full.columns and _same(ofs_audit.full_explanation(j), before)
    for name in ("table", "full", "same_sets"):
        read = getattr(j, name)
        del read[read.columns[0]]
        assert len(getattr(j, name).columns) == len(read.columns) + 1, name
    t = ofs.tables()
    for name in ("table2", "table3", "totals", "audit", "alpha"):
        read = getattr(t, name)
        first = read.iloc[0, 0]
        read.iloc[0, 0] = "edited" if isinstance(first, str) else -777.0
        assert read.iloc[0, 0] != first and _same(getattr(t, name).iloc[0, 0], first), name


def test_g4_a_nested_result_of_a_produced_result_is_read_only() -> None:
    """G4: ``weight_pair(...).fruit_fly_seeds.fruit_fly_x[0] = nan`` is refused (FruitFlySeeds freezes its arrays)."""
    from fusion.book.chapters import ci

    R_, Q_ = np.diag([150.0**2, 150.0**2]), np.diag([100.0] * 4)
    wp = ci.weight_pair(R_, R_ / 9, Q_, 2, seed=1, search_seed=2, fruit_fly_seeds=[3], runs=2, T=5.0)
    seeds = wp.fruit_fly_seeds
    for f in dataclasses.fields(seeds):
        value = getattr(seeds, f.name)
        if isinstance(value, np.ndarray):
            with pytest.raises(ValueError, match="read-only"):
                value.flat[0] = np.nan


# -- the main package's results (fuzz 19 "Debatable": mut.py) -----------------------------------------------------


def _writable(obj: object, path: str, out: list[str], seen: set[int]) -> None:
    """Every path in ``obj`` to a writable array, a dict, a list or a DataFrame held by the object itself."""
    if id(obj) in seen:
        return
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        if obj.flags.writeable:
            out.append(path)
        if obj.dtype == object:
            for i, x in enumerate(obj.ravel()[:5]):
                _writable(x, f"{path}[{i}]", out, seen)
    elif isinstance(obj, (list, dict, set)):
        out.append(f"{path} ({type(obj).__name__})")
    elif isinstance(obj, Mapping):
        for k, v in obj.items():
            _writable(v, f"{path}[{k!r}]", out, seen)
    elif isinstance(obj, tuple):
        for i, v in enumerate(obj):
            _writable(v, f"{path}[{i}]", out, seen)
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        if not type(obj).__dataclass_params__.frozen:
            out.append(f"{path} (not frozen)")
            return
        for f in dataclasses.fields(obj):
            value = getattr(obj, f.name)
            if isinstance(value, (pd.DataFrame, pd.Series)) and not isinstance(type(obj).__dict__.get(f.name),
                                                                              FrameField):
                out.append(f"{path}.{f.name} (unprotected {type(value).__name__})")
            _writable(value, f"{path}.{f.name}", out, seen)


#: The registry calls whose results fuzz 19 found editable (mut.py, 25 of 303 calls: writable arrays, dicts or lists
#: in ReadingsFusion, EpochFusion, Reconstruction, FusedEstimate, ClusterFusion, ChernoffGaussian, MixtureFusion,
#: FusedTracks, ConsistencyStudy, EstimatedCovarianceStudy, PairedStudy, FusionRuns, FruitFlySeeds, BenchmarkResult).
FUZZ19_PRODUCERS = (
    "fusion.readings.fusion_set.arithmetic_mean", "fusion.readings.fusion_set.optimal_fusion_set",
    "fusion.readings.fusion_set.support_degree", "fusion.readings.fusion_set.fusion_set_weights",
    "fusion.readings.fusion_set.fuse_epochs", "fusion.readings.fusion_set.belief_degree",
    "fusion.readings.fusion_set.binary_deletion", "fusion.readings.wavelet.reconstruct",
    "fusion.readings.wavelet.fuse_denoised", "fusion.estimates.ci.covariance_intersection",
    "fusion.estimates.ci.convex_combination", "fusion.estimates.ci.split_covariance_intersection",
    "fusion.data.as_printed.wang2024_eqs_1_2", "fusion.estimates.fuzzy_cluster.fuzzy_cluster_fusion",
    "fusion.estimates.chernoff.chernoff_fuse_gaussians", "fusion.estimates.chernoff.gaussian_chernoff_weights",
    "fusion.estimates.chernoff.fuse_mixtures", "fusion.filtering.tracks.fuse_tracks",
    "fusion.scenarios.lecture_weighting.consistency.consistency_study",
    "fusion.scenarios.correlated_sensors.estimated_covariance_study", "fusion.scenarios.thermocouples.paired_study",
    "fusion.scenarios.time_registration.fusion_runs", "fusion.scenarios.two_sensor.fruit_fly_over_seeds",
    "fusion.scenarios.two_sensor.printed_fruit_fly_over_seeds", "fusion.book.benchmarks.load_benchmark",
)


@pytest.mark.parametrize("name", FUZZ19_PRODUCERS)
def test_a_produced_result_holds_nothing_editable(name: str) -> None:
    """The bad-input registry's valid call of each producer: no writable array, dict, list or unprotected table
    anywhere in the result (nested results included), also in its copies; an edit is refused."""
    from test_bad_input import CALLABLES, REG

    result = CALLABLES[name](**{k: a.value for k, a in REG[name].items()})
    assert dataclasses.is_dataclass(result) and type(result).__dataclass_params__.frozen
    for how, obj in (("result", result), ("deepcopy", copy.deepcopy(result)),
                     ("pickle", pickle.loads(pickle.dumps(result)))):
        found: list[str] = []
        _writable(obj, type(obj).__name__, found, set())
        assert not found, (how, found)
    arrays = [getattr(result, f.name) for f in dataclasses.fields(result)
              if isinstance(getattr(result, f.name), np.ndarray) and getattr(result, f.name).size]
    for a in arrays:
        with pytest.raises(ValueError, match="read-only"):
            a.flat[0] = a.flat[0]


def test_the_sweep_finds_what_fuzz_19_found() -> None:
    """The walk of the test above is not vacuous: a plain frozen dataclass with a writable array, a dict, a list and
    an unprotected DataFrame is reported four times."""

    @dataclasses.dataclass(frozen=True)
    class Plain:
        x: np.ndarray
        d: dict
        items: list
        frame: pd.DataFrame

    found: list[str] = []
    _writable(Plain(np.ones(2), {}, [], _frame()), "Plain", found, set())
    assert len(found) == 4, found


def test_a_shared_bundle_freezes_in_place_and_shares_its_study() -> None:
    """``@frozen_arrays(shared=True)`` (a bundle of a study's values, ``PairedClaimInputs``): the same arrays, made
    read-only, in a read-only mapping; a plain ``frozen_arrays`` result owns copies."""

    @dataclasses.dataclass(frozen=True)
    @frozen_arrays(shared=True)
    class Bundle:
        d: Mapping[str, np.ndarray]

    a = np.ones(3)
    b = Bundle({"a": a})
    assert b.d["a"] is a and not a.flags.writeable and isinstance(b.d, ReadOnlyMapping)
    c = np.ones(3)
    assert not np.shares_memory(_Decorated(c, {}, [], _frame()).x, c) and c.flags.writeable


def test_the_chapter_bundle_shares_the_cached_study() -> None:
    """PairedClaimInputs (claim_inputs of the cached PairedStudies) holds the study's own read-only arrays."""
    from fusion.book.chapters import ci

    st = ci.paired_study()
    inputs = st.claim_inputs()
    assert all(inputs.paired[k] is st.paired[k] and not st.paired[k].flags.writeable for k in st.paired)


def test_fresh_freezes_a_producer_s_own_arrays_in_place() -> None:
    """``fusion._frozen.fresh`` (the fusion-set producers' constructor, built 40,200 times in chapter 02's
    shift_weight_draws): the producer's arrays made read-only in place, dicts and lists frozen, defaults filled."""
    from fusion._frozen import fresh
    from fusion.readings import fusion_set as fs

    w = np.full(3, 1 / 3)
    r = fresh(fs.ReadingsFusion, value=1.0, weights=w, members=np.ones(3, bool), method="mean")
    assert r.weights is w and not w.flags.writeable
    obj = fresh(_Decorated, x=np.ones(2), d={"k": 1.0}, items=[1], frame=_frame())
    assert isinstance(obj.d, ReadOnlyMapping) and obj.items == (1,)
    read = obj.frame
    read.iloc[0, 0] = -1.0
    assert obj.frame.iloc[0, 0] == 1.0
    assert fresh(_Specced, frame=_frame()).extra is None
    with pytest.raises(TypeError, match="misses the field frame"):
        fresh(_Specced)
    single = fs.belief_degree(np.array([1.0, 1.1, 0.9, 5.0]))
    assert not single.weights.flags.writeable and not single.members.flags.writeable
