"""The lock file, pyproject and the environment agree; every import of the tests is declared.

``requirements.lock`` pins every package of the environment (``make lock`` regenerates it from
pyproject.toml; ``make book`` and ``make test`` install from it). Stored notebook outputs are
compared exactly, so the versions that computed them are part of the book.
"""

from __future__ import annotations

import ast
import json
import re
import sys
import tomllib
from importlib.metadata import PackageNotFoundError, packages_distributions, version
from pathlib import Path

import pytest
from packaging.markers import Marker
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[1]
LOCK = ROOT / "requirements.lock"
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
PIN = re.compile(r"^(?P<name>[A-Za-z0-9][A-Za-z0-9._-]*)==(?P<version>[^\s;]+)\s*(?:;\s*(?P<marker>.+))?$")


def read_lock(text: str) -> dict[str, list[tuple[Version, Marker | None]]]:
    """Pins of a lock file: canonical name -> [(version, marker or None)] (one name may fork by marker)."""
    pins: dict[str, list[tuple[Version, Marker | None]]] = {}
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith(("#", "-")):
            continue
        m = PIN.match(line)
        if m is None:
            raise ValueError(f"not an exact pin: {line!r}")
        marker = Marker(m["marker"]) if m["marker"] else None
        pins.setdefault(canonicalize_name(m["name"]), []).append((Version(m["version"]), marker))
    return pins


def pinned_here(pins: dict[str, list[tuple[Version, Marker | None]]], name: str) -> Version | None:
    """The version pinned for this interpreter and platform, or None."""
    for v, marker in pins.get(canonicalize_name(name), []):
        if marker is None or marker.evaluate():
            return v
    return None


def unsatisfied(requirements: list[str], pins: dict[str, list[tuple[Version, Marker | None]]]) -> list[str]:
    """Requirements (of this environment) that no pin satisfies."""
    bad = []
    for text in requirements:
        req = Requirement(text)
        if req.marker is not None and not req.marker.evaluate({"extra": ""}):
            continue
        v = pinned_here(pins, req.name)
        if v is None or not req.specifier.contains(v, prereleases=True):
            bad.append(f"{text} (locked: {v})")
    return bad


PINS = read_lock(LOCK.read_text(encoding="utf-8"))
LOCKED_REQUIREMENTS = PYPROJECT["project"]["dependencies"] + PYPROJECT["project"]["optional-dependencies"]["dev"]


def test_lock_parser_reads_pins_and_markers() -> None:
    pins = read_lock("# header\nnumpy==2.4.6\n    # via x\nappnope==1.0.0 ; sys_platform == 'no-such-os'\n")
    assert pinned_here(pins, "NumPy") == Version("2.4.6")
    assert pinned_here(pins, "appnope") is None
    with pytest.raises(ValueError, match="not an exact pin"):
        read_lock("numpy>=2\n")


def test_unsatisfied_flags_a_pin_outside_the_range() -> None:
    pins = read_lock("numpy==2.4.6\n")
    assert unsatisfied(["numpy>=2,<3"], pins) == []
    assert unsatisfied(["numpy>=3"], pins) == ["numpy>=3 (locked: 2.4.6)"]
    assert unsatisfied(["scipy>=1"], pins) == ["scipy>=1 (locked: None)"]


def test_every_pyproject_requirement_is_satisfied_by_the_lock() -> None:
    assert unsatisfied(LOCKED_REQUIREMENTS, PINS) == [], "pyproject.toml and requirements.lock disagree: run `make lock`"


def test_lock_covers_the_supported_pythons() -> None:
    """The lock is resolved for the oldest Python pyproject allows (`make lock`, --python-version)."""
    requires = PYPROJECT["project"]["requires-python"]
    header = LOCK.read_text(encoding="utf-8").splitlines()[:3]
    assert any("make lock" in line for line in header), "requirements.lock was not written by `make lock`"
    assert requires == ">=3.11", "requires-python changed: update --python-version in the Makefile's lock target"


def test_the_environment_is_the_locked_one() -> None:
    """Every locked package installed here has the locked version (make installs from the lock)."""
    wrong = []
    for name, entries in PINS.items():
        want = pinned_here(PINS, name)
        if want is None:
            continue
        try:
            have = Version(version(name))
        except PackageNotFoundError:
            wrong.append(f"{name}: not installed (locked {want})")
            continue
        if have != want:
            wrong.append(f"{name}: {have} installed, {want} locked")
    assert not wrong, "environment differs from requirements.lock (rebuild it: make distclean test):\n" + "\n".join(wrong)


def _imported_modules(source: str) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names


def test_every_import_of_the_tests_and_notebooks_is_declared() -> None:
    """Third-party modules imported by tests/ and the notebooks (which nbval runs) are declared in pyproject."""
    modules: set[str] = set()
    for path in sorted((ROOT / "tests").glob("*.py")):
        modules |= _imported_modules(path.read_text(encoding="utf-8"))
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "code":
                modules |= _imported_modules("".join(cell["source"]))
    declared = {canonicalize_name(Requirement(r).name)
                for group in [PYPROJECT["project"]["dependencies"], *PYPROJECT["project"]["optional-dependencies"].values()]
                for r in group}
    local = {"fusion", "conftest"} | {p.stem for p in (ROOT / "tests").glob("*.py")} | {p.stem for p in (ROOT / "tools").glob("*.py")}
    dists = packages_distributions()
    missing = []
    for module in sorted(modules - set(sys.stdlib_module_names) - local):
        providers = {canonicalize_name(d) for d in dists.get(module, [module])}
        if not providers & declared:
            missing.append(f"{module} (from {sorted(providers)})")
    assert not missing, f"imported by the tests but not declared in pyproject.toml: {missing}"
    assert {"numpy", "yaml", "pytest", "hypothesis"} <= modules  # the scan sees the imports
