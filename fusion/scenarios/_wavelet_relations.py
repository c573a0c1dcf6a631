"""Cross-field checks of the wavelet studies' result specs (``fusion.scenarios.wavelet_sensors``; fuzz 24d S).

A :class:`~fusion.scenarios.wavelet_sensors.SignalStudy`'s and a
:class:`~fusion.scenarios.wavelet_sensors.SeedStudy`'s cases and a
:class:`~fusion.scenarios.wavelet_sensors.MechanismStudy`'s configurations, checked when a study is built or
rebuilt with ``dataclasses.replace`` (``fusion._results``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from fusion._shown import shown
from fusion._validation import as_array

__all__: list[str] = []  # private module: nothing public


#: The errors of every configuration of a ``MechanismStudy`` (its ``err``; ``evar`` holds the first three).
MECHANISM_ERRORS = ("raw", "denoised", "denoise-first", "fuse-first")


def cases_relation(values: Mapping[str, Any], cls: str) -> None:
    """A ``SignalStudy``'s cases: one per (signal, mode, normaliser) run, each with the metrics its consumers read,
    arrays (runs, sensors), finite, the errors non-negative."""
    want = {(g, m, n) for g in values["signals"] for m in values["modes"] for n in values["normalisers"]}
    if set(values["cases"]) != want:
        raise ValueError(f"{cls}.cases must hold one case per (signal, mode, normaliser) of {cls}.signals, "
                         f"{cls}.modes and {cls}.normalisers, got {shown(sorted(map(str, values['cases'])), 200)}")
    shape = (values["runs"], values["gains"].size)
    for key, case in values["cases"].items():
        _case(case, f"{cls}.cases[{shown(key)}]", shape, f"{cls}.runs and the sensors of {cls}.gains")


def seed_cases_relation(values: Mapping[str, Any], cls: str) -> None:
    """A ``SeedStudy``'s cases (one per seed: ``same_keys``), each a case as a ``SignalStudy``'s, arrays (runs, sensors)
    of the same sensors in every case (those of the first case's ``"weights"``)."""
    first = next(iter(values["cases"].values()), {})
    sensors = as_array(first.get("weights", ()), f"{cls}.cases[...]['weights']").shape[-1:]
    shape = (values["runs"], *sensors)
    for key, case in values["cases"].items():
        _case(case, f"{cls}.cases[{shown(key)}]", shape, f"{cls}.runs and the sensors of the first case's weights")


def _case(case: Mapping[str, Any], label: str, shape: tuple[int, ...], source: str) -> None:
    """One case of a wavelet study: the metrics its consumers read, finite arrays of ``shape``, errors >= 0."""
    for part in ("raw", "denoised", "reconstructed", "gain_err", "weights"):
        if part not in case:
            raise ValueError(f"{label} misses {shown(part)} (its consumers read it)")
    for part, value in case.items():
        if part == "example":
            continue
        metrics = value if isinstance(value, Mapping) else {"": value}
        for name, arr in metrics.items():
            where = f"{label}[{shown(part)}]" + (f"[{shown(name)}]" if name else "")
            arr = as_array(arr, where, finite=True)
            if arr.shape != shape:
                raise ValueError(f"{where} must have shape (runs, sensors) = {shape} ({source}), got {arr.shape}")
            if isinstance(value, Mapping) and (arr < 0).any():
                raise ValueError(f"{where} must be non-negative (an error), got {shown(float(arr.min()))}")


def configs_relation(values: Mapping[str, Any], cls: str) -> None:
    """A ``MechanismStudy`` has one configuration per label."""
    if len(values["configs"]) != len(values["labels"]):
        raise ValueError(f"{cls}.configs must hold one configuration per label of {cls}.labels "
                         f"({len(values['labels'])}), got {len(values['configs'])}")
