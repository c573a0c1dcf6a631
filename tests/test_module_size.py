"""No module of the package over 1,000 lines (issue 36's done-when, a house rule).

A module that grows past it is split by concept (as ``time_registration_fig4``, ``time_registration_closed``,
``ofs_support`` and ``fusion._options`` were), not trimmed of its documentation.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1] / "fusion"
MAX_LINES = 1000


def _lines(path: Path) -> int:
    return len(path.read_text(encoding="utf-8").splitlines())


def test_the_scan_reads_the_package() -> None:
    files = list(ROOT.rglob("*.py"))
    assert len(files) > 100 and any(p.name == "_validation.py" for p in files)


def test_no_module_is_over_the_house_limit() -> None:
    over = sorted(f"{p.relative_to(ROOT)}: {n} lines" for p in ROOT.rglob("*.py") if (n := _lines(p)) > MAX_LINES)
    assert not over, f"modules over {MAX_LINES} lines (split them by concept): {over}"
