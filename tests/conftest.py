"""Shared test configuration: deterministic hypothesis runs, and the book built once per session."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parents[1]

# Derandomised: the same examples on every machine and every run, so a failure is
# reproducible and CI is not flaky. No deadline: CI machines vary in speed.
settings.register_profile(
    "fusion", derandomize=True, deadline=None, max_examples=200,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("fusion")


def build_book(out: Path) -> subprocess.CompletedProcess[str]:
    """Build the HTML book into ``out`` from the committed notebook outputs (no re-execution).

    Warnings are errors (``-W``) and every cross-reference must resolve (``-n``, nitpicky).
    nbval proves that the committed outputs still follow from the code, so building from them
    checks the book that ``make book`` would build, without executing every notebook twice.
    """
    config = yaml.safe_load((ROOT / "_config.yml").read_text(encoding="utf-8"))
    config.setdefault("execute", {})["execute_notebooks"] = "off"
    # paths in the config are relative to its folder: make them absolute for the copy
    config["bibtex_bibfiles"] = [str(ROOT / b) for b in config.get("bibtex_bibfiles", [])]
    sphinx = config.setdefault("sphinx", {})
    sphinx["local_extensions"] = {k: str(ROOT / v) for k, v in sphinx.get("local_extensions", {}).items()}
    conf = sphinx.setdefault("config", {})
    conf["html_static_path"] = [str(ROOT / p) for p in conf.get("html_static_path", [])]
    config_path = out / "_config.yml"
    config_path.write_text(yaml.safe_dump(config, allow_unicode=True), encoding="utf-8")
    jb = Path(sys.executable).with_name("jupyter-book")
    return subprocess.run(
        [str(jb), "build", str(ROOT), "--config", str(config_path), "--path-output", str(out),
         "--builder", "html", "-W", "-n", "--keep-going"],
        capture_output=True, text=True, timeout=900,
    )


@pytest.fixture(scope="session")
def book_html(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The HTML book, built once per test run (tests/test_book_build.py, tests/test_browser.py).

    ``make test`` runs pytest on every core (pytest-xdist, ``--dist loadscope``: a notebook's cells
    stay together in one worker). The two test files that need the book may land on different
    workers, so the first one builds it into a directory shared by the run, under a file lock, and
    the other reuses that build (or its failure).
    """
    import fcntl
    import json
    import os

    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent                      # shared by every worker of this run
    out, record = root / "book", root / "book-build.json"
    with open(root / "book-build.lock", "w", encoding="utf-8") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not record.exists():
            out.mkdir(exist_ok=True)
            proc = build_book(out)
            record.write_text(json.dumps({"returncode": proc.returncode, "stdout": proc.stdout[-6000:],
                                          "stderr": proc.stderr[-6000:]}), encoding="utf-8")
        result = json.loads(record.read_text(encoding="utf-8"))
    assert result["returncode"] == 0, f"book build failed:\n{result['stdout']}\n{result['stderr']}"
    return out / "_build" / "html"

