"""Round 63's remainder and fuzz 65a C2: glue_all weighs an Interval, a Period or a date-time held by an object container (a list,
tuple, set, dict, object array, object Series, Index of labels, table column) by its type, as a pandas dtype of them
is weighed by kind: 4,900,000 Intervals in an object Series were charged 200 units each (about 9.8e8 units) and ran
past 40 CPU-s; measured 6.9-11.8 us an Interval, 3.4-6.3 us a Period or date-time, in every such container."""

from __future__ import annotations

import datetime
import enum
import pathlib
import warnings

import numpy as np
import pandas as pd
import pytest

from _helpers import glue_refused

#: The plain units of an entry of each container inside a value (``glue._container_work``): a Python container's
#: ``_GLUE_NESTED``, an object array's, Series', Index's, table column's ``_GLUE_OBJECT``.
_PLAIN = {"list": 400, "dict": 400, "object array": 200, "object Series": 200, "labels": 200, "column": 200,
          "pandas array": 200, "sparse array": 200}
#: The units of a float entry of each: a Python container's plain weight (its floats are checked at once), an object
#: array's, Series', Index's or column's by its type (``_glue_axes._OBJECT_ANY``, fuzz 65a C2).
_FLOAT = {k: v if k in ("list", "dict") else 900 for k, v in _PLAIN.items()}


class _Kind(enum.Enum):
    A = 1


def _holder(kind: str, atoms: np.ndarray) -> object:
    if kind == "list":
        return list(atoms)
    if kind == "dict":   # its keys are ints (plain), its values the atoms
        return dict(zip(range(len(atoms)), atoms))
    if kind == "object array":
        return atoms
    if kind == "object Series":
        return pd.Series(atoms, dtype=object)
    if kind == "pandas array":
        return pd.array(atoms, dtype=object)
    if kind == "sparse array":   # pandas warns that it drops a time zone here: the entries stay date-times
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            return pd.arrays.SparseArray(atoms, dtype=pd.SparseDtype(object, None))
    if kind == "labels":
        return pd.Series(np.zeros(len(atoms)), index=pd.Index(atoms, dtype=object))
    return pd.DataFrame({"a": pd.Series(atoms, dtype=object)})


def _atoms(kind: str, n: int) -> np.ndarray:
    out = np.empty(n, dtype=object)
    base = {"interval": pd.Interval(0, 1), "period": pd.Period("2020-01", "M"),
            "datetime": datetime.datetime(2020, 1, 1), "zoned": pd.Timestamp("2020-01-01", tz="UTC"),
            "date": datetime.date(2020, 1, 1), "time": datetime.time(1, 2, 3), "duration": pd.Timedelta(seconds=5),
            "path": pathlib.PurePosixPath("/a/b"), "enum": _Kind.A}[kind]
    out[:] = [base] * n
    return out


@pytest.mark.parametrize("holder", list(_PLAIN))
@pytest.mark.parametrize(("atom", "weight"), [("interval", 2_800), ("period", 1_300), ("datetime", 1_300),
                                              ("zoned", 1_300), ("date", 1_300), ("time", 1_300),
                                              ("duration", 1_300), ("path", 1_300), ("enum", 1_600)])
def test_an_object_containers_costly_atoms_are_weighed_by_type(holder, atom, weight) -> None:
    """The container's units grow by ``weight - plain`` an atom over the plain weight (its other entries unchanged),
    and an object container of them beyond the budget is refused naming values['k'] within 1 CPU-s."""
    from fusion._limits import MAX_WORK
    from fusion.book import glue as G

    n = 1_000
    plain = G._container_work(_holder(holder, np.arange(n, dtype=float).astype(object)))[1]
    costly = G._container_work(_holder(holder, _atoms(atom, n)))[1]
    assert costly - plain == n * (weight - _FLOAT[holder])
    glue_refused({"k": _holder(holder, _atoms(atom, MAX_WORK // weight + 1))}, ValueError)


def test_a_mixed_list_is_weighed_entry_by_type() -> None:
    """Only the costly entries are weighed more: a list of 10 Intervals and 990 floats costs 10 x (2,800 - 300)
    more than 1,000 floats (a value's list entries weigh ``_GLUE_ENTRY``)."""
    from fusion.book import glue as G

    mixed = [pd.Interval(0, 1)] * 10 + [0.5] * 990
    assert G._glue_units(mixed) - G._glue_units([0.5] * 1_000) == 10 * (2_800 - G._GLUE_ENTRY)


def test_a_valid_list_of_intervals_within_the_budget_is_glued(monkeypatch) -> None:
    """10**4 Intervals in a list (2.8e7 units, ~0.1 CPU-s) are glued as before: the type count refuses only what
    the budget does not allow."""
    from _helpers import glued

    got = glued(monkeypatch, {"k": [pd.Interval(i, i + 1) for i in range(10**4)]})
    assert len(got["k"]) == 10**4


def test_any_other_atom_of_an_object_array_weighs_its_measured_cost() -> None:
    """An int, str or float of an object array (2.8-5.4 us measured) weighs ``_OBJECT_ANY`` (900 units), a float of
    a list its list's plain weight (checked at once, 0.12 us), a container held its kind's fixed cost (its entries
    charged where they are reached; fix74c, fuzz 66a C5: a list 2,000 units); fuzz 65a C2: 4,900,000 Enum members of an object array ran 43.9 CPU-s accepted."""
    from fusion.book import glue as G

    n = 1_000
    for atom in (1, "x", 0.5, None):
        arr = np.empty(n, dtype=object)
        arr[:] = [atom] * n
        assert G._container_work(arr)[1] == n * 900
    assert G._glue_units([0.5] * n) == n * G._GLUE_ENTRY
    assert G._glue_units([[0.5]] * n) == n * 2_000
    assert G._glue_units([1] * n) == n * 900
