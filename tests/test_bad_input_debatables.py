"""The debatable findings of fuzz 17, decided (issue 35).

Each decision is one rule, stated in the docstring of the function or shared check that enforces it, and tested
here: by a property over every argument of its kind in the registry of ``test_bad_input`` where the rule belongs to
the shared validation (text options, scalars, seeds), and by the fuzz's reproducer where it belongs to one chapter.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest

from test_bad_input import REG, _excluded
from test_bad_input_classes import SLOW, _is_number, _names
from test_bad_input_classes import call as classes_call
from _helpers import parsed

# --------------------------------------------------------------------------------------------
# comparing two results
# --------------------------------------------------------------------------------------------


def same(a: Any, b: Any) -> bool:
    """Whether two results are equal: arrays and floats exactly (NaN equal to NaN), containers and frozen
    dataclasses field by field (timings left out), anything else by ``==``."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype.kind in "fc" or b.dtype.kind in "fc":
            return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=True))
        return a.shape == b.shape and bool((a == b).all())
    if isinstance(a, (float, np.floating)) and isinstance(b, (float, np.floating)):
        return (math.isnan(a) and math.isnan(b)) or a == b
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return type(a) is type(b) and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(same(getattr(a, f.name), getattr(b, f.name))
                                          for f in dataclasses.fields(a) if "time" not in f.name)
    if callable(a) and callable(b):
        return True
    if type(a).__eq__ is object.__eq__ and hasattr(a, "__dict__"):  # a plain object: its attributes
        return type(a) is type(b) and same(vars(a), vars(b))
    try:
        return bool(a == b)
    except Exception:  # noqa: BLE001 - incomparable objects (a DataFrame): equal enough when both calls succeeded
        return True


def call(name: str, arg: str, value: Any) -> tuple[str, Any]:
    """The registry call of ``test_bad_input_classes`` with every argument fresh (deep copies: a list of generators
    or a callable with state starts from the same state in the two calls compared)."""
    return classes_call(name, arg, value, fresh=True)


_VALID: dict[str, tuple[str, Any]] = {}


def plain_call(name: str, arg: str, plain: Any) -> tuple[str, Any]:
    """:func:`call` with ``arg = plain``. When ``plain`` is the registry's own value of ``arg`` (an int, float or
    str of the same type), that is the registry's valid call of ``name``, whatever ``arg``: made once per callable."""
    v = REG[name][arg].value
    if not (type(plain) is type(v) and isinstance(v, (int, float, str)) and plain == v):
        return call(name, arg, plain)
    if name not in _VALID:
        _VALID[name] = call(name, arg, plain)
    return _VALID[name]


def assert_same_or_refused(name: str, arg: str, value: Any, plain: Any) -> None:
    """The call with ``value`` equals the call with ``plain``, or raises a ValueError/TypeError naming ``arg``."""
    how, out = call(name, arg, value)
    if how == "raised":
        assert isinstance(out, (ValueError, TypeError)), f"{name}: {arg}: {type(out).__name__}: {out}"
        assert _names(out, arg), f"{name}: {arg}: message does not name it: {out}"
        return
    how0, ref = plain_call(name, arg, plain)
    assert how0 == "ok", f"{name}: the plain call raised {ref!r}"
    assert same(out, ref), f"{name}: {arg} = {type(value).__name__}: a result different from the plain value's"


# --------------------------------------------------------------------------------------------
# a. a str subclass whose own comparison raises, as a text option
# --------------------------------------------------------------------------------------------

#: The registry's callables (the book's presentation helpers included, the slow network studies left out).
NAMES = sorted(n for n in REG if not _excluded(n) and n not in SLOW)
#: Text options of the registry (their "unknown" mutation is refused).
OPTIONS = [(n, a) for n in NAMES for a, spec in REG[n].items()
           if isinstance(spec.value, str) and "unknown" in spec.mutations]


class _ExplodingEq(str):
    """A text option whose own ``==`` raises (fuzz 17)."""

    def __eq__(self, other: object) -> bool:
        raise RuntimeError("eq")

    __hash__ = str.__hash__


class _ExplodingHash(str):
    """A text option whose own ``hash`` raises."""

    def __hash__(self) -> int:
        raise RuntimeError("hash")


class _Lying(str):
    """A text option equal to everything."""

    def __eq__(self, other: object) -> bool:
        return True

    __hash__ = str.__hash__


class _Plain(str):
    """A well-behaved str subclass: it is its text."""


def test_the_registry_has_text_options() -> None:
    assert len(OPTIONS) > 50


@pytest.mark.parametrize("target", OPTIONS, ids=[f"{n}:{a}" for n, a in OPTIONS])
@pytest.mark.parametrize("kind", [_ExplodingEq, _ExplodingHash, _Lying])
def test_a_text_option_whose_own_comparison_misbehaves_is_refused_by_name(target: tuple[str, str],
                                                                          kind: type) -> None:
    name, arg = target
    value = REG[name][arg].value
    how, out = call(name, arg, kind(value))
    assert how == "raised", f"{name}: {arg} = {kind.__name__}({value!r}) accepted"
    assert isinstance(out, TypeError) and _names(out, arg), f"{name}: {arg}: {type(out).__name__}: {out}"


@pytest.mark.parametrize("target", OPTIONS, ids=[f"{n}:{a}" for n, a in OPTIONS])
def test_a_text_option_given_as_a_well_behaved_str_subclass_is_its_text(target: tuple[str, str]) -> None:
    name, arg = target
    value = REG[name][arg].value
    assert_same_or_refused(name, arg, _Plain(value), value)
    assert_same_or_refused(name, arg, np.str_(value), value)


# --------------------------------------------------------------------------------------------
# b. a float subclass whose __float__ disagrees with its value
# --------------------------------------------------------------------------------------------

#: Real scalars of the registry (their NaN is refused).
SCALARS = [(n, a) for n in NAMES for a, spec in REG[n].items()
           if _is_number(spec.value) and isinstance(spec.value, float) and "nan_s" in spec.mutations]


class _Disagreeing(float):
    """A float whose stored value is ``stored`` but whose ``__float__`` (what numpy reads) says ``number``."""

    def __new__(cls, stored: float, number: float) -> _Disagreeing:
        obj = super().__new__(cls, stored)
        obj.number = number
        return obj

    def __float__(self) -> float:
        return self.number


def test_numpy_reads_a_float_subclass_through_its_float() -> None:
    """The rule the shared scalar reader follows is numpy's for arrays: the number is what ``__float__`` says."""
    x = _Disagreeing(3.0, 1.0)
    assert np.asarray([x], dtype=float)[0] == 1.0 and np.asarray(x, dtype=float) == 1.0
    assert np.asarray([x, 2.0])[0] == 1.0


def test_the_registry_has_scalars() -> None:
    assert len(SCALARS) > 100


@pytest.mark.parametrize("target", SCALARS, ids=[f"{n}:{a}" for n, a in SCALARS])
def test_a_float_subclass_is_the_number_its_float_gives_on_every_path(target: tuple[str, str]) -> None:
    """The scalar is read once, through ``__float__``, and only that number reaches the computation: the result
    equals the plain call with that number (or the value is refused by name), whatever the stored value."""
    name, arg = target
    v = REG[name][arg].value
    assert_same_or_refused(name, arg, _Disagreeing(2.0 * v + 1.0, v), v)


# --------------------------------------------------------------------------------------------
# c. a 0-d integer array is a seed, as it is a count
# --------------------------------------------------------------------------------------------

#: Integer seeds of the registry.
SEEDS = [(n, a) for n in NAMES for a, spec in REG[n].items()
         if "seed" in a and _is_number(spec.value) and not isinstance(spec.value, float)]


def test_the_registry_has_seeds() -> None:
    assert len(SEEDS) > 20


@pytest.mark.parametrize("target", SEEDS, ids=[f"{n}:{a}" for n, a in SEEDS])
def test_a_0d_integer_array_is_the_seed_it_holds(target: tuple[str, str]) -> None:
    """One rule with counts (rule 13) and with ``numpy.random.default_rng``: ``np.array(s)`` is the seed ``s``, and
    what a result stores of it is the plain int (never the caller's array)."""
    name, arg = target
    s = int(REG[name][arg].value)
    how, out = call(name, arg, np.array(s))
    assert how == "ok", f"{name}: {arg} = np.array({s}) refused: {out!r}"
    how0, ref = plain_call(name, arg, s)
    assert how0 == "ok" and same(out, ref), f"{name}: {arg} = np.array({s}): a result different from seed {s}'s"
    stored = [getattr(out, f.name) for f in dataclasses.fields(out)] if dataclasses.is_dataclass(out) else []
    assert not any(isinstance(v, np.ndarray) and v.ndim == 0 for v in stored), f"{name}: stores the 0-d array"


@pytest.mark.parametrize("bad", [np.array(True), np.array(3.0), np.array([3]), np.array(-1)])
def test_a_0d_array_that_is_not_a_non_negative_integer_is_not_a_seed(bad: np.ndarray) -> None:
    from fusion._validation import seed
    with pytest.raises((TypeError, ValueError), match="^seed "):
        seed(bad, "seed")


#: Seed checks whose value is never used as a seed: a key of a results dict read from a file (a 0-d array is not
#: hashable, so it cannot be one).
SEED_CHECKS_WITHOUT_USE = {"scenarios/lecture_weighting/readings_benchmark.py"}


def test_every_seed_check_hands_on_the_int_it_read() -> None:
    """An AST scan of ``fusion/``: a call of the shared seed reader (imported as ``check_seed``, ``_seed`` or
    ``V_seed``) is never a bare statement, whose result would be dropped and the caller's object (a 0-d array,
    which ``numpy.random.default_rng`` refuses) used instead."""
    import ast
    from pathlib import Path

    import fusion

    readers = {"check_seed", "_seed", "V_seed"}
    root = Path(fusion.__file__).resolve().parent
    found = []
    for path in sorted(root.rglob("*.py")):
        rel = str(path.relative_to(root))
        if rel in SEED_CHECKS_WITHOUT_USE or rel.endswith("_lecture_checks.py"):
            continue
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Expr):
                calls = node.value.elts if isinstance(node.value, ast.Tuple) else [node.value]
                found += [f"{rel}:{node.lineno}" for c in calls if isinstance(c, ast.Call)
                          and isinstance(c.func, ast.Name) and c.func.id in readers]
    assert found == []


# --------------------------------------------------------------------------------------------
# d. an evidence function's run count is checked even where its reading is exact
# --------------------------------------------------------------------------------------------

def _evidence_functions_that_ignore_runs() -> list[tuple[str, str]]:
    """Every ``ev_*`` of the chapters with a ``runs`` parameter its body never reads (an AST scan).

    Run at collection by every worker: only the modules whose text holds a ``def`` of an ``ev_`` name are walked (a
    function definition named ``ev_*`` is that text in its source), the same list; walking every node of every
    chapter module cost about 1.6 CPU-s a worker."""
    import ast
    import re
    from pathlib import Path

    import fusion

    root = Path(fusion.__file__).resolve().parent
    out = []
    for path in sorted((root / "book" / "chapters").rglob("*.py")):
        if not re.search(r"\bdef[\s\\]+ev_", path.read_text(encoding="utf-8")):
            continue
        module = ".".join(path.relative_to(root.parent).with_suffix("").parts)
        for fn in ast.walk(parsed(path)):
            if isinstance(fn, ast.FunctionDef) and fn.name.startswith("ev_") \
                    and "runs" in [a.arg for a in fn.args.args + fn.args.kwonlyargs]:
                body = [n for stmt in fn.body for n in ast.walk(stmt)]
                reads = any(isinstance(n, ast.Name) and n.id == "runs" and isinstance(n.ctx, ast.Load) for n in body)
                if not reads or any(isinstance(n, ast.Call) and getattr(n.func, "id", "") == "count"
                                    and n.args and getattr(n.args[0], "id", "") == "runs" and not any(
                                        isinstance(m, ast.Name) and m.id == "runs" and isinstance(m.ctx, ast.Load)
                                        and m is not n.args[0] for m in body) for n in body):
                    out.append((module, fn.name))
    return out


UNUSED_RUNS = _evidence_functions_that_ignore_runs()


def test_the_scan_finds_the_exact_readings() -> None:
    assert ("fusion.book.chapters.chernoff.evidence", "ev_common_once") in UNUSED_RUNS and len(UNUSED_RUNS) >= 10


@pytest.mark.parametrize("target", UNUSED_RUNS, ids=[f"{m}:{f}" for m, f in UNUSED_RUNS])
@pytest.mark.parametrize("runs", [0, -1, 2.0, "100"])
def test_an_exact_readings_runs_is_still_a_count(target: tuple[str, str], runs: Any) -> None:
    """``ev_common_once({}, seed=0, runs=0)`` ran its 100 fixed cases: an exact reading does not use ``runs``, but a
    value that is no run count is refused by name, as in every other evidence function."""
    import importlib

    fn = getattr(importlib.import_module(target[0]), target[1])
    with pytest.raises((ValueError, TypeError), match=r"^runs "):
        fn({}, seed=0, runs=runs)


# --------------------------------------------------------------------------------------------
# e. the James-Stein table's Monte-Carlo column needs the book's minimum of runs
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("runs", [1, 2, 99])
def test_the_james_stein_table_refuses_fewer_runs_than_the_books_minimum(runs: int) -> None:
    """``table_james_stein(runs=1)`` printed one draw (3.1) beside the exact 0.76 as if it were an estimate."""
    from fusion.book.chapters.lecture_correlated import appendix as lca

    with pytest.raises(ValueError, match=r"^runs .*>= 100"):
        lca.table_james_stein((3,), (1.0,), runs, 0)
    tab = lca.table_james_stein((3,), (1.0,), 100, 0)
    with pytest.raises(ValueError, match=r"^runs .*>= 100"):
        lca.glue_james_stein(tab, runs=runs)


def test_the_james_stein_table_at_the_minimum_is_an_estimate_of_the_exact_ratio() -> None:
    """At 100 draws the Monte-Carlo column is within a few standard errors of the exact one (d = 5, 10: the loss
    has a finite variance there; per-draw SD at most 0.7, so 4 SE < 0.3)."""
    from fusion.book.chapters.lecture_correlated import appendix as lca

    tab = lca.table_james_stein((5, 10), (0.0, 1.0, 3.0, 10.0), 100, 0)
    assert float((tab["Monte Carlo"] - tab["exact"]).abs().max()) < 0.3


# --------------------------------------------------------------------------------------------
# f. time registration: the record's instants and the latency's domain
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("call, arg", [
    (lambda trl: trl.cost_count([0.0, 1.0, 2.0], [0.5, 0.2]), "t2"),           # not increasing
    (lambda trl: trl.cost_count([0.0, 1.0], [0.5]), "t1"),                     # fewer than three samples
    (lambda trl: trl.cost_count([0.0, 1.0, 2.0], [3.0]), "t2"),                # an instant after the record
    (lambda trl: trl.noise_gain_by_instant([0.0, 1.0, 2.0], [3.0]), "t2"),     # a query outside the data
    (lambda trl: trl.noise_gain_by_instant([0.0, 1.0, 2.0], [-1.0]), "t2"),
    (lambda trl: trl.noise_gain_by_instant([0.0, 1.0], [2.0]), "t1"),
])
def test_the_records_instants_are_checked_by_name(call: Any, arg: str) -> None:
    from fusion.book.chapters import time_registration_ledger as trl

    with pytest.raises(ValueError, match=rf"^{arg} "):
        call(trl)


def test_the_noise_gains_are_those_of_the_samples_given() -> None:
    """Mid-interval of t1's own samples: (-1/8, 3/4, 3/8) and (1/2, 1/2), gains 46/64 and 1/2 (the docstring's);
    they used to be computed on the scenario's samples whatever t1 was (0.63 and 0.625 here)."""
    from fusion.book.chapters import time_registration_ledger as trl

    g = trl.noise_gain_by_instant([0.0, 1.0, 2.0], [1.5])
    assert g["g three-point"].iloc[0] == pytest.approx(46 / 64) and g["g two-point"].iloc[0] == pytest.approx(0.5)


@pytest.mark.parametrize("delay", [1e9, 1.5, -1.5, -1e9])
def test_a_latency_outside_the_flight_is_refused_by_name(delay: float) -> None:
    """``delay_table([1e9], [1.0])`` gave -4.2e23 m²: the truth is the UAV's from t = 0 to the end of the 40 s
    record, so sensor 1's true sample times ``t - delay`` (1 s to 39 s stamped) allow -1 s <= delay <= 1 s."""
    from fusion.book.chapters import time_registration as tr
    from fusion.scenarios import time_registration as sc

    with pytest.raises(ValueError, match=r"^delays\[0\] "):
        tr.delay_table([delay], [1.0])
    with pytest.raises(ValueError, match=r"^delay "):
        sc.expected(sc.RegMethod.TWO_POINT, 1.0, delay=delay)


@pytest.mark.parametrize("delay", [-1.0, -0.02, 0.0, 0.03, 1.0])
def test_a_latency_within_the_flight_negative_included_is_a_latency(delay: float) -> None:
    """A negative latency (the sample taken after its stamp) is the appendix's own reading (-20 and -10 ms)."""
    from fusion.book.chapters import time_registration as tr

    assert np.isfinite(tr.delay_table([delay], [1.0]).to_numpy()).all()


# --------------------------------------------------------------------------------------------
# g. a fault size is a magnitude
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("arg, kwargs", [("sizes", dict(sizes=(-1.0,), counts=(0,))),
                                         ("sizes", dict(sizes=(2.0, -0.5), counts=(0,))),
                                         ("opposite", dict(sizes=(1.0,), counts=(0,), opposite=(-2.0,)))])
def test_a_negative_fault_size_is_refused_by_name(arg: str, kwargs: dict[str, Any]) -> None:
    from fusion.book.chapters import ofs_fair

    with pytest.raises(ValueError, match=rf"^{arg}\[\d\] must be non-negative"):
        ofs_fair.fair_study(0, 2, 2, **kwargs)


def test_a_zero_fault_size_is_the_point_without_a_fault() -> None:
    """Size 0 is valid (the chapter's sweep starts there): two 'faulty' sensors with a zero bias are the clean
    readings, whose errors equal the zero-count point's."""
    from fusion.book.chapters import ofs_fair

    st = ofs_fair.fair_study(0, 3, 4, sizes=(0.0,), counts=(0,), spreads=(1.0,), opposite=(0.0,))
    clean = st.mae[(ofs_fair.COUNT, 0.0)]
    assert same(st.mae[(ofs_fair.SIZE, 0.0)], clean) and same(st.mae[(ofs_fair.OPPOSITE, 0.0)], clean)


# --------------------------------------------------------------------------------------------
# h. the book's number formatters: one rule for non-numbers and non-finite numbers
# --------------------------------------------------------------------------------------------

def _formatters() -> list[tuple[str, str, Any]]:
    """(name, argument, callable) of every number formatter of the book layer."""
    from fusion.book import ledger, tables
    from fusion.book.chapters import ci, lecture

    return [("tables.sci", "x", tables.sci), ("ledger.fmt", "x", ledger.fmt), ("ci.readable", "x", ci.readable),
            ("ci.excess_text", "excess", ci.excess_text), ("lecture.sci", "value", lecture.sci),
            ("tables.roundoff", "value", tables.roundoff)]


FORMATTERS = _formatters()
#: Non-numbers every formatter refuses with a TypeError naming its argument (``None`` and bools: see below).
NON_NUMBERS = ["1", "nan", b"1", 1 + 0j, [1.0], {"x": 1.0}, object()]


@pytest.mark.parametrize("fmt", FORMATTERS, ids=[f[0] for f in FORMATTERS])
@pytest.mark.parametrize("value", NON_NUMBERS, ids=[type(v).__name__ for v in NON_NUMBERS])
def test_a_formatter_refuses_a_non_number_by_name(fmt: tuple[str, str, Any], value: Any) -> None:
    """``lecture.sci('1')`` printed 1: text is never read as a number."""
    name, arg, f = fmt
    with pytest.raises(TypeError, match=rf"^{arg} "):
        f(value)


@pytest.mark.parametrize("fmt", FORMATTERS, ids=[f[0] for f in FORMATTERS])
@pytest.mark.parametrize("value, word", [(float("nan"), "—"), (np.float64("nan"), "—"), (float("inf"), "∞"),
                                         (-float("inf"), "-∞"), (np.float32("inf"), "∞")])
def test_a_non_finite_number_is_printed_as_the_books_word_or_refused_by_the_residual_check(
        fmt: tuple[str, str, Any], value: float, word: str) -> None:
    """One rule (``fusion.book.tables.NONFINITE_RULE``): NaN reads ``—`` and the infinities ``∞``/``-∞`` in every
    formatter (``ci.readable(nan)`` said ``n/a``, ``lecture.sci(nan)`` said ``nan``); ``roundoff`` formats a check's
    residual and ``excess_text`` a search's distance to the minimum, finite by definition: they refuse them by name
    (a word would hide a failed check or search)."""
    name, arg, f = fmt
    if name in ("tables.roundoff", "ci.excess_text"):
        with pytest.raises(ValueError, match=rf"^{arg} must be finite"):
            f(value)
        return
    assert f(value) == word


@pytest.mark.parametrize("fmt", FORMATTERS, ids=[f[0] for f in FORMATTERS])
def test_none_and_bools_are_words_of_a_table_cell_only(fmt: tuple[str, str, Any]) -> None:
    """``tables.sci`` writes a table cell: ``None`` is a missing cell (``—``) and a bool ``yes``/``no``, as its
    docstring says; every other formatter refuses them by name (a bool is not a number, rule 10)."""
    name, arg, f = fmt
    if name == "tables.sci":
        assert (f(None), f(True), f(np.bool_(False))) == ("—", "yes", "no")
        return
    for v in (None, True, np.bool_(False)):
        with pytest.raises(TypeError, match=rf"^{arg} "):
            f(v)


def test_the_formatters_are_every_number_formatter_of_the_book() -> None:
    """Every public function of ``fusion.book`` whose first parameter is annotated ``float`` and which returns a
    ``str`` is in :data:`FORMATTERS` (a new one must follow the rule), keys and labels excepted."""
    import ast
    from pathlib import Path

    import fusion

    keys = {"alpha_key"}  # a method key (validated positive), not a number printed for the reader
    root = Path(fusion.__file__).resolve().parent / "book"
    found = set()
    for path in sorted(root.rglob("*.py")):
        for fn in parsed(path).body:
            if isinstance(fn, ast.FunctionDef) and not fn.name.startswith("_") and fn.returns is not None \
                    and ast.unparse(fn.returns) == "str" and fn.args.args and fn.args.args[0].annotation is not None \
                    and ast.unparse(fn.args.args[0].annotation) == "float" and fn.name not in keys:
                found.add(fn.name)
    assert found == {n.split(".")[1] for n, _, _ in FORMATTERS}


# --------------------------------------------------------------------------------------------
# i. the two tracks of per_step_weights are one simulation's
# --------------------------------------------------------------------------------------------

def test_per_step_weights_refuses_tracks_of_different_runs_by_name() -> None:
    """Tracks of 3 and 2 runs were accepted (only their covariances are read): they are not a pair of one scenario,
    and ``fuse_tracks`` refuses them; so does ``per_step_weights`` now, naming ``a`` and ``b``."""
    from test_bad_input import _objects

    from fusion.filtering.tracks import local_track
    from fusion.scenarios import two_sensor

    o = _objects()
    ta, z, x0 = o["ta"], o["z"], o["x0"]
    assert z.shape[0] == 3
    tb_runs = local_track(z[:2], o["F"], o["H"], o["Q"], 2 * o["R"], x0[:2], 0.5 * o["P0"], 0.5 * o["P0"])
    with pytest.raises(ValueError, match=r"^a and b must be tracks of one simulation"):
        two_sensor.per_step_weights(ta, tb_runs, seed=0)
    w = two_sensor.per_step_weights(ta, o["tb"], seed=0, n_grid=11, population=5, iterations=5)
    assert all(np.all((v >= 0) & (v <= 1)) for v in w)
