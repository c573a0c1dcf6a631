"""The public API's type hints resolve, and the frozen results' arrays are read-only (issue 36).

``typing.get_type_hints`` must work on every public class, its public methods and every public function, although
the packages rename their objects' ``__module__`` (:func:`fusion._public.name_by_package`). Every public frozen
dataclass with an ndarray field is declared with :func:`fusion._frozen.frozen_arrays` (one decorator instead of a
``__post_init__`` per class) or validates its fields (``fusion._results``); :data:`NOT_YET_FROZEN` and
:data:`CONTAINERS_NOT_YET_FROZEN` are empty since fuzz 19 (the main package's and the chapter layer's results alike;
tests/test_frozen_results.py checks the produced objects and their DataFrame fields).
"""

from __future__ import annotations

import collections.abc
import copy
import dataclasses
import importlib
import pickle
import inspect
import pkgutil
import types
import typing

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import fusion
from fusion._frozen import freeze_arrays, freeze_shared, frozen_arrays, restore_frozen


def _public() -> dict[str, object]:
    out: dict[str, object] = {}
    for modname in ["fusion"] + [m.name for m in pkgutil.walk_packages(fusion.__path__, "fusion.")]:
        mod = importlib.import_module(modname)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if inspect.isclass(obj) or inspect.isfunction(obj):
                out.setdefault(f"{obj.__module__}.{obj.__qualname__}", obj)
    return out


PUBLIC = _public()
CLASSES = {k: v for k, v in PUBLIC.items() if inspect.isclass(v)}
DATACLASSES = {k: v for k, v in CLASSES.items() if dataclasses.is_dataclass(v)}

#: Public frozen dataclasses with ndarray fields that do not freeze them yet (they predate frozen_arrays; making them
#: read-only changes what their callers may do with the arrays). Shrink this list; do not grow it.
NOT_YET_FROZEN: frozenset[str] = frozenset()
#: Frozen results that validate their fields and make their arrays read-only in their own ``__post_init__``.
SELF_FROZEN = frozenset({"fusion.estimates.mixtures.GaussianMixture", "fusion.scenarios.fusion_networks.NetworkStudy",
                         "fusion.optimise.result.OptimumResult"})


def _is_array(hint: object) -> bool:
    if hint is np.ndarray or typing.get_origin(hint) is np.ndarray:
        return True
    return typing.get_origin(hint) in (typing.Union, types.UnionType) and any(map(_is_array, typing.get_args(hint)))


def _array_fields(cls: type) -> list[str]:
    hints = typing.get_type_hints(cls)
    return [f.name for f in dataclasses.fields(cls) if _is_array(hints[f.name])]


def test_the_public_api_is_enumerated() -> None:
    assert len(PUBLIC) > 500 and len(DATACLASSES) > 100
    assert "fusion.scenarios.two_sensor.FusionStudy" in CLASSES     # renamed by its package, still found


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_type_hints_resolve(name: str) -> None:
    obj = PUBLIC[name]
    typing.get_type_hints(obj)
    if inspect.isclass(obj):
        for attr, member in vars(obj).items():
            if inspect.isfunction(member) and not attr.startswith("_"):
                typing.get_type_hints(member)


_MAPPINGS = (dict, collections.abc.Mapping, collections.abc.MutableMapping)


def _untyped_dict(hint: object) -> bool:
    """True for a ``dict`` or mapping whose values are ``Any`` or unstated (bare ``dict``), at any depth of ``hint``."""
    if hint in _MAPPINGS or hint in (typing.Dict, typing.Mapping):  # noqa: UP006
        return True
    args = typing.get_args(hint)
    if typing.get_origin(hint) in _MAPPINGS and (len(args) != 2 or args[1] is typing.Any):
        return True
    return any(_untyped_dict(a) for a in args if not isinstance(a, typing.ForwardRef) and a is not Ellipsis)


def _returns(obj: object) -> list[tuple[str, object]]:
    fns = ([("", obj)] if inspect.isfunction(obj) else
           [(f".{a}", m) for a, m in vars(obj).items() if inspect.isfunction(m) and not a.startswith("_")])
    return [(n, typing.get_type_hints(f).get("return")) for n, f in fns]


def test_the_untyped_dict_check() -> None:
    from fusion.book._json import JSONObject
    for bad in (dict, dict[str, typing.Any], dict[typing.Any, typing.Any], dict[float, dict[typing.Any, typing.Any]],
                tuple[int, dict[str, typing.Any]], list[dict] | None, collections.abc.Mapping[str, typing.Any]):
        assert _untyped_dict(bad), bad
    for good in (dict[str, float], dict[float, np.ndarray], tuple[dict[str, int], ...], JSONObject, list[JSONObject],
                 typing.Any, None):
        assert not _untyped_dict(good), good


def test_no_public_function_returns_an_untyped_dict() -> None:
    """Issue 36: a result is a frozen dataclass, or a dict with a precise value type; never ``dict[str, Any]``."""
    found = [f"{name}{n} -> {hint}" for name, obj in sorted(PUBLIC.items()) for n, hint in _returns(obj)
             if _untyped_dict(hint)]
    assert not found, found


def test_renamed_classes_keep_their_hints() -> None:
    from fusion.scenarios.two_sensor import FusionStudy
    assert FusionStudy.__module__ == "fusion.scenarios.two_sensor"
    assert typing.get_origin(typing.get_type_hints(FusionStudy)["truth"]) is np.ndarray


def _declared(cls: type) -> bool:
    return getattr(cls, "__post_init__", None) in (freeze_arrays, freeze_shared)


def _validated(cls: type) -> bool:
    """A result checked field by field when built (``__result_spec__``, fusion._results: read-only copies too,
    tests/test_result_objects.py)."""
    return getattr(cls, "__result_spec__", None) is not None


def test_every_frozen_result_with_arrays_declares_frozen_arrays() -> None:
    with_arrays = {k for k, c in DATACLASSES.items() if c.__dataclass_params__.frozen and _array_fields(c)}
    assert NOT_YET_FROZEN | SELF_FROZEN <= with_arrays      # the lists name only such results
    missing = {k for k in with_arrays - NOT_YET_FROZEN - SELF_FROZEN
               if not (_declared(DATACLASSES[k]) or _validated(DATACLASSES[k]))}
    assert not missing, sorted(missing)
    assert not {k for k in NOT_YET_FROZEN | SELF_FROZEN if _declared(DATACLASSES[k])}


FROZEN = sorted(k for k, c in DATACLASSES.items() if getattr(c, "__post_init__", None) is freeze_arrays)


@pytest.mark.parametrize("name", FROZEN)
def test_frozen_arrays_are_read_only_copies(name: str) -> None:
    cls = DATACLASSES[name]
    assert cls.__dataclass_params__.frozen
    arrays = _array_fields(cls)
    given = {f.name: (np.arange(6.0).reshape(2, 3) if f.name in arrays else None) for f in dataclasses.fields(cls)
             if f.init}
    obj = cls(**given)
    for f in arrays:
        value = getattr(obj, f)
        assert not value.flags.writeable and np.array_equal(value, given[f])
        assert given[f].flags.writeable and not np.shares_memory(value, given[f])   # the caller's array is untouched
        with pytest.raises(ValueError):
            value[0, 0] = 1.0


def _copies(obj: object) -> list[tuple[str, object]]:
    return [("deepcopy", copy.deepcopy(obj)), ("pickle", pickle.loads(pickle.dumps(obj))), ("copy", copy.copy(obj))]


def test_every_result_with_read_only_arrays_refreezes_them_when_copied_or_unpickled() -> None:
    """fuzz13 bug 3: deepcopy and pickle rebuild an object without __init__ (numpy restores arrays writeable);
    every frozen, validated or self-frozen result restores read-only arrays (``__setstate__``)."""
    frozen = {k for k, c in DATACLASSES.items() if _declared(c) or _validated(c)} | SELF_FROZEN
    assert len(frozen) >= 50
    assert not {k for k in frozen if getattr(DATACLASSES[k], "__setstate__", None) is not restore_frozen}


def _mutable_hint(hint: object) -> bool:
    """True for ``list``, ``dict`` or ``set`` (bare or subscripted) anywhere in ``hint``."""
    if hint in (list, dict, set) or typing.get_origin(hint) in (list, dict, set):
        return True
    return any(_mutable_hint(a) for a in typing.get_args(hint) if not isinstance(a, typing.ForwardRef) and a is not Ellipsis)


def test_the_mutable_hint_check() -> None:
    for bad in (list, dict, set, list[str], dict[str, np.ndarray], tuple[dict[str, float], ...],
                collections.abc.Mapping[str, list[float]], dict[str, float] | None, set[int]):
        assert _mutable_hint(bad), bad
    for good in (tuple[str, ...], collections.abc.Mapping[str, np.ndarray], frozenset[int], np.ndarray, float | None,
                 collections.abc.Mapping[tuple[float, str], tuple[np.ndarray, np.ndarray]]):
        assert not _mutable_hint(good), good


def test_frozen_results_annotate_what_they_store() -> None:
    """Issue 35: a result that freezes its fields stores a dict as a read-only mapping and a list as a tuple
    (``fusion._frozen.frozen_value``); its annotations say ``Mapping`` and ``tuple``, never ``dict``, ``list`` or
    ``set`` (26 classes annotated list/dict fields they never held)."""
    frozen = {k: c for k, c in DATACLASSES.items() if c.__dataclass_params__.frozen
              and getattr(c, "__setstate__", None) is restore_frozen}
    assert len(frozen) >= 50
    found = [f"{k}.{name}: {hint}" for k, c in sorted(frozen.items())
             for name, hint in typing.get_type_hints(c).items()
             if name in {f.name for f in dataclasses.fields(c)} and _mutable_hint(hint)]
    assert not found, found


def test_no_result_holds_a_mappingproxy() -> None:
    """A ``mappingproxy`` can be neither deep-copied nor pickled (fuzz13: ``BenchmarkResult``): a read-only mapping
    field of a result is a ``fusion._results.ReadOnlyMapping``; no module of the package builds a mappingproxy
    (``MappingProxyType(...)`` called; ``glue_all`` names the type among the containers whose text it trusts)."""
    import re
    from pathlib import Path

    root = Path(fusion.__file__).resolve().parent
    users = sorted(str(p.relative_to(root)) for p in root.rglob("*.py")
                   if re.search(r"MappingProxyType\s*\(", p.read_text("utf-8")))
    assert not users, users


@given(items=st.dictionaries(st.text(max_size=5), st.recursive(st.none() | st.integers() | st.text(max_size=5),
                                                               lambda c: st.lists(c, max_size=3)
                                                               | st.dictionaries(st.text(max_size=3), c, max_size=3)),
                             max_size=5))
def test_a_read_only_mapping_survives_copies_and_stays_read_only(items: dict) -> None:
    """copy, deepcopy and pickle of a ReadOnlyMapping: an equal ReadOnlyMapping (deep copies for the last two), still
    refusing item and attribute assignment."""
    from fusion._results import ReadOnlyMapping

    m = ReadOnlyMapping(items)
    assert m == items and dict(m) == items and len(m) == len(items)
    for how, c in _copies(m):
        assert type(c) is ReadOnlyMapping and c == m, how
        with pytest.raises(TypeError):
            c["new key"] = 1  # type: ignore[index]
        with pytest.raises(AttributeError):
            c._items = {}  # type: ignore[misc]
    items["new key"] = 1  # the caller's dict is not the mapping's
    assert "new key" not in m


def test_a_benchmark_result_survives_copies_and_stays_read_only() -> None:
    """fuzz13: ``BenchmarkResult`` could not be deep-copied or pickled (its record a mappingproxy)."""
    from fusion.book.benchmarks import load_benchmark

    b = load_benchmark("ci")
    for how, c in _copies(b):
        assert c == b and c.values == b.values and c.caption == b.caption, how
        with pytest.raises(TypeError):
            c.record["date"] = "tomorrow"  # type: ignore[index]
        with pytest.raises(TypeError):
            c.measurements[0]["value"] = 0.0  # type: ignore[index]
        assert how == "copy" or c.record is not b.record


@pytest.mark.parametrize("name", FROZEN)
def test_copies_of_frozen_arrays_stay_read_only_and_equal(name: str) -> None:
    cls = DATACLASSES[name]
    arrays = _array_fields(cls)
    obj = cls(**{f.name: (np.arange(6.0).reshape(2, 3) if f.name in arrays else None) for f in dataclasses.fields(cls)
                 if f.init})
    for how, c in _copies(obj):
        for f in arrays:
            value = getattr(c, f)
            assert not value.flags.writeable and np.array_equal(value, getattr(obj, f)), f"{how}: {f}"
            assert how == "copy" or not np.shares_memory(value, getattr(obj, f)), f"{how}: {f}"


def test_frozen_arrays_decorator() -> None:
    @dataclasses.dataclass(frozen=True)
    @frozen_arrays
    class R:
        a: np.ndarray
        b: int

    src = np.ones(3)
    r = R(src, 2)
    assert not r.a.flags.writeable and src.flags.writeable and r.b == 2
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.a = src  # type: ignore[misc]


def test_frozen_arrays_refuses_a_class_with_its_own_post_init() -> None:
    """The decorator would silently replace a validating ``__post_init__`` (fusion._results) by a bare freeze."""
    from fusion._frozen import frozen_arrays

    class Validated:
        def __post_init__(self) -> None:
            raise AssertionError("never replaced")

    with pytest.raises(TypeError, match="own __post_init__"):
        frozen_arrays(Validated)
    assert "__post_init__" in vars(Validated) and Validated.__post_init__ is not freeze_arrays


def _container_fields(cls: type) -> list[str]:
    """Fields typed as a dict, mapping or list (their items could be reassigned in place unless frozen)."""
    hints = typing.get_type_hints(cls)
    out = []
    for f in dataclasses.fields(cls):
        origin = typing.get_origin(hints[f.name]) or hints[f.name]
        if origin in (dict, list, collections.abc.Mapping, collections.abc.MutableMapping):
            out.append(f.name)
    return out


#: Public frozen dataclasses with dict or list fields (and no array field) that do not freeze them yet. Shrink this
#: list; do not grow it (fuzz 16 found seven such results whose dicts held writeable arrays; they are frozen now).
#: (BenchmarkResult keeps its mapping read-only itself.)
CONTAINERS_NOT_YET_FROZEN: frozenset[str] = frozenset()
#: Results with containers that validate and freeze them in their own ``__post_init__`` (``freeze_arrays`` last).
SELF_FROZEN_CONTAINERS = frozenset({"fusion.book.claims.ReadingSpec", "fusion.book.claims.ClaimsFile"})


def test_every_frozen_result_with_containers_freezes_them() -> None:
    """A frozen result whose dict or list fields stay plain lets a caller reassign their items (fuzz 16)."""
    holding = {k for k, c in DATACLASSES.items() if c.__dataclass_params__.frozen and _container_fields(c)
               and k not in NOT_YET_FROZEN and k not in SELF_FROZEN}
    missing = {k for k in holding if not (_declared(DATACLASSES[k]) or _validated(DATACLASSES[k]))}
    assert missing == set(CONTAINERS_NOT_YET_FROZEN) | SELF_FROZEN_CONTAINERS, \
        sorted(missing ^ (set(CONTAINERS_NOT_YET_FROZEN) | SELF_FROZEN_CONTAINERS))
    assert all(getattr(DATACLASSES[k], "__setstate__", None) is restore_frozen for k in SELF_FROZEN_CONTAINERS)


def test_every_frozen_result_protects_its_dataframe_fields() -> None:
    """fuzz 19 G1-G3: a DataFrame field of a frozen result (chapter layer and main package alike) is a private copy
    handed out as a copy on each read (``fusion._frozen.FrameField``), so an in-place edit never reaches the object."""
    from fusion._frozen import FrameField

    found = {}
    for k, c in DATACLASSES.items():
        if not c.__dataclass_params__.frozen:
            continue
        hints = typing.get_type_hints(c)
        frames = [f.name for f in dataclasses.fields(c) if "DataFrame" in str(hints[f.name])]
        if frames:
            found[k] = [n for n in frames if not isinstance(inspect.getattr_static(c, n, None), FrameField)]
    assert len(found) >= 7, sorted(found)          # AuditResult, TableReproduction, LedgerInputs, chapter 06 studies
    assert not {k: v for k, v in found.items() if v}
