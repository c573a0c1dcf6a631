"""Fuzz 57c: a chapter's record reader refuses a run count rule R4 will certainly refuse BEFORE its studies.

The readers (``ev_*(settings, *, seed, runs)``, :func:`fusion.book.claims.evaluate`'s entry) of records whose
readings compare ``runs`` paired runs without a reason refused fewer than ``MIN_RUNS`` runs only when the comparison
was made, after the studies: ``ci.ev_fig7_improved_vs_ci({}, seed=2024, runs=3)`` computed chapter 05's studies
(~11 CPU-s) and then refused. Each reader below is called at a seed no other test uses (no study cached) with 3 and
with ``MIN_RUNS - 1`` runs: the refusal names ``runs`` and the rulebook's minimum, is rule R4's (a FewRunsError) and
comes before the work, counted as Python function calls (a study makes tens of thousands; the refusal a few
hundred) and as CPU time (< 1 s).
"""

from __future__ import annotations

import importlib
import sys
import time

import pytest

from fusion.book._few_runs import FewRunsError
from fusion.book.rulebook import MIN_RUNS

#: A seed no other test uses: nothing of it is cached in the process.
SEED = 57003

#: (chapter module, reader, settings) of every chapter's readers of paired records.
READERS = [
    ("ci", "ev_fig4_convex_part", {}), ("ci", "ev_fig7_improved_vs_ci", {}), ("ci", "ev_fig6_foa_vs_grid", {}),
    ("ci", "ev_fig10_x_below_y", {}), ("ci", "ev_fig10_convex_errors", {}), ("ci", "ev_fig10_fuzzy_errors", {}),
    ("time_registration_ledger", "ev_improved", {}), ("time_registration_ledger", "ev_ls_info", {}),
    ("time_registration_ledger", "ev_interp_vs_ls", {}), ("time_registration_ledger", "ev_fusion", {}),
    ("lecture_correlated", "ev_correlation_matters", {}), ("lecture_correlated", "ev_ridge_fusion_plugin", {}),
    ("lecture_weighting", "ev_awf_fault_tolerance", {}), ("lecture_weighting", "ev_awf_estimated", {}),
    ("lecture_weighting", "ev_belief_accuracy", {}), ("lecture_weighting", "ev_awf_adapts", {"reading": "primary"}),
    ("lecture_wavelets", "ev_wavelet_better", {}), ("lecture_wavelets", "ev_wavelet_weighting", {}),
    ("ofs", "ev_fig2_vs_mean", {}), ("ofs", "ev_fig2_vs_support", {"alpha": 0.5}), ("ofs", "ev_fig4_unaffected", {}),
    ("ofs", "ev_fig4_robust", {}), ("ofs", "ev_membership_free", {}), ("ofs", "ev_weights_reasonable", {}),
    ("ofs", "ev_weights_reasonable", {"sweep": "fault size (σ), 2 faulty sensors", "value": 2.0}), ("ofs", "ev_weights_stability", {}),
]

#: Python function calls a refusal before the work may make (the checks and the message: ~100 measured).
CALLS = 2_000


def _calls_and_cpu(fn, *args, **kwargs) -> tuple[int, float, BaseException | None]:
    """Python function calls made and CPU seconds spent by ``fn(*args, **kwargs)``, and what it raised."""
    calls = 0

    def count(frame, event, arg):  # noqa: ARG001
        nonlocal calls
        if event == "call":
            calls += 1

    raised = None
    t = time.process_time()
    sys.setprofile(count)
    try:
        fn(*args, **kwargs)
    except BaseException as e:  # noqa: BLE001 (returned, judged by the caller)
        raised = e
    finally:
        sys.setprofile(None)
    return calls, time.process_time() - t, raised


@pytest.fixture(scope="module", autouse=True)
def _claim_files_read() -> None:
    """Chapters 02-03 name an unknown reading from the claim file before the run count (fuzz 19): the file is read
    once per process (~0.3 CPU-s, cached), not per call; read here so that only the call's own work is counted. Each
    reader is called once untimed too: a first use in a worker reads and checks its chapter's claim file (the claim
    text rule's regular expressions, the parsed YAML kept), 98,768 calls in 0.06 CPU-s for chapter 05's when it ran
    first in its worker (a full run's order). The untimed call is at another seed, so no study of ``SEED`` is cached
    by it if a reader ran one before refusing."""
    from fusion.book.chapters.lecture import _source_claims
    _source_claims()
    for module, name, settings in READERS:
        fn = getattr(importlib.import_module(f"fusion.book.chapters.{module}"), name)
        with pytest.raises(FewRunsError):
            fn(settings, seed=SEED + 1, runs=3)


@pytest.mark.parametrize("runs", [3, MIN_RUNS - 1])
@pytest.mark.parametrize("module, name, settings", READERS)
def test_reader_refuses_too_few_runs_before_the_work(module, name, settings, runs) -> None:
    fn = getattr(importlib.import_module(f"fusion.book.chapters.{module}"), name)
    calls, cpu, raised = _calls_and_cpu(fn, settings, seed=SEED, runs=runs)
    assert isinstance(raised, FewRunsError), repr(raised)
    msg = str(raised)
    assert msg.startswith("runs ") and f"of {runs} runs" in msg and str(MIN_RUNS) in msg, msg
    assert calls < CALLS and cpu < 1.0, (calls, cpu)


def test_shi_ledger_evidence_refuses_too_few_runs_before_the_study() -> None:
    from fusion.book.chapters import time_registration_ledger as shi
    calls, cpu, raised = _calls_and_cpu(shi.ledger_evidence, SEED, 3)
    assert isinstance(raised, FewRunsError) and str(raised).startswith("runs "), repr(raised)
    assert calls < CALLS and cpu < 1.0, (calls, cpu)


def test_settings_are_still_named_first() -> None:
    """The reading is read before the run count (fuzz 19): an unknown reading is named, not ``runs``."""
    from fusion.book.chapters import lecture_weighting as lw
    from fusion.book.chapters import lecture_wavelets as lwv
    from fusion.book.chapters import ofs
    for call in (lambda: lw.ev_belief_accuracy({"reading": "nope"}, seed=SEED, runs=3),
                 lambda: lwv.ev_wavelet_better({"reading": "nope"}, seed=SEED, runs=3),
                 lambda: ofs.ev_fig2_vs_mean({"alpha": 0.25}, seed=SEED, runs=3)):
        with pytest.raises(ValueError) as e:
            call()
        assert not isinstance(e.value, FewRunsError) and "settings" in str(e.value), str(e.value)


def test_explanation_reading_without_comparisons_keeps_any_runs() -> None:
    """Only a certain refusal comes first: Table 1's reading of ``yang-membership-free`` compares no runs."""
    from fusion.book.chapters import ofs
    assert type(ofs.ev_membership_free({"vary": "table1"}, seed=SEED, runs=3)).__name__ == "Conjunction"


def test_runs_first_bounds() -> None:
    from fusion.book._few_runs import runs_first
    assert runs_first(MIN_RUNS) == MIN_RUNS
    with pytest.raises(FewRunsError, match=rf"^runs gives paired comparisons of {MIN_RUNS - 1} runs"):
        runs_first(MIN_RUNS - 1)
    with pytest.raises(ValueError, match="^n_runs") as e:
        runs_first(0, "n_runs")
    assert not isinstance(e.value, FewRunsError)
    with pytest.raises(TypeError):
        runs_first(100.0)


def test_valid_runs_still_accepted() -> None:
    """At the rulebook's minimum a reader computes its evidence (the cheapest reader of chapter 01, 100 runs)."""
    from fusion.book.chapters import ofs
    from fusion.book.rulebook import STATUSES
    assert ofs.ev_fig4_unaffected({}, seed=SEED, runs=MIN_RUNS).status() in STATUSES
