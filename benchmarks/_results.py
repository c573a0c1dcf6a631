"""Write a benchmark's measurements to ``benchmarks/results/<name>.json`` (read by the status page)."""

from __future__ import annotations

import json
import os
import platform
from datetime import date
from pathlib import Path
from typing import Any

RESULTS = Path(__file__).resolve().parent / "results"


def write_results(name: str, measurements: list[dict[str, Any]], **extra: Any) -> Path:
    """Store the measurements with the date and machine, print them, and return the file's path.

    Parameters
    ----------
    name : str
        File stem (``ci`` → ``benchmarks/results/ci.json``).
    measurements : list of dict
        Each with ``what``, ``value`` and ``unit``.
    **extra
        Further top-level fields (e.g. ``repeats``, ``runs``).
    """
    record = {
        "date": date.today().isoformat(),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        **extra,
        "measurements": measurements,
    }
    out = RESULTS / f"{name}.json"
    out.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")
    for m in measurements:
        print(f"{m['what']:70s} {m['value']:10.4g} {m.get('unit', '')}")
    return out
