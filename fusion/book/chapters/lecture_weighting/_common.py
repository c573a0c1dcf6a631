r"""Private helpers shared by the submodules of chapter 02's package."""

from __future__ import annotations


import numpy as np

from fusion.book._t_interval import t_pvalue
from fusion.book.ledger import Proposition

__all__: list[str] = []


def _unbiased(err: np.ndarray, rmse: float, what: str, margin: float = 0.05) -> Proposition:
    """TOST of a zero mean error: the mean of the per-run mean errors within ±``margin`` × ``rmse`` of 0.

    Two one-sided t tests (Schuirmann 1987) at level 0.05 each, on the per-run mean errors.
    """
    e = np.asarray(err, dtype=float)
    delta = margin * float(rmse)
    p = max(t_pvalue(e, -delta, "greater"), t_pvalue(e, delta, "less"))   # no precision-loss warning (fuzz 37b C3)
    p_txt = "p < 0.001" if p < 0.001 else f"p = {p:.3f}"
    return Proposition(bool(p < 0.05), f"{what}: mean error {float(e.mean()):+.4f} over {e.size} runs; within "
                       f"±{delta:.4f} ({margin:.0%} of the fused RMSE {rmse:.3f}) {'shown' if p < 0.05 else 'not shown'} "
                       f"(TOST, {p_txt})")
