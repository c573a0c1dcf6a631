"""Fuzz 29b of the chapter layer (issue 35): each class fixed once, where it is decided, and tested here.

* B1: a chapter function uses the value its check returns, not the caller's object (a numpy small integer
  overflowed a budget; a ``Decimal`` was divided by a float).
* B2: :func:`fusion._frozen.frozen_value` freezes every mapping (a caller's ``MappingProxyType`` or ``ChainMap``
  was kept by reference in a frozen result): a property test of the rule and a sweep of every mapping field of
  every frozen result of the four chapter registries.
* B3, D4: the memory budget before any draw (``check_grid``, ``fault_shapes_study``).
* B4: ``LedgerInputs.fig5_hyp`` holds :func:`fig5_hypotheses`' table (its columns and rows), refused by the field.
* B5: ``path_period_table`` and ``path_numbers`` read any mapping as the dict it is.
* B6: rule R4 refused by the reader's own argument, never the comparison's ``a and b`` and "the argument reason".
* D1: a table column of non-native byte order refused by name (``fusion.book.tables._frame``); D2: the benchmark
  readers pair ``stab`` with the results in their key order (documented).

The registries' objects are shared with their own test files (built once per worker).
"""

from __future__ import annotations

import collections
import dataclasses
import importlib
import pickle
import sys
import types
from collections.abc import Mapping
from decimal import Decimal
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings, strategies as st  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))

REGISTRIES = ("test_bad_input_calls_ch010307", "test_bad_input_calls_ch0204", "test_bad_input_calls_ch05",
              "test_bad_input_calls_ch06")
CI = "fusion.book.chapters.ci."


def _registry(name: str) -> dict:
    return importlib.import_module(name).registry()


def _valid(name: str, fname: str) -> dict[str, Any]:
    """The valid call of ``fname`` in the registry ``name``: argument -> value."""
    return {k: a.value for k, a in _registry(name)[fname].items()}


def _call(fname: str, **kwargs: Any) -> Any:
    mod, fn = fname.rsplit(".", 1)
    return getattr(importlib.import_module(mod), fn)(**kwargs)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, (pd.DataFrame, pd.Series)):
        return a.equals(b)
    return a == b


# --------------------------------------------------------------------------------------------------- B1
def test_numpy_small_integer_seeds():
    """B1: ``seeds=np.int8(2)`` ran its budget in int8 (OverflowError); ``np.int16(20000)`` wrapped under the budget
    and fruit_fly_batch refused by its own ``rngs``."""
    from fusion.book.chapters import ci

    small = ci.fruit_fly_step_study(seeds=np.int8(2), target=0.8, seed=0)
    assert small.equals(ci.fruit_fly_step_study(seeds=2, target=0.8, seed=0))
    with pytest.raises(ValueError, match="seeds") as e:
        ci.fruit_fly_step_study(seeds=np.int16(20000), target=0.8, seed=0)
    assert "rngs" not in str(e.value)


#: (registry function, argument, the same value in another number type its check reads); the other checked values
#: now used (ml_gap, t_min, w_pub, ...) gave the same results before, through a later conversion
_CONVERTED = (("paired_numbers", "rmse_avg", lambda v: Decimal(repr(float(v)))),)


@pytest.mark.parametrize("fname, arg, kind", _CONVERTED, ids=[f"{f}-{a}" for f, a, _ in _CONVERTED])
def test_checked_value_is_used(fname, arg, kind):
    """B1: the value a check returns is the one used (a Decimal ``rmse_avg`` was divided by a float: TypeError)."""
    kw = _valid(REGISTRIES[2], CI + fname)
    want = _call(CI + fname, **kw)
    assert _same(_call(CI + fname, **{**kw, arg: kind(kw[arg])}), want)


# --------------------------------------------------------------------------------------------------- B2
#: A dict, then mappings that are not one: a view, a chain, a user mapping (no dict subclass)
_KINDS = (dict, collections.OrderedDict, types.MappingProxyType, collections.ChainMap, collections.UserDict)
_leaf = st.one_of(st.floats(allow_nan=False), st.integers(), st.text(max_size=3))
_tree = st.recursive(_leaf, lambda kids: st.dictionaries(st.text(max_size=3), kids, max_size=3), max_leaves=8)


@settings(max_examples=25, deadline=None)
@given(st.dictionaries(st.text(max_size=3), _tree, max_size=4), st.sampled_from(_KINDS))
def test_frozen_value_freezes_every_mapping(d, kind):
    """B2: any mapping (nested too) becomes a ReadOnlyMapping of its items, independent of the caller's and picklable."""
    from fusion._frozen import ReadOnlyMapping, frozen_value

    def wrap(x: Any) -> Any:
        return kind({k: wrap(v) for k, v in x.items()}) if isinstance(x, dict) else x

    src = wrap(d)
    out = frozen_value(src, copy=True)
    assert isinstance(out, ReadOnlyMapping) and out == d
    inner = [k for k, v in d.items() if isinstance(v, dict)]
    assert all(isinstance(out[k], ReadOnlyMapping) for k in inner)
    base = src.maps[0] if isinstance(src, collections.ChainMap) else getattr(src, "data", None)
    if base is not None:   # the caller changes what its mapping shows
        base["new key"] = 1.0
        assert "new key" not in out
    assert pickle.loads(pickle.dumps(out)) == d


def _mapping_fields() -> list[tuple[Any, str]]:
    """(object, field) for every ReadOnlyMapping field of every frozen result class of the four registries."""
    from fusion._frozen import ReadOnlyMapping

    seen, out = set(), []
    for name in REGISTRIES:
        for spec in _registry(name).values():
            for a in spec.values():
                v = a.value
                if not dataclasses.is_dataclass(v) or isinstance(v, type) or type(v) in seen:
                    continue
                seen.add(type(v))
                out += [(v, f.name) for f in dataclasses.fields(v) if isinstance(getattr(v, f.name), ReadOnlyMapping)]
    return out


def test_every_result_mapping_field_is_frozen():
    """B2: each mapping field rebuilt from a caller's MappingProxyType of a dict holds a copy: the caller's later
    change of the dict does not reach it, and it pickles (LedgerInputs, PairedInputs, IrInputs kept the proxy)."""
    from fusion._frozen import ReadOnlyMapping

    fields = _mapping_fields()
    assert len(fields) > 100   # every chapter's results (131 fields when written)
    kept = []
    for obj, name in fields:
        d = dict(getattr(obj, name))
        new = dataclasses.replace(obj, **{name: types.MappingProxyType(d)})
        first = next(iter(d))
        was = new.__dict__[name][first] if isinstance(new.__dict__[name], Mapping) else None
        d[first] = "changed by the caller"
        value = getattr(new, name)
        if not isinstance(value, ReadOnlyMapping) or value[first] is not was:
            kept.append(f"{type(obj).__name__}.{name}")
            continue
        pickle.dumps(value)
    assert not kept, kept


# --------------------------------------------------------------------------------------------------- B3, D4
def _no_draw(*args: Any, **kwargs: Any) -> Any:
    raise AssertionError("drew before refusing")


@pytest.mark.parametrize("call, name", [
    (lambda m: m.check_grid(eps_factors=(1.0,), biases=(5.0,), runs=3_000_000, samples=100, sigma=(0.5, 1.0, 1.5)),
     "runs, samples and sigma"),
    (lambda m: m.fault_shapes_study(0, n_runs=10**6), "n_runs")], ids=["check_grid", "fault_shapes_study"])
def test_memory_budget_before_any_draw(monkeypatch, call, name):
    """B3, D4: within the work budget (check_grid: 9e8 units), beyond the memory budget: refused by name before the
    generator is made (6.7 and 7.45 GiB were drawn)."""
    from fusion.book.chapters import ofs_fair
    from fusion.book.chapters.lecture_weighting import consistency

    monkeypatch.setattr(np.random, "default_rng", _no_draw)
    mod = consistency if "runs," in name else ofs_fair
    with pytest.raises(ValueError, match=f"{name} ask for an array"):
        call(mod)


def test_fault_shapes_study_is_public():
    """D4: the notebook's fault_shapes_study and fault_shapes_table are in their module's ``__all__``."""
    from fusion.book.chapters import ofs_fair

    assert {"fault_shapes_study", "fault_shapes_table"} <= set(ofs_fair.__all__)


# --------------------------------------------------------------------------------------------------- B4
def _fig5_tables() -> list[tuple[str, pd.DataFrame]]:
    hyp = _valid(REGISTRIES[2], CI + "ledger_inputs")["fig5_hyp"]
    other = _valid(REGISTRIES[2], CI + "fruit_fly_step_values")["table"]
    return [("another table", other), ("its first 2 rows", hyp.iloc[:2]), ("without tr P", hyp.drop(columns="tr P")),
            ("rows reversed", hyp.iloc[::-1])]


@pytest.mark.parametrize("label", ["another table", "its first 2 rows", "without tr P", "rows reversed"])
def test_fig5_hyp_is_fig5_hypotheses_table(label):
    """B4: a table ev_fig5 cannot read (KeyError 'tr P', IndexError) or would read wrongly (rows in another order)
    is refused when the inputs are built, naming the field."""
    from fusion.book.chapters import ci

    kw = _valid(REGISTRIES[2], CI + "ledger_inputs")
    with pytest.raises(ValueError, match="fig5_hyp"):
        ci.ledger_inputs(**{**kw, "fig5_hyp": dict(_fig5_tables())[label]})


# --------------------------------------------------------------------------------------------------- B5
@pytest.mark.parametrize("kind", _KINDS[2:], ids=lambda k: k.__name__)
def test_path_rows_any_mapping(kind):
    """B5: the documented "mapping" of rows: a MappingProxyType or ChainMap gave pandas' unnamed error."""
    from fusion.book.chapters import ci

    rows = _valid(REGISTRIES[2], CI + "path_period_table")["rows"]
    given_ = kind({k: kind(dict(v)) for k, v in rows.items()})
    assert ci.path_period_table(given_).equals(ci.path_period_table(rows))
    assert ci.path_numbers(given_) == ci.path_numbers(rows)


# --------------------------------------------------------------------------------------------------- B6
def _few_run_calls() -> dict[str, tuple[Any, str]]:
    """Reader -> (a call of it on valid few-run input, the argument its R4 refusal must name)."""
    import fusion.book.chapters.lecture_wavelets as wa
    from fusion.book.chapters import time_registration_ledger as trl
    from fusion.book.chapters.lecture_wavelets import records as lwr, verdicts
    from fusion.book.chapters.lecture_weighting import belief
    from fusion.scenarios import lecture_weighting as lw

    a, b = np.ones((3, 4)), np.ones((3, 4)) + 0.1
    return {"table_lengths": (lambda: wa.table_lengths({64: wa.length_study(64, runs=3)}), "studies[64]"),
            "evidence": (lambda: lwr.evidence({k: lwr.study(k, 2601, 3) for k in lwr.STUDIES}), "st"),
            "sensor_conjunction": (lambda: verdicts.sensor_conjunction(a, b, "A", "B", "m", 0), "a and b"),
            "sign_conjunction": (lambda: verdicts.sign_conjunction(a, b, "A", "B", 0), "a and b"),
            "glue_24": (lambda: belief.glue_24(lw.belief_study(snapshots=3)), "s holds"),
            "ledger_evidence": (lambda: trl.ledger_evidence(0, 3), "runs")}


@pytest.mark.parametrize("reader", ["table_lengths", "evidence", "sensor_conjunction", "sign_conjunction", "glue_24",
                                    "ledger_evidence"])
def test_few_runs_named_by_the_reader(reader):
    """B6: rule R4's refusal names the reader's argument, not the comparison's "a and b hold" nor "the argument
    reason", which none of them takes (nor eig_row_comparison's ``select`` inside glue_24)."""
    call, name = _few_run_calls()[reader]
    with pytest.raises(ValueError) as e:
        call()
    msg = str(e.value)
    assert msg.startswith(name) and "the argument reason" not in msg and "select" not in msg


def test_typical_run_keeps_the_reason():
    """B6: the sign test of a comparison that gives a reason for its few runs reads them with that reason
    (typical_run and table_typical refused it as "a and b")."""
    import fusion.book.chapters.lecture_wavelets as wa
    from fusion.book.ledger import Comparison

    x = np.arange(3.0)
    c = Comparison(x, x + 1, "A", "B", "less", "m", reason="three runs suffice for this test")
    assert wa.typical_run(c).reason == c.reason
    assert len(wa.table_typical({"r": {"primary": c}})) == 1


# --------------------------------------------------------------------------------------------------- D1, D2
#: (registry, function, table argument)
_TABLES = ((REGISTRIES[0], "fusion.book.chapters.ofs.figure_mc", "table"),
           (REGISTRIES[0], "fusion.book.chapters.ofs.mc_numbers", "mc"),
           (REGISTRIES[0], "fusion.book.chapters.time_registration.benchmark_numbers", "bench"),
           (REGISTRIES[0], "fusion.book.chapters.time_registration.named_crossings", "crossings"),
           (REGISTRIES[2], CI + "slip_numbers", "slip"),
           (REGISTRIES[2], CI + "architecture_numbers", "arch_table"))


def _big_endian(df: pd.DataFrame) -> pd.DataFrame:
    out = df.copy()
    for c in out.columns:
        if out[c].dtype.kind == "f":
            out[c] = out[c].to_numpy().astype(">f8")
    return out


@pytest.mark.parametrize("reg, fname, arg", _TABLES, ids=[f.rsplit(".", 1)[1] for _, f, _ in _TABLES])
def test_big_endian_columns_named(reg, fname, arg):
    """D1 (decided: refused by the readers' rule): pandas reads native byte order only; its "Big-endian buffer"
    error named nothing, and two readers said the table differs."""
    kw = _valid(reg, fname)
    with pytest.raises(ValueError, match=rf"^{arg}\[.*non-native byte order"):
        _call(fname, **{**kw, arg: _big_endian(kw[arg])})


def test_benchmark_pairs_results_in_their_order():
    """D2 (decided: documented): the same results in another key order are another benchmark's first seed, so a
    ``stab`` of the original order is refused by name."""
    fname = "fusion.book.chapters.lecture_weighting.readings_benchmark.table_benchmark"
    kw = _valid(REGISTRIES[1], fname)
    reordered = dict(reversed(list(kw["results"].items())))
    with pytest.raises(ValueError, match="^stab must be seed_stability"):
        _call(fname, **{**kw, "results": reordered})
