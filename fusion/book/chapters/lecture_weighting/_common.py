r"""Private helpers shared by the submodules of chapter 02's package."""

from __future__ import annotations


import numpy as np

from fusion.book._t_interval import t_pvalue
from fusion.book.ledger import Proposition
from fusion._shown import shown
from fusion._validation import MAX_STD, MIN_STD, std_scalar

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


def _std_entries(sig: np.ndarray, name: str) -> np.ndarray:
    """``sig`` (a 1-D float array, as ``fusion._validation.as_array`` returns it) when every entry is a standard
    deviation by :func:`fusion._validation.std_scalar`'s rule, checked at once; else that rule's ValueError for the
    first entry outside it, naming ``name[i]``.

    Vectorised (fuzz 68b C7, C8: a Python loop of ``std_scalar`` over 10**7 entries ran 34-37 CPU-s before the
    callers' memory and work budgets refused their number; 10**7 entries now take some 0.05 CPU-s).
    """
    arr = np.asarray(sig, dtype=float)
    bad = np.flatnonzero(~((arr >= MIN_STD) & (arr <= MAX_STD)))   # NaN fails both comparisons
    if bad.size:
        i = int(bad[0])
        std_scalar(arr[i], f"{name}[{i}]")   # raises, with the rule's own message
        raise ValueError(f"{name}[{i}] = {shown(float(arr[i]))} is not a standard deviation in [{MIN_STD:.3g}, "
                         f"{MAX_STD:.3g}]")
    return sig
