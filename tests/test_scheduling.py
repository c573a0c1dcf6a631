"""The order in which ``make test`` hands work to its two xdist workers (tests/conftest.py, issue 37)."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import COSTS_FILE, schedule_order, scope_of

ROOT = Path(__file__).resolve().parents[1]


def test_longest_first_waiting_units_last_unknown_after_known_stable() -> None:
    costs = {"a.py": 5.0, "b.ipynb": 120.0, "c.py": 5.0, "book.py": 90.0}
    order = schedule_order(["a.py", "new.py", "book.py", "b.ipynb", "c.py", "new2.py"], costs, {"book.py"})
    assert order == ["b.ipynb", "a.py", "c.py", "new.py", "new2.py", "book.py"]
    assert schedule_order([], costs) == []


def test_scope_is_xdist_loadscope_split() -> None:
    """The unit the ordering sorts is the one ``--dist loadscope`` hands out whole."""
    from xdist.scheduler.loadscope import LoadScopeScheduling

    split = LoadScopeScheduling._split_scope
    for nodeid in ("notebooks/06_chernoff_fusion.ipynb::Cell 12", "tests/test_ofs_audit.py::test_x[a-b]",
                   "tests/test_x.py::TestClass::test_y"):
        assert scope_of(nodeid) == split(None, nodeid)


def test_every_notebook_has_a_recorded_cost() -> None:
    """A unit without a record is scheduled after all recorded ones: a new long notebook would end the run late.

    (A new test module may go without one: test modules are short.)
    """
    costs = json.loads(COSTS_FILE.read_text(encoding="utf-8"))
    notebooks = {f"notebooks/{p.name}" for p in (ROOT / "notebooks").glob("*.ipynb")
                 if '"cell_type": "code"' in p.read_text(encoding="utf-8")}   # a prose-only notebook is no work unit
    assert notebooks - set(costs) == set(), \
        "record with: FUSION_TEST_COSTS=tests/data/scope_costs.json .venv/bin/python -m pytest -n 0"
    assert all(isinstance(v, (int, float)) and v >= 0 for v in costs.values())


def test_a_study_reader_goes_after_the_unit_that_computes_its_studies() -> None:
    costs = {"nb.ipynb": 30.0, "reader.py": 40.0, "other.py": 35.0, "x.py": 1.0}
    after = {"reader.py": "nb.ipynb", "x.py": "missing.ipynb"}
    order = schedule_order(["reader.py", "other.py", "nb.ipynb", "x.py"], costs, after=after)
    assert order == ["other.py", "nb.ipynb", "reader.py", "x.py"]
    # already after its producer: unchanged
    assert schedule_order(["a.py", "nb.ipynb"], {"nb.ipynb": 9.0, "a.py": 1.0}, after={"a.py": "nb.ipynb"}) \
        == ["nb.ipynb", "a.py"]


def test_study_readers_name_recorded_units() -> None:
    """Every reader and producer of :data:`conftest.STUDY_READERS` is a unit of the test run."""
    from conftest import STUDY_READERS

    for unit in {*STUDY_READERS, *STUDY_READERS.values()}:
        assert (ROOT / unit).is_file(), unit
