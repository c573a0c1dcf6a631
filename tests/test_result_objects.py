"""Result objects that a later public function takes as input are validated where they are built (issue 35).

``dataclasses.replace`` is their public constructor: every field of every such class (one level of nested
results included: ``LocalTrack.gains.P``, ``Scenario.tracks[0].est``), tampered with (NaN or an infinity at
any entry, one step short, one dimension too many), is refused by a ValueError naming the field; a valid
``replace`` (the same values, copied) is accepted and its consumer gives bit-for-bit the same result.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
import re
from collections.abc import Mapping

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fusion._results import trusted
from fusion.filtering import kalman as kf
from fusion.filtering import tracks as tk
from fusion.scenarios import infrared_radar as ir
from fusion.scenarios import range_bearing as rb
from fusion.scenarios import two_sensor as ts
from fusion.scenarios.lecture_weighting import belief as bl
from fusion.readings import consistency as cs
from fusion.readings import weighting as wt

Q = np.kron(np.eye(2), [[0.25, 0.5], [0.5, 1.0]])
R1, R2 = np.diag([100.0**2, 100.0**2]), np.diag([50.0**2, 50.0**2])
MODEL = kf.cv_model(1.0)
Z = np.random.default_rng(3).normal(scale=100.0, size=(2, 6, 2))
X0 = np.zeros((2, 4))


def _track(z: np.ndarray, R: np.ndarray) -> tk.LocalTrack:
    return tk.local_track(z, MODEL.F, MODEL.H, Q, R, X0, np.diag([0.0, 1e4, 0.0, 1e4]), np.diag([R[0, 0], 0.0, R[1, 1], 0.0]))


def _examples() -> dict[str, tuple[object, object]]:
    """Per result class: a valid object and its consumer (a public function of it alone)."""
    gains = kf.gain_sequence(MODEL.F, MODEL.H, Q, R1, np.diag([1e4] * 4), 6)
    a, b = _track(Z, R1), _track(Z[::-1].copy(), R2)
    sc = ts.two_sensor_scenario(R1, R2, Q, np.random.default_rng(1), runs=2, T=20.0)
    sim = ir.simulate(np.random.default_rng(2), runs=2, T=0.5, duration=3.0)
    ct = ir.cartesian_tracks(sim)
    study = bl.belief_parameter_study(snapshots=4, params=(0.5, 1.0, 2.0), grid=(0.5, 2.0))
    rb_sc = rb.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100, n_components=2)
    run = rb.monte_carlo(rb_sc, 1, 1, all_nodes_first=False)[0]
    readings = 5.0 + np.random.default_rng(4).normal(size=(2, 6, 3))  # a batch of two problems: the "..." form
    fused = wt.awf(readings, guard="none")  # weights of both signs
    checked = cs.consistency_awf(readings, 1.0)
    return {
        "AWFResult": (fused, lambda r: cs.ConsistentAWF(awf=r, mask=np.ones(r.weights.shape, dtype=bool))),
        "ConsistentAWF": (checked, lambda c: dataclasses.replace(c.awf)),
        "GainSequence": (gains, lambda g: (kf.filter_runs(Z, g, X0), kf.split_covariances(g, Q, R1, np.diag([0.0, 1e4] * 2),
                                                                                            np.diag([1e4, 0.0] * 2)))),
        "LocalTrack": (a, lambda t: [tk.fuse_tracks(t, b, rule) for rule in tk.RULES]),
        "Scenario": (sc, ts.fusion_study),
        "Truth": (ir.truth(T=0.5, duration=3.0), lambda p: ir.many_scan_bound(p, 1e-4, 0.02, 5.0)),
        "IrRadarRuns": (sim, ir.rule_errors),
        "CartesianTracks": (ct, lambda c: ir.cartesian_errors(sim, c)),
        "BeliefParameterStudy": (study, lambda s: [bl.belief_spread(s, k, s.grid) for k in bl.BELIEF_KINDS]),
        "TrackingRun": (run, lambda r: ([rb.position_sq_errors([r], k) for k in r.estimates],
                                        [rb.nees_per_frame([r], k) for k in r.covariances], rb.min_local_ess([r]))),
    }


EXAMPLES = _examples()


def _leaves(obj: object, path: tuple = ()) -> list[tuple]:
    """Paths to every float array or float of a result, one level of nested results (or a tuple of them) down."""
    out = []
    spec = type(obj).__result_spec__.fields  # type: ignore[attr-defined]
    for f in dataclasses.fields(obj):  # type: ignore[arg-type]
        if f.name not in spec:  # a record the class does not validate (TrackingRun's per-variant diagnostics)
            continue
        v = getattr(obj, f.name)
        here = path + (("field", f.name),)
        if isinstance(v, np.ndarray):
            out.append(here)
        elif isinstance(v, float):
            out.append(here)
        elif isinstance(v, Mapping):
            out += [here + (("key", k),) for k in v]
        elif dataclasses.is_dataclass(v) and len(path) < 2:
            out += _leaves(v, here)
        elif isinstance(v, tuple) and v and all(dataclasses.is_dataclass(x) for x in v):
            for i, x in enumerate(v):
                out += _leaves(x, here + (("index", i),))
    return out


LEAVES = [(cls, leaf) for cls, (obj, _) in EXAMPLES.items() for leaf in _leaves(obj)]


def _rebuild(obj: object, path: tuple, fn) -> object:
    """``obj`` rebuilt with ``dataclasses.replace`` (its public constructor), the leaf at ``path`` replaced by ``fn(leaf)``."""
    (kind, key), rest = path[0], path[1:]
    value = getattr(obj, key)
    if rest and rest[0][0] == "key":  # a dict field: replace the dict with the entry changed
        new = dict(value)
        new[rest[0][1]] = fn(value[rest[0][1]])
        return dataclasses.replace(obj, **{key: new})
    if rest and rest[0][0] == "index":
        i, inner = rest[0][1], rest[1:]
        return dataclasses.replace(obj, **{key: tuple(_rebuild(x, inner, fn) if j == i else x for j, x in enumerate(value))})
    return dataclasses.replace(obj, **{key: fn(value) if not rest else _rebuild(value, rest, fn)})


def _field_name(path: tuple) -> str:
    """The name a refusal must mention: the innermost field (for a dict entry, the dict's field)."""
    return [key for kind, key in path if kind == "field"][-1]


def _mutated(value: object, how: str, where: float, sign: float) -> object:
    if isinstance(value, float):
        return np.nan if how == "nan" else sign * np.inf
    arr = np.array(value, dtype=float, copy=True)
    if how in ("nan", "inf"):
        arr.reshape(-1)[int(where * (arr.size - 1))] = np.nan if how == "nan" else sign * np.inf
        return arr
    if how == "short":
        return arr[:-1].copy()
    return arr[..., None]  # one dimension too many


def _names(exc: Exception, name: str) -> bool:
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", str(exc)) is not None


def _short_applies(cls: str, obj: object, path: tuple) -> bool:
    """A step short is an inconsistency for every array of length >= 2 along its first axis, except a study's grid:
    a shorter grid (still a subset of ``params``) whose spreads happen to be the same is a consistent study."""
    leaf = obj
    for kind, key in path:
        leaf = getattr(leaf, key) if kind == "field" else leaf[key]
    return isinstance(leaf, np.ndarray) and leaf.ndim >= 1 and leaf.shape[0] >= 2 and _field_name(path) != "grid"


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(leaf=st.sampled_from(LEAVES), how=st.sampled_from(("nan", "inf", "short", "ndim")),
       where=st.floats(0.0, 1.0), sign=st.sampled_from((1.0, -1.0)))
def test_a_tampered_field_is_refused_by_name(leaf: tuple, how: str, where: float, sign: float) -> None:
    cls, path = leaf
    obj = EXAMPLES[cls][0]
    value = obj
    for kind, key in path:
        value = getattr(value, key) if kind == "field" else value[key]
    if isinstance(value, float) and how in ("short", "ndim"):
        how = "nan"
    if how == "short" and not _short_applies(cls, obj, path):
        how = "ndim"
    with pytest.raises(ValueError) as info:
        _rebuild(obj, path, lambda v: _mutated(v, how, where, sign))
    assert _names(info.value, _field_name(path)), (cls, path, how, str(info.value))


def _same(a: object, b: object) -> None:
    if dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            _same(getattr(a, f.name), getattr(b, f.name))
    elif isinstance(a, Mapping):
        assert a.keys() == b.keys()
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, (tuple, list)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same(x, y)
    elif isinstance(a, np.ndarray):
        np.testing.assert_array_equal(a, b)
    else:
        assert a == b or (a != a and b != b)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(leaf=st.sampled_from(LEAVES))
def test_a_valid_replace_is_accepted_with_the_same_result(leaf: tuple) -> None:
    cls, path = leaf
    obj, consumer = EXAMPLES[cls]
    same = _rebuild(obj, path, lambda v: v if isinstance(v, float) else np.array(v, copy=True))
    _same(obj, same)
    _same(consumer(obj), consumer(same))


@pytest.mark.parametrize("cls", sorted(EXAMPLES))
def test_arrays_are_read_only_and_owned(cls: str) -> None:
    """Every array of a result is read-only; one built by ``replace`` from a caller's array does not share it."""
    obj = EXAMPLES[cls][0]
    for path in _leaves(obj):
        value = obj
        for kind, key in path:
            value = getattr(value, key) if kind == "field" else value[key]
        if isinstance(value, np.ndarray) and len(path) == 1:
            assert not value.flags.writeable, (cls, path)
            mine = np.array(value, copy=True)
            built = dataclasses.replace(obj, **{path[0][1]: mine})
            assert not np.shares_memory(getattr(built, path[0][1]), mine)


def test_the_private_constructor_gives_the_validated_object() -> None:
    """``trusted`` (the producers' fast path) builds the same object as the public constructor, without the checks."""
    for cls, (obj, _) in EXAMPLES.items():
        fields = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
        _same(trusted(type(obj), **fields), type(obj)(**fields))


def test_cross_field_relations() -> None:
    """Finite, well-shaped but inconsistent fields: the split that does not sum to the filter's covariance, the
    spherical coordinates of another path, an unevenly sampled simulation, a covariance that is not PSD."""
    a = EXAMPLES["LocalTrack"][0]
    with pytest.raises(ValueError, match=r"LocalTrack\.Pd and LocalTrack\.Pi must sum"):
        dataclasses.replace(a, Pd=2.0 * a.Pd)
    path = EXAMPLES["Truth"][0]
    with pytest.raises(ValueError, match=r"Truth\.sph"):
        dataclasses.replace(path, sph=path.sph + [0.0, 1e-3, 0.0])
    sim = EXAMPLES["IrRadarRuns"][0]
    t = sim.t.copy()
    t[-1] += 0.1
    with pytest.raises(ValueError, match=r"IrRadarRuns\.t must be evenly spaced"):
        dataclasses.replace(sim, t=t)
    g = EXAMPLES["GainSequence"][0]
    P = g.P.copy()
    P[2] = -P[2]
    with pytest.raises(ValueError, match=r"GainSequence\.P: every matrix must be positive semidefinite"):
        dataclasses.replace(g, P=P)
    with pytest.raises(TypeError, match=r"LocalTrack\.gains"):
        dataclasses.replace(a, gains="not gains")
    with pytest.raises(ValueError, match=r"Scenario\.central"):  # a centralised filter of other runs
        sc = EXAMPLES["Scenario"][0]
        dataclasses.replace(sc, central=a)


def test_awf_relations_and_the_consistency_mask() -> None:
    """fuzz (issue 35): an AWFResult whose weights do not sum to one, whose value is not the weighted sum of its
    means, or a ConsistentAWF whose mask is not boolean, of another shape or rejects a weighted reading, is refused;
    negative variance estimates (the lecture's, by design) are accepted."""
    r = EXAMPLES["AWFResult"][0]
    with pytest.raises(ValueError, match=r"AWFResult\.weights must sum to one"):
        dataclasses.replace(r, weights=2.0 * r.weights)
    with pytest.raises(ValueError, match=r"AWFResult\.value must be the weighted sum"):
        dataclasses.replace(r, value=r.value + 1e-6 * np.abs(r.value).max())
    v = np.array(r.variances)
    v[0, 0, 0] = -abs(v[0, 0, 0]) - 1.0
    assert dataclasses.replace(r, variances=v).variances[0, 0, 0] < 0
    c = EXAMPLES["ConsistentAWF"][0]
    assert not c.mask.all() and not c.mask.flags.writeable
    with pytest.raises(ValueError, match=r"ConsistentAWF\.mask: a rejected reading"):
        dataclasses.replace(c, mask=np.zeros_like(c.mask))
    with pytest.raises(ValueError, match=r"ConsistentAWF\.mask must have the shape"):
        dataclasses.replace(c, mask=c.mask[0].copy())
    with pytest.raises(TypeError, match=r"ConsistentAWF\.mask must be a boolean array"):
        dataclasses.replace(c, mask=c.mask.astype(float))
    with pytest.raises(TypeError, match=r"ConsistentAWF\.awf"):
        dataclasses.replace(c, awf="abc")


def _batch_class() -> type:
    from fusion._results import BATCH, ResultSpec, array, validated_post_init

    @dataclasses.dataclass(frozen=True)
    class Batched:
        a: np.ndarray
        b: np.ndarray
        c: np.ndarray
        __result_spec__ = ResultSpec({"a": array(BATCH, "K"), "b": array(BATCH, "K", 2), "c": array("K")})
        __post_init__ = validated_post_init

    return Batched


BATCHED = _batch_class()
_shapes = st.lists(st.integers(1, 3), min_size=0, max_size=3).map(tuple)


@settings(max_examples=60, deadline=None)
@given(batch=_shapes, other=_shapes, K=st.integers(1, 4))
def test_leading_batch_axes_are_one_named_group(batch: tuple, other: tuple, K: int) -> None:
    """The ``"..."`` form of a spec: any number of leading axes (none included), the same batch shape in every
    field that declares it; another batch shape in one field is refused naming it and the field it came from."""
    a, b, c = np.zeros(batch + (K,)), np.zeros(batch + (K, 2)), np.zeros(K)
    obj = BATCHED(a, b, c)
    assert obj.b.shape == batch + (K, 2) and not obj.a.flags.writeable
    from fusion._results import BATCH, dimensions
    assert dimensions(obj) == {BATCH: batch, "K": K}
    if other != batch:
        with pytest.raises(ValueError, match=r"Batched\.b must have shape .*from Batched\.a"):
            BATCHED(a, np.zeros(other + (K, 2)), c)
    with pytest.raises(ValueError, match=r"Batched\.b must have shape"):  # a core axis of the wrong length
        BATCHED(a, np.zeros(batch + (K, 3)), c)
    with pytest.raises(ValueError, match=r"Batched\.c must have shape"):  # K bound through the batch form
        BATCHED(a, b, np.zeros(K + 1))
    with pytest.raises(ValueError, match=r"Batched\.a must have shape .*at least 1 axes"):
        BATCHED(np.float64(0.0), b, c)
    with pytest.raises(ValueError, match=r"only be the first"):
        from fusion._results import array
        array("K", BATCH)


def _optimum() -> object:
    from fusion.optimise.swarm import particle_swarm

    target = np.array([0.2, 0.3, 0.5])
    return particle_swarm(lambda e: -((e - target) ** 2).sum(axis=-1), 3, np.random.default_rng(1), trace=True)


OPTIMUM = _optimum()


@pytest.mark.parametrize("field, value, exc", [
    ("x", "abc", TypeError), ("x", True, TypeError), ("x", np.array([np.nan, 0.5, 0.5]), ValueError),
    ("x", np.array([0.5, 0.5]), ValueError), ("x", np.array([0.6, 0.3, 0.3]), ValueError),
    ("x", np.array([[0.2, 0.3, 0.5]]), ValueError), ("fun", np.nan, ValueError), ("fun", -np.inf, ValueError),
    ("fun", "abc", TypeError), ("n_evaluations", -1, ValueError), ("n_evaluations", 1.5, TypeError),
    ("history", np.array([0.0, np.nan]), ValueError), ("history", np.array([0.0, -1.0]), ValueError),
    ("history", np.array([-1.0, 0.0]), ValueError), ("trace", "abc", TypeError),
])
def test_a_tampered_optimum_is_refused_by_name(field: str, value: object, exc: type) -> None:
    """fuzz (issue 35): an OptimumResult (the swarm's, held by MixtureFusion.swarm) rebuilt with a non-finite or
    ill-typed field, a history that is not the best value so far ending at ``fun``, a swarm point off the simplex,
    is refused naming the field."""
    with pytest.raises(exc, match=rf"OptimumResult\.{field}"):
        dataclasses.replace(OPTIMUM, **{field: value})


def test_a_valid_optimum_is_accepted() -> None:
    """The producers' results rebuild: the swarm's (history starting at -inf before a feasible point included),
    a scalar optimiser's float ``x``, the closed form's zero evaluations."""
    from fusion.optimise.result import OptimumResult
    from fusion.optimise.scalar import grid_search

    _same(OPTIMUM, dataclasses.replace(OPTIMUM, x=np.array(OPTIMUM.x), history=list(OPTIMUM.history)))
    assert not OPTIMUM.x.flags.writeable and not OPTIMUM.history.flags.writeable
    h = np.concatenate([[-np.inf], OPTIMUM.history])
    assert dataclasses.replace(OPTIMUM, history=h).history[0] == -np.inf
    g = grid_search(lambda x: (x - 0.3) ** 2, 11)
    assert isinstance(dataclasses.replace(g).x, float)
    assert OptimumResult(x=0.5, fun=-1.0, n_evaluations=0).n_evaluations == 0


def test_a_gaussian_mixture_is_read_only() -> None:
    """fuzz12 (debatable): writing ``gm.weights[:] = nan`` after construction bypassed the simplex check; every
    validated field of a GaussianMixture is read-only and owned."""
    from fusion.estimates.mixtures import GaussianMixture

    w, m, c = np.array([0.25, 0.75]), np.zeros((2, 2)), np.stack([np.eye(2)] * 2)
    gm = GaussianMixture(w, m, c)
    for name, mine in (("weights", w), ("means", m), ("covs", c)):
        arr = getattr(gm, name)
        assert not arr.flags.writeable and not np.shares_memory(arr, mine)
        with pytest.raises(ValueError, match="read-only"):
            arr[0] = np.nan


def _arrays(obj: object, path: str = "") -> list[tuple[str, np.ndarray]]:
    """Every ndarray reachable through the fields of ``obj`` (nested results, dicts, tuples and lists)."""
    out: list[tuple[str, np.ndarray]] = []
    if isinstance(obj, np.ndarray):
        return [(path, obj)]
    if isinstance(obj, Mapping):
        for k, v in obj.items():
            out += _arrays(v, f"{path}[{k!r}]")
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            out += _arrays(v, f"{path}[{i}]")
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            out += _arrays(getattr(obj, f.name), f"{path}.{f.name}")
    return out


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_deepcopy_and_pickle_keep_every_array_read_only_and_equal(name: str) -> None:
    """fuzz13 bug 3: a deep copy or an unpickled result had writeable arrays, so NaN written into it reached the
    consumers that trust the type; now every array of the copy (nested ones too) is read-only and equal."""
    obj, consumer = EXAMPLES[name]
    original = _arrays(obj)
    assert original and all(not a.flags.writeable for _, a in original)
    for how, c in [("deepcopy", copy.deepcopy(obj)), ("pickle", pickle.loads(pickle.dumps(obj)))]:
        got = _arrays(c)
        assert [p for p, _ in got] == [p for p, _ in original], how
        for (path, a), (_, b) in zip(got, original):
            assert not a.flags.writeable and np.array_equal(a, b, equal_nan=True), f"{how}: {name}{path}"


# --------------------------------------------------------------------------------------------
# every public result the registry's valid calls build (fuzz14 bugs 4-5)
# --------------------------------------------------------------------------------------------


def _walk(obj: object, found: dict[str, object]) -> None:
    """Collect the first instance of each dataclass reachable from ``obj`` (fields, mappings, tuples, lists)."""
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        key = f"{type(obj).__module__}.{type(obj).__qualname__}"
        if key in found:
            return
        found[key] = obj
        for f in dataclasses.fields(obj):
            _walk(getattr(obj, f.name), found)
    elif isinstance(obj, Mapping):
        for v in obj.values():
            _walk(v, found)
    elif isinstance(obj, (list, tuple)):
        for v in obj:
            _walk(v, found)


def _registry_results() -> dict[str, object]:
    """One instance of every result class that the bad-input registry's valid calls take or return."""
    import warnings

    from test_bad_input import CALLABLES, REG
    from test_bad_input_classes import SLOW

    found: dict[str, object] = {}
    for name in sorted(REG):
        if name in SLOW:
            continue
        kwargs = {k: (np.random.default_rng(0) if isinstance(a.value, np.random.Generator) else a.value)
                  for k, a in REG[name].items()}
        _walk(list(kwargs.values()), found)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _walk(CALLABLES[name](**kwargs), found)
    return found


REGISTRY_RESULTS = _registry_results()
#: Public frozen results outside the book's chapter helpers that no fast valid call of the registry builds (the
#: published tables, the swarm's trace, the network study and the constant-level runs: built by the slow studies).
UNREACHED = {"fusion.data._published.Published", "fusion.optimise.result.SwarmTrace",
             "fusion.scenarios.fusion_networks.NetworkStudy",
             "fusion.scenarios.lecture_weighting.estimators.ConstantLevelRuns"}


def _public_frozen_results() -> set[str]:
    from test_public_types import DATACLASSES

    return {k for k, c in DATACLASSES.items() if c.__dataclass_params__.frozen and not k.startswith("fusion.book.")}


def test_the_registry_reaches_every_public_result() -> None:
    """The copy and mutation tests below enumerate every public frozen result (the previous copy test took eight
    hand-picked examples, so FusionStudy, whose arrays are read-only views of its Scenario's, escaped it)."""
    public = _public_frozen_results()
    assert UNREACHED <= public
    missing = sorted(public - UNREACHED - set(REGISTRY_RESULTS))
    assert not missing, missing
    assert not sorted(UNREACHED & set(REGISTRY_RESULTS))  # reached now: leave the list


@pytest.mark.parametrize("name", sorted(REGISTRY_RESULTS))
def test_copies_keep_every_read_only_array_read_only(name: str) -> None:
    """fuzz14 bug 4: an array read-only in a result is read-only (and equal) in its deep copy and its unpickled copy."""
    obj = REGISTRY_RESULTS[name]
    original = _arrays(obj)
    for how, c in [("deepcopy", copy.deepcopy(obj)), ("pickle", pickle.loads(pickle.dumps(obj)))]:
        got = _arrays(c)
        assert [p for p, _ in got] == [p for p, _ in original], how
        for (path, a), (_, b) in zip(got, original):
            assert a.flags.writeable or not b.flags.writeable, f"{how}: {name}{path} became writeable"
            assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"), f"{how}: {name}{path}"


def _mutable_parts(obj: object, path: str = "") -> list[str]:
    """Paths of everything in ``obj``'s fields that can be changed in place: a writeable array, a dict, a list, a set
    (nested results are checked as results of their own)."""
    if isinstance(obj, np.ndarray):
        return [path] if obj.flags.writeable else []
    if isinstance(obj, (dict, list, set, bytearray)) or (isinstance(obj, Mapping) and hasattr(obj, "__setitem__")):
        return [f"{path} ({type(obj).__name__})"]
    if isinstance(obj, Mapping):
        return [p for k, v in obj.items() for p in _mutable_parts(v, f"{path}[{k!r}]")]
    if isinstance(obj, tuple):
        return [p for i, v in enumerate(obj) for p in _mutable_parts(v, f"{path}[{i}]")]
    return []


def _frozen_result(cls: type) -> bool:
    """A result that freezes its fields when built (frozen_arrays, a validated result, a self-frozen one)."""
    from fusion._frozen import restore_frozen

    return getattr(cls, "__setstate__", None) is restore_frozen


FROZEN_RESULTS = sorted(k for k, v in REGISTRY_RESULTS.items() if _frozen_result(type(v)))


@pytest.mark.parametrize("name", FROZEN_RESULTS)
def test_no_field_of_a_frozen_result_can_be_changed_in_place(name: str) -> None:
    """fuzz14 bug 5: a frozen result's dict fields are read-only mappings and its list fields tuples (their arrays
    read-only), also in its copies: ``BeliefParameterStudy.sq[k] = nan`` was accepted, then ``belief_spread`` gave
    NaN. The same holds for any object built through ``dataclasses.replace`` from plain dicts and lists."""
    obj = REGISTRY_RESULTS[name]
    for how, c in [("built", obj), ("deepcopy", copy.deepcopy(obj)), ("pickle", pickle.loads(pickle.dumps(obj)))]:
        parts = [p for f in dataclasses.fields(c) for p in _mutable_parts(getattr(c, f.name), f".{f.name}")]
        assert not parts, f"{how}: {name}: {parts}"
    rebuilt = dataclasses.replace(obj, **{f.name: _thawed(getattr(obj, f.name)) for f in dataclasses.fields(obj)
                                          if f.init})
    parts = [p for f in dataclasses.fields(rebuilt) for p in _mutable_parts(getattr(rebuilt, f.name), f".{f.name}")]
    assert not parts, f"replace: {name}: {parts}"


def _thawed(value: object) -> object:
    """Plain, writeable containers of the same values (what a caller would pass to ``dataclasses.replace``)."""
    if isinstance(value, np.ndarray):
        return np.array(value)
    if isinstance(value, Mapping):
        return {k: _thawed(v) for k, v in value.items()}
    if type(value) is tuple:  # a list, except a tuple of nested results (a validated field of that type)
        items = [_thawed(v) for v in value]
        return tuple(items) if any(dataclasses.is_dataclass(v) for v in value) else items
    return value


def test_a_frozen_result_refuses_item_assignment_and_its_consumer_stays_finite() -> None:
    """The report's case: writing NaN into ``BeliefParameterStudy.sq`` (or ``.fused``, ``.spread``) is refused."""
    study, consumer = EXAMPLES["BeliefParameterStudy"]
    before = consumer(study)
    for field in ("fused", "sq", "spread"):
        mapping = getattr(study, field)
        k = next(iter(mapping))
        with pytest.raises(TypeError):
            mapping[k] = np.full_like(mapping[k], np.nan)
        with pytest.raises(ValueError, match="read-only"):
            mapping[k][...] = np.nan
    _same(before, consumer(study))
