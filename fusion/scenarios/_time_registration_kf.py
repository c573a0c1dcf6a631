"""The ``kf`` options of :mod:`fusion.scenarios.time_registration` (kept apart: that module is at its size limit)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from fusion._validation import FloatArray, text
from fusion.registration import methods as _methods

__all__: list[str] = []  # private module: nothing public


def kf_kwargs(kf: Mapping[str, Any] | None, t_dst: FloatArray, allowed: tuple[str, ...]) -> dict[str, Any]:
    """Translate the chapter's ``kf`` options (keys among ``allowed``) into
    :func:`fusion.registration.methods.kalman_runs` keywords. Each key is read as its plain text (rule 19 of
    ``fusion._validation``): a ``str`` subclass whose own ``!=`` disagrees with its text would otherwise drop an
    option without a word (fuzz 32a C1)."""
    if kf is None:
        return {}
    if not isinstance(kf, Mapping):
        raise TypeError(f"kf must be a mapping of options, got {type(kf).__name__}")
    kf = {text(k, "kf keys") if isinstance(k, str) else k: v for k, v in kf.items()}  # keys as their text (rule 19)
    bad = [k for k in kf if k not in allowed]
    if bad:
        raise ValueError(f"kf keys must be among {allowed}, got {bad}")
    out = {k: v for k, v in kf.items() if k != "period_change"}
    try:  # the values too, with messages that name kf (issue 35, class 6)
        _methods._kf_options(1.0, 0.0, 0.0, out.get("q_model", "per-step"), out.get("init", "source"),
                        out.get("p0", (100.0, 100.0)), out.get("period", 2.0))
        if "smooth" in out and not isinstance(out["smooth"], (bool, np.bool_)):
            raise TypeError(f"smooth must be a bool, got {type(out['smooth']).__name__}")
        if not isinstance(kf.get("period_change", False), (bool, np.bool_)):
            raise TypeError(f"period_change must be a bool, got {type(kf['period_change']).__name__}")
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"kf: {exc}") from None
    if kf.get("period_change", False):
        out["t_extra"] = t_dst
    return out
