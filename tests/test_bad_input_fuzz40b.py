"""Fuzz 40b (book layer): what ``Ledger.records()`` stores for valid evidence is read back (C1, D1); ``brief()`` of
an infinite mean with few runs (C9); the median interval's level needs values (C10); the study cache's entries that
are not regular files or whose bytes changed are misses (C2, C3); ``parameters_matching`` returns roots only (C4);
``claims.evaluate`` refuses an evidence function that cannot take its arguments (C5); ``stability.tasks`` refuses
runs beyond the ceiling and a sweep beyond the work budget (C6, C7); the iterables of ``recommend.check`` have the
ceiling of an iterable's items (C8); float32 and float16 glue values as the decimal that prints them (D2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from _helpers import CACHE_CALLS, cached_study, study_entry


def _ledger(evidence):
    from fusion.book.ledger import SOURCES, Claim, Ledger

    src = sorted(SOURCES)[0]
    led = Ledger(src)
    led.add(Claim(id="x-y", source=src, where="T1", claim="c", published="q", evidence=evidence, link="l",
                  headline=True))
    return led


def _records(evidence) -> list[dict]:
    return _ledger(evidence).records()


@pytest.mark.parametrize("a, b", [
    ([1.0] * 100, [2.0] * 99 + [math.inf]),                         # C1: B's mean infinite (mean_b None)
    ([math.inf] * 5 + [1.0] * 95, [2.0] * 55 + [math.inf] * 45),    # D1: both infinite, median interval [-inf, -1]
])
def test_margin_sensitivity_reads_what_the_ledger_stores_for_an_infinite_mean(a, b):
    """C1, D1: a ledger made by Ledger.records() from valid R3 evidence was refused ("mean_b must be a number, got
    None"); an infinite baseline mean gives no relative margin, so no row (as an infinite A's mean already gave)."""
    from fusion.book.chapters.ofs_fair import margin_sensitivity
    from fusion.book.ledger import Comparison

    records = _records(Comparison(a, b, "A", "B", "less", "err", seed=1))
    ev = records[0]["evidence"]
    assert ev["mean_b"] is None
    assert margin_sensitivity({"claims": records}).empty


def test_margin_sensitivity_still_refuses_one_open_end_with_a_finite_baseline():
    """No valid evidence stores one ``None`` end beside a finite ``mean_b`` (only R3's median of two infinite means
    has an infinite end): still refused by name."""
    from fusion.book.chapters.ofs_fair import margin_sensitivity
    from fusion.book.ledger import Comparison

    records = _records(Comparison([1.0 + 0.01 * i for i in range(100)], [2.0] * 100, "A", "B", "less", "err", seed=1))
    assert isinstance(records[0]["evidence"]["mean_b"], float)
    records[0]["evidence"]["ci_high"] = None
    with pytest.raises((TypeError, ValueError), match=r"ledger\['claims'\]\[0\]\['evidence'\]\['ci_high'\]"):
        margin_sensitivity({"claims": records})


@pytest.mark.parametrize("a, b, declared", [([math.inf, 1.0, 2.0], [1.0] * 3, ()), ([3.0] * 5, [1.0] * 5, ("a",)),
                                            ([1.0] * 2, [2.0, math.inf], ())])
def test_brief_of_an_infinite_mean_with_few_runs(a, b, declared, tmp_path):
    """C9: brief() of valid R3 evidence with 2-5 runs (a reason given) raised "d must hold at least 6 values", and so
    did Claim.to_dict, Ledger.records() and Ledger.write(); it now gives the infinite mean without a median interval,
    as summary() does."""
    from fusion.book.ledger import Comparison

    c = Comparison(a, b, "A", "B", "less", "err", reason="pilot", infinite_mean=declared)
    text = c.brief()
    assert "infinite mean" in text and f"{len(a)} runs" in text and "[" not in text
    assert _records(c)[0]["evidence"]["runs"] == len(a)
    assert _ledger(c).write(tmp_path) and list(tmp_path.glob("*.json"))   # written (its digest returned)


def test_brief_of_an_infinite_mean_keeps_its_median_interval_from_six_runs():
    from fusion.book.ledger import Comparison

    c = Comparison([math.inf] + [1.0] * 5, [2.0] * 6, "A", "B", "less", "err", reason="pilot")
    assert c.brief() == "A: infinite mean vs B 2.000; median difference -1.000 [-1.000, ∞], 6 runs"


@pytest.mark.parametrize("n, level, need", [(6, 0.99, 8), (8, 0.999, 11), (7, 0.99, 8), (53, 1 - 1e-16, 54)])
def test_median_interval_refuses_too_few_values_for_its_level(n, level, need):
    """C10: [min, max] of 6 values was returned at level 0.99; its coverage is 1 - 2 * 2**-6 = 0.969."""
    from fusion.book.rulebook import median_interval, median_values_needed

    assert median_values_needed(level) == need
    with pytest.raises(ValueError, match=rf"^d must hold at least {need} values for level .*, got {n}$"):
        median_interval(np.arange(float(n)), level=level)
    med, lo, hi = median_interval(np.arange(float(need)), level=level)
    assert (lo, hi) == (0.0, need - 1.0) and 1 - 2 * 0.5 ** need >= level


def test_median_interval_at_the_books_level_is_unchanged():
    from fusion.book.rulebook import median_interval, median_values_needed

    assert median_values_needed() == median_values_needed(0.96875) == 6 and median_values_needed(0.97) == 7
    assert median_interval(np.arange(6.0)) == (2.5, 0.0, 5.0)
    assert median_interval(np.arange(100.0)) == (49.5, 39.0, 60.0)


# --- C2, C3: the study cache's entries ------------------------------------------------------------------------------

_CALLS, _cached_study, _cache = CACHE_CALLS, cached_study, study_entry   # one tiny cached study (tests/_helpers)


class _Hang(BaseException):   # not caught as an unreadable entry
    pass


def _alarm(signum, frame):
    raise _Hang("blocked for 30 s")


@pytest.mark.parametrize("where", [".pkl", ".lock"])
def test_a_fifo_in_place_of_an_entry_or_its_lock_is_a_miss_without_blocking(where, tmp_path, monkeypatch):
    """C2: a FIFO at ``<key>.pkl`` or ``<key>.lock`` made every cached call block for ever in ``open()``."""
    import os
    import signal

    entry = _cache(tmp_path, monkeypatch)
    path = entry.with_suffix(where)
    path.unlink()
    os.mkfifo(path)
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(30)
    try:
        value = _cached_study(5)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    assert np.array_equal(value, np.arange(5) * 1.5) and _CALLS == [5, 5]   # a miss: computed
    if where == ".pkl":
        assert entry.is_file()   # and rewritten over the FIFO
        _cached_study.cache_clear()
        assert np.array_equal(_cached_study(5), value) and _CALLS == [5, 5]   # loaded


def test_a_changed_byte_of_a_stored_entry_is_a_miss(tmp_path, monkeypatch):
    """C3: one changed float of a stored array loaded silently ([0, 1.5, 3.25, 4.5, 6]); the module promises the
    computed values bit for bit. The entry's digest finds it: a miss, recomputed and rewritten."""
    import struct

    entry = _cache(tmp_path, monkeypatch)
    good = entry.read_bytes()
    at = good.find(struct.pack("<d", 3.0))
    assert at > 0
    entry.write_bytes(good[:at] + struct.pack("<d", 3.25) + good[at + 8:])
    assert np.array_equal(_cached_study(5), np.arange(5) * 1.5) and _CALLS == [5, 5]
    assert entry.read_bytes() == good


# --- C4: parameters_matching returns roots only -----------------------------------------------------------------------

def _numeric_options():
    from fusion.book.audit import _NOT_NUMERIC
    from fusion.readings.fusion_set import METHODS

    return [(m, o) for m, (_, opts) in METHODS.items() for o in opts if o not in _NOT_NUMERIC]


@pytest.mark.parametrize("method, name", _numeric_options())
@pytest.mark.parametrize("target", [900.5, 905.0, 910.0])
def test_parameters_matching_returns_only_values_where_the_fused_value_is_the_target(method, name, target):
    """C4: for belief_degree's step options (binary_eps, limit, and a jump of scale) brentq converged onto a jump of
    the fused value and returned it as a root ([0.3, 49.6] for 905, where the fused value is 900.25 and 904.33).
    Every option of every method: each value returned gives the target to round-off (the documented tie)."""
    from fusion.book.audit import parameters_matching
    from fusion.readings.fusion_set import fuse_epochs

    x = np.array([900.1, 901.3, 899.7, 950.0, 900.4])
    for r in parameters_matching(x, target, method, name, 1e-3, 1e3):
        fused = fuse_epochs(x, method, **{name: float(r)}).values[0]
        assert abs(fused - target) <= 1e-9 * 950.0, (method, name, r, fused)


def test_parameters_matching_still_finds_the_roots_of_a_continuous_option():
    from fusion.book.audit import parameters_matching

    x = np.array([900.1, 901.3, 899.7, 950.0, 900.4])
    assert parameters_matching(x, 905.0, "support_degree", "alpha", 1e-3, 1e3).size == 1
    assert parameters_matching(x, 905.0, "fusion_set_weights", "scale", 1e-3, 1e3).size == 2
    assert parameters_matching(x, 905.0, "belief_degree", "scale", 1e-3, 1e3).size == 1   # its jump dropped


# --- C5: evaluate calls an evidence function only as its signature allows ----------------------------------------------

def _deterministic_records():
    import inspect

    from fusion.book import claims as C

    out = []
    for cf in C.load_all(C.claims_dir()).values():
        for spec in cf.records:
            if spec.evidence:
                fn = C._evidence_function(spec.evidence, "")
                try:
                    inspect.signature(fn).bind({}, seed=0, runs=1)
                except TypeError:
                    out.append(spec)
    return out


class _Drawn(BaseException):
    """Raised at the first draw of an evidence function: evaluate called it."""


def test_evaluate_refuses_the_books_deterministic_records_naming_their_evidence_field(monkeypatch):
    """C5: 23 evidence functions of the book's claim files (every lecture_weighting ev_*, ci's ev_headline, ...) take a
    chapter's studies, not ``(settings, seed=, runs=)``: evaluate raised a raw TypeError ("unexpected keyword argument
    'seed'") or the function's own refusal of a dict. Each such record is deterministic (the ledger's primary evidence
    has no run count) and refused by a ClaimsFileError naming the field evidence, before the call; every stochastic
    record (as the stability sweep reads them) is called, up to its first draw. Review 18: their count was pinned."""
    import time

    from fusion.book import claims as C
    from fusion.book import stability as S

    stochastic = {rid for _, rid in S.stochastic_readings()}
    unbound = {spec.id for spec in _deterministic_records()}
    assert unbound and not unbound & stochastic
    specs = {spec.id: spec for cf in C.load_all(C.claims_dir()).values() for spec in cf.records if spec.evidence}
    assert stochastic <= set(specs)

    def drawn(*args, **kwargs):
        raise _Drawn

    monkeypatch.setattr(np.random, "default_rng", drawn)
    for rid in sorted(unbound):
        t0 = time.process_time()
        with pytest.raises(C.ClaimsFileError, match=rf"record {rid}: field evidence: .* not \(settings, \*, seed, "
                                                    r"runs\)"):
            C.evaluate(specs[rid], "primary", 0, 100)
        assert time.process_time() - t0 < 1.0
    for rid in sorted(stochastic):
        try:
            C.evaluate(specs[rid], "primary", 0, 100)
        except _Drawn:
            pass
        except C.ClaimsFileError as exc:
            pytest.fail(f"stochastic record {rid} refused: {exc}")


# --- D2: a float32 or float16 is glued as the decimal it prints ------------------------------------------------------

@pytest.mark.parametrize("value, decimals, expected", [
    (np.float32(0.654), None, 0.654), (np.array(np.float32(0.654)), None, 0.654), (np.float16(0.1), 5, 0.1),
    (np.float32(1e-8), None, 1e-8), (np.float64(0.654), None, 0.654), (np.int32(7), None, 7)])
def test_glue_all_glues_a_float32_as_the_decimal_it_prints(monkeypatch, value, decimals, expected):
    """D2: np.float32(0.654) was glued as 0.6539999842643738 and np.float16(0.1) at 5 decimals as 0.09998, while a
    float32 table cell is read as the decimal it prints (fuzz 26c q10): one rule for both now."""
    from fusion.book import glue as G

    glued = []
    monkeypatch.setattr("myst_nb.glue", lambda key, v, display: glued.append(v))
    G.glue_all({"x-a": value}, decimals)
    assert glued == [expected] and type(glued[0]) is type(expected)
    import pandas as pd

    if np.ndim(value) == 0 and isinstance(expected, float):
        table = pd.DataFrame({"c": np.array([value])})
        assert G._glued_cell(table, 0, "c", "t") == expected


# --- C6, C7: stability.tasks refuses before building ----------------------------------------------------------------

def _readings(records: int, runs: int = 1000) -> dict:
    return {("src", f"r{i}"): {"primary": ("primary", runs)} for i in range(records)}


def test_tasks_refuses_a_runs_factor_beyond_the_run_ceiling():
    """C6: runs_factor = 10**4 gave tasks of 2e8 runs, refused only on the Dask workers after the sweep's work."""
    from fusion.book import stability as S

    seed_list = S.seeds(3)
    assert max(t.runs for t in S.tasks(_readings(2), seed_list, 10**4)) == 10**7   # 1000 x 10**4: the ceiling
    with pytest.raises(ValueError, match=r"^runs_factor .* got runs_factor = 10001 x 1000 runs"):
        S.tasks(_readings(2), seed_list, 10**4 + 1)


def test_tasks_refuses_more_tasks_than_the_budget_builds_before_building_them():
    """C7: seeds(10_000) (k = MAX_SEEDS) built 5.1e6 tasks in 101 CPU-s. The edge, 500,000 tasks, is accepted (by the
    budget alone: about 8 CPU-s to build); one seed more is refused at once, naming seed_list."""
    import time

    from fusion._limits import work
    from fusion.book import stability as S

    assert work((500_000,), "seed_list", weight=S.TASK_WORK) == 10**9
    readings = _readings(1000)
    assert len(S.tasks(readings, S.seeds(20), 1)) == 20_000
    seed_list = S.seeds(501)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^readings and seed_list \(at least 99\d readings.* x 501 seeds"):
        S.tasks(readings, seed_list, 1)   # 501,000 tasks
    assert time.process_time() - t0 < 1.0
    with pytest.raises(ValueError, match=r"^readings and seed_list "):
        S.tasks({k: {f"x{j}": ("primary", 100) for j in range(51)} for k in _readings(1)}, S.seeds(10_000), 1)


# --- C8: recommend.check reads at most the ceiling of an iterable's items ---------------------------------------------

@pytest.mark.parametrize("which", ["records", "recommendations"])
def test_recommend_check_refuses_an_endless_iterable_by_name(which):
    """C8: check([], itertools.cycle(RECOMMENDATIONS)) ran into a MemoryError; an endless generator of records did not
    return within 90 s. Rule 9's ceiling of an iterable's items (as stability.seeds(avoid=...)) refuses it at once."""
    import itertools
    import time

    from fusion.book.recommend import RECOMMENDATIONS, check

    endless = {"records": itertools.repeat({"id": "a", "status": "reproduced"}),
               "recommendations": itertools.cycle(RECOMMENDATIONS)}[which]
    args = {"records": [], "recommendations": RECOMMENDATIONS} | {which: endless}
    t0 = time.process_time()
    most = {"records": 5000000, "recommendations": 10000000}[which]
    with pytest.raises(ValueError, match=rf"^{which} has more than {most} items"):
        check(**args)
    assert time.process_time() - t0 < 5.0


def test_recommend_check_reads_no_more_records_than_it_checks():
    """Review 18 (fix46): a generator of records was read up to 1e7 + 1 items (2 GB of distinct dicts) before the
    refusal; the work budget checks 5e6 records (CHECK_RECORD units each), so at most 5e6 + 1 are read, and refused
    by name at once (fresh dicts: the caller's memory held by the read stays bounded)."""
    import itertools
    import time

    from fusion._limits import MAX_WORK
    from fusion.book.recommend import CHECK_RECORD, check

    drawn = itertools.count()
    fresh = (dict() for _ in drawn)    # a distinct new dict each
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^records has more than 5000000 items \(the work budget"):
        check(fresh, [])
    assert time.process_time() - t0 < 4.0  # reading 5e6 dicts: 0.56 CPU-s measured; an endless read never ends
    assert next(drawn) == MAX_WORK // CHECK_RECORD + 1   # items read


def test_recommend_check_budget_edges():
    """Within the ceiling of items, the check's work is budgeted: 5e6 records (the edge, about 8 CPU-s) are accepted
    by the budget alone, 5e6 + 1 refused before the check, naming records and recommendations; a generator is read."""
    import time

    from fusion._limits import work
    from fusion.book import recommend as RC

    assert work((RC.CHECK_RECORD * 5_000_000,), "records") == 10**9
    records = [{"id": "a", "status": "reproduced"}] * (5_000_001)
    t0 = time.process_time()
    with pytest.raises(ValueError, match=r"^records and recommendations"):
        RC.check(records, [])
    assert time.process_time() - t0 < 1.0
    assert RC.check(({"id": f"r{i}", "status": "reproduced"} for i in range(3)), []) == []
