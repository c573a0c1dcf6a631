"""The paired comparisons the records and the prose share: squared error and NEES per run, in words.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

import numpy as np

from fusion.book.ledger import Comparison, Proposition
from fusion.book.style import METHOD_LABELS
from fusion.scenarios.range_bearing import TrackingRun, position_sq_errors
from fusion.book.chapters.chernoff.settings import ALL_FRAMES, EARLY, LATE, STUDY_REASON, STUDY_RUNS, _MSE
from fusion.book.chapters.chernoff.tracking import per_run_mse
from fusion._shown import shown

__all__ = ["NEES_CONSISTENT"]


# --------------------------------------------------------------------------- claims ledger
def _reason(runs: int) -> str:
    return "" if runs >= STUDY_RUNS else f"{runs} runs: {STUDY_REASON}"


def _mse_comparison(runs: list[TrackingRun], a: str, b: str, claim: str, seed: int, frames: slice = LATE) -> Comparison:
    metric = _MSE if frames == LATE else _MSE.replace("from frame 5 on", _window_text(frames))
    if frames == LATE:
        va, vb = per_run_mse(runs, a), per_run_mse(runs, b)
    else:
        va = np.round(position_sq_errors(runs, a)[:, frames].mean(axis=1), 4)
        vb = np.round(position_sq_errors(runs, b)[:, frames].mean(axis=1), 4)
    return Comparison(va, vb, METHOD_LABELS[a], METHOD_LABELS[b], claim,  # type: ignore[arg-type]
                      metric, seed=seed, reason=_reason(len(runs)))


def _window_text(frames: slice) -> str:
    for window, text in ((LATE, "from frame 5 on"), (EARLY, "over frames 1-4"), (ALL_FRAMES, "over every frame")):
        if frames == window:
            return text
    raise ValueError(f"frames must be LATE, EARLY or ALL_FRAMES, got {shown(frames)}")


_NEES = "per-run mean NEES (4-D) from frame 5 on"


#: NEES of a consistent estimator of a 4-D state (its expected value).
NEES_CONSISTENT = 4.0


def _equivalent(cmp: Comparison) -> Proposition:
    """"No difference that matters": the paired interval inside ±5 % of the baseline's mean (R2's margin)."""
    eq = Comparison(cmp.a, cmp.b, cmp.a_name, cmp.b_name, "equal", cmp.metric, cmp.seed, cmp.reason)
    return Proposition(eq.status() == "reproduced", eq.summary())


def _word(c: Comparison) -> str:
    """A squared-error comparison in one word, A against B, by the rulebook's region (margin included, R2-R3)."""
    return {"lower": "better", "higher": "worse", "equivalent": "no different beyond the margin",
            "undecided": "not distinguishable"}[c.judgement().region]
