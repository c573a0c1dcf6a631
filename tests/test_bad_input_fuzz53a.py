"""Fuzz 53a C1, C2, C3 (fix59c): the claim files' YAML aliases let one long text be scanned once per use before any
budget (C1, ``claims.load``; also ``ClaimSpec``'s and ``ClaimsFile``'s own texts); ``stability.summarise`` walked
``committed`` (and its results) before its budget, as ``claims.build_ledger`` walked ``evidence`` (C2);
``stability.seeds`` hashed every ``avoid`` integer, however many digits (C3)."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping

import pytest

from fusion._counts import MAX_COUNT
from fusion._limits import MAX_WORK
from fusion.book import claims as C
from fusion.book import stability as S
from fusion.book._claim_text import TEXT_CHAR_WORK, texts_work


def _refused_fast(f, match, limit=1.0, error=ValueError):
    t0 = time.process_time()
    with pytest.raises(error, match=match):
        f()
    assert time.process_time() - t0 < limit


def _record(i: int, where: str, extra: str = "") -> str:
    return (f"- id: lec-x{i}\n  chapter: notebooks/02_lecture_weighting\n  where: {where}\n  claim: a claim {i}\n"
            f"  claimant: source\n  published:\n    value: qualitative\n  test: exact\n  link: lec-awf\n"
            f"  headline: {'true' if i == 0 else 'false'}\n{extra}")


def _file(tmp_path, records: list[str]):
    path = tmp_path / "c.yaml"
    path.write_text("source: lecture003\nrecords:\n" + "".join(records), encoding="utf-8")
    return path


class _Lazy(Mapping):
    """A read-only mapping of ``n`` integer keys (None each), iterated at C speed, holding no memory."""

    def __init__(self, n):
        self.n = n

    def __len__(self):
        return self.n

    def __iter__(self):
        return iter(range(self.n))

    def __getitem__(self, k):
        if isinstance(k, int) and 0 <= k < self.n:
            return None
        raise KeyError(k)


# --- C1 -------------------------------------------------------------------------------------------------------------

def test_c1_texts_budget_edges():
    edge = MAX_WORK // TEXT_CHAR_WORK  # 27,027,027 characters
    assert texts_work(edge, "texts") <= MAX_WORK
    with pytest.raises(ValueError, match="texts .*work budget"):
        texts_work(edge + 1, "texts")


def test_c1_an_aliased_long_text_is_refused_before_it_is_scanned(tmp_path):
    text = "é" * 500_000  # aliased in 100 records: 5e7 characters to scan, beyond the budget's 2.7e7
    path = _file(tmp_path, [_record(i, f'&a "{text}"' if i == 0 else "*a") for i in range(100)])
    _refused_fast(lambda: C.load(path), limit=2.0, match=r"c\.yaml: field records: its texts with the YAML aliases written out "
                                        r"\(50,0\d\d,\d+ characters to scan\).*work budget", error=C.ClaimsFileError)


def test_c1b_aliased_critiques_refused_before_they_are_scanned(tmp_path):
    text = "é" * 100_000
    crit = "  critiques:\n" + "".join(["  - *a\n"] * 300)  # 3e7 characters
    path = _file(tmp_path, [_record(0, f'&a "{text}"', crit)])
    _refused_fast(lambda: C.load(path), r"field records\.0\.critiques: its texts .*work budget",
                  error=C.ClaimsFileError)


def test_c1_a_file_inside_the_budget_still_loads_its_aliases(tmp_path):
    text = "a" * 100_000
    path = _file(tmp_path, [_record(i, f'&a "{text}"' if i == 0 else "*a") for i in range(3)])
    cf = C.load(path)
    assert [r.where for r in cf.records] == [text] * 3


def _book_file():
    return C.load(C.claims_dir() / "lecture003.yaml")


def test_c1_claimspec_counts_its_texts_before_scanning_them():
    spec = _book_file().records[0]
    many = tuple("é" * 1_000_000 + str(i) for i in range(30))  # 3e7 characters of distinct assumptions
    _refused_fast(lambda: dataclasses.replace(spec, assumptions=many), "the record's texts .*work budget")
    # a repeated label is refused before the labels are scanned
    _refused_fast(lambda: dataclasses.replace(spec, critiques=("é" * 5_000_000,) * 3), "must not repeat a label",
                  limit=0.1)


def test_c1_claimsfile_counts_its_quantities_texts_before_scanning_them():
    cf = _book_file()
    label = "é" * 1_000_000
    quantities = {**cf.quantities, **{f"q{i}": {"label": label, "margin": {"relative": 0.1}} for i in range(30)}}
    _refused_fast(lambda: dataclasses.replace(cf, quantities=quantities), "field quantities .*work budget",
                  error=C.ClaimsFileError)


def test_c1_build_ledger_reads_no_more_evidence_keys_than_the_file_has_records():
    cf = _book_file()
    _refused_fast(lambda: C.build_ledger(cf.source, None, _Lazy(MAX_COUNT), claims=cf), r"\(among others\)",
                  limit=0.5, error=C.ClaimsFileError)
    ids = [r.id for r in cf.records if r.chapter == cf.records[0].chapter]
    _refused_fast(lambda: C.build_ledger(cf.source, None, {i: _Lazy(MAX_COUNT) for i in ids}, claims=cf),
                  "field readings: evidence for", limit=0.5, error=C.ClaimsFileError)


# --- C2 -------------------------------------------------------------------------------------------------------------

def test_c2_summarise_counts_committed_before_reading_it():
    _refused_fast(lambda: S.summarise([], [1], _Lazy(MAX_COUNT + 1)), "committed has more than 10,000,000 entries")
    # just inside: the budget alone (a committed of 10**7 entries is 5e7 units)
    assert S._summary_work(0, 0, 1, MAX_COUNT) <= MAX_WORK
    assert S.summarise([], [1], _Lazy(1000)) == {}


def test_c2_summarise_refuses_a_committed_that_grows_while_read():
    class Growing(_Lazy):
        def __init__(self):
            super().__init__(3)
            self.reads = 0

        def __iter__(self):
            self.reads += 1
            self.n = 3 if self.reads == 1 else 5
            return iter(range(self.n))

    with pytest.raises(ValueError, match="committed yielded more than the 3 entries counted"):
        S.summarise([], [1], Growing())


def test_c2_summarise_results_budget_before_they_are_walked():
    r = S.TaskResult(S.Task("s", "r", "primary", "primary", 1, 100, False), "reproduced", 0.1)
    _refused_fast(lambda: S.summarise([r] * (5 * 10**6), [1], {}), "results and seed_list and committed .*work budget",
                  limit=0.5)


# --- C3 -------------------------------------------------------------------------------------------------------------

def test_c3_seeds_skips_avoid_integers_outside_the_seed_range_unhashed():
    want = S.seeds(5)
    t0 = time.process_time()
    assert S.seeds(5, avoid=[1 << 10**7] * 4000) == want
    assert time.process_time() - t0 < 0.5
    # an integer outside [0, 2**31) can never be a seed: -1 (a chapter without a seed), or a seed plus 2**31
    assert S.seeds(5, avoid=[-1, want[0] + 2**31, -want[0]]) == want
    assert want[0] not in S.seeds(5, avoid=[want[0]])


def test_c3_tasks_and_summarise_refuse_a_seed_beyond_31_bits_before_hashing():
    big = 1 << 10**7
    _refused_fast(lambda: S.tasks({}, [big] * 2000), r"seed_list\[0\] must be a seed of the sweep, below 2\*\*31",
                  limit=0.1)
    _refused_fast(lambda: S.summarise([], [5, big] * 1000, {}), r"seed_list\[1\] must be a seed of the sweep",
                  limit=0.1)
    # just inside: the largest 31-bit seed
    assert S.tasks({}, [2**31 - 1]) == [] and S.summarise([], [2**31 - 1], {}) == {}

    # a Task's seed too (batches and summarise hash it): refused when built
    with pytest.raises(ValueError, match="Task.seed must be a seed of the sweep, below 2"):
        S.Task("s", "r", "primary", "primary", big, 10)
    assert S.Task("s", "r", "primary", "primary", 2**31 - 1, 10).seed == 2**31 - 1
