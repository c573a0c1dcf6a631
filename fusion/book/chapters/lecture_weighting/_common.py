r"""Private helpers shared by the submodules of chapter 02's package."""

from __future__ import annotations


import numpy as np

from fusion.book.ledger import Proposition

__all__: list[str] = []


def _unbiased(err: np.ndarray, rmse: float, what: str, margin: float = 0.05) -> Proposition:
    """TOST of a zero mean error: the mean of the per-run mean errors within ±``margin`` × ``rmse`` of 0.

    Two one-sided t tests (Schuirmann 1987) at level 0.05 each, on the per-run mean errors.
    """
    from scipy import stats as _st

    e = np.asarray(err, dtype=float)
    delta = margin * float(rmse)
    p = max(float(_st.ttest_1samp(e, -delta, alternative="greater").pvalue),
            float(_st.ttest_1samp(e, delta, alternative="less").pvalue))
    p_txt = "p < 0.001" if p < 0.001 else f"p = {p:.3f}"
    return Proposition(bool(p < 0.05), f"{what}: mean error {float(e.mean()):+.4f} over {e.size} runs; within "
                       f"±{delta:.4f} ({margin:.0%} of the fused RMSE {rmse:.3f}) {'shown' if p < 0.05 else 'not shown'} "
                       f"(TOST, {p_txt})")
