"""The name-list check of ``fusion.scenarios.wavelet_sensors`` (moved out of that module, at its 1,000-line limit)."""

from __future__ import annotations

from fusion._validation import LOOP_STEP, one_of, sequence, shown

__all__: list[str] = []

#: Units of one step of ``signal_study`` (a signal's raw metrics, a rule's denoising, a normaliser's fusion and
#: metrics: a few validated calls each), on top of its 20 units a sample: 205-300 us a step measured at 2 runs x 2
#: sensors x 64 samples (1 or 4 signals, 1 or 2 modes, 1 or 4 normalisers; min of 3, time.process_time,
#: OPENBLAS_NUM_THREADS=1, shared machine), so about twice that, 600 us (fuzz 64b C8: LOOP_STEP, 10 us, let 80,000
#: steps of one signal run 44.7 CPU-s).
_SIGNAL_STEP = 60 * LOOP_STEP


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


def _swt_level(cfg: dict[str, object], length: int, nm: str) -> None:
    """Refuse, naming ``nm`` (``configs[i]``) and ``length``, a stationary (``"swt"``) config whose ``2**level`` does
    not divide ``length`` samples, before any draw (fix71a: ``denoise`` refused it after the draw and the earlier
    configs, ~3.6 CPU-s, naming its own ``x``); ``level`` already read as an int. Other transforms pass."""
    level = int(cfg["level"])  # type: ignore[call-overload]
    if cfg.get("transform", "dwt") == "swt" and (level >= int(length).bit_length() or int(length) % 2**level):
        raise ValueError(f"{nm}: a stationary (transform 'swt') config needs length a multiple of 2**level; level "
                         f"{level} does not divide length {int(length)}")
