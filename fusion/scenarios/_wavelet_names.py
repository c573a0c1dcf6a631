"""The name-list check of ``fusion.scenarios.wavelet_sensors`` (moved out of that module, at its 1,000-line limit)."""

from __future__ import annotations

from fusion._validation import one_of, sequence, shown

__all__: list[str] = []


def _names(seq: object, nm: str, allowed: tuple[str, ...]) -> list[str]:
    """A non-empty sequence ``nm`` of names among ``allowed``, as plain texts (rule 19), named by place (32a C4).
    Every entry is read: a caller with a budget by ``len(nm)`` counts it first (fuzz 62b C5)."""
    items = sequence(seq, nm)   # a list, tuple or 1-D array: TypeError otherwise (an iterator, a str)
    if not items:
        raise ValueError(f"{nm} must be a non-empty sequence of names")
    for i, v in enumerate(items):
        if not isinstance(v, str):
            raise TypeError(f"{nm}[{i}] must be a name (a str), got {type(v).__name__}")
        if v not in allowed:
            raise ValueError(f"{nm} must be among {allowed}, got {shown(v)}")
    return [one_of(v, allowed, f"{nm}[{i}]") for i, v in enumerate(items)]
