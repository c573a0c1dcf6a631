"""Fuzz 45b's findings on the book layer, fixed by fix52b: C2 (the cache log), C6 (record_status), C7 (glue_all)."""

from __future__ import annotations

import os
import time

import pytest

from fusion.book import study_cache as sc_mod


def _log_path(tmp_path, case: str) -> str:
    if case == "dangling":
        log = tmp_path / "log.jsonl"
        os.symlink(tmp_path / "missing" / "x.log", log)
        return str(log)
    if case == "longname":
        return str(tmp_path / ("a" * 300))
    return {"proc": "/proc/version", "procdir": "/proc/self/newlog"}[case]


@pytest.mark.parametrize("case", ["dangling", "longname", "proc", "procdir"])
def test_c2_a_log_that_cannot_be_appended_to_is_named_before_the_work(tmp_path, monkeypatch, case) -> None:
    """C2: these logs passed the environment check; the study ran, then ``open(log, "a")`` raised an OS error."""
    monkeypatch.setenv(sc_mod.ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(sc_mod.LOG_ENV, _log_path(tmp_path, case))
    calls: list[int] = []

    @sc_mod.study_cache(0)
    def double(x: int) -> int:
        calls.append(x)
        return 2 * x

    with pytest.raises(ValueError, match=f"^the environment variable {sc_mod.LOG_ENV} "):
        double(1)
    assert calls == []
    monkeypatch.setenv(sc_mod.LOG_ENV, str(tmp_path / "log.txt"))   # a new file in an existing directory: valid
    assert double(1) == 2
    assert calls == [1]


def test_c2_a_log_made_unusable_after_the_check_is_named(tmp_path, monkeypatch) -> None:
    """C2: the write itself converts an OS error (the log's folder removed after the check) to the named ValueError."""
    monkeypatch.setenv(sc_mod.LOG_ENV, str(tmp_path / "gone" / "log.jsonl"))
    with pytest.raises(ValueError, match=f"^the environment variable {sc_mod.LOG_ENV} "):
        sc_mod._log("f", {}, "computed", 0.0)


def test_c6_record_status_counts_its_readings_by_the_work_budget() -> None:
    """C6: 10**7 readings (the sequence ceiling) were accepted and checked for ~70 CPU-s; now refused at entry."""
    from fusion._limits import MAX_WORK, work
    from fusion.book import rulebook as R
    edge = MAX_WORK // R._STATUS_READING
    assert work((edge,), "readings", weight=R._STATUS_READING) <= MAX_WORK   # just inside: accepted (not run: ~9 s)
    reading = ("open-choice", "reproduced", 100)
    for n in (edge + 1, 10**7):
        big = [reading] * n
        t = time.process_time()
        with pytest.raises(ValueError, match="^readings ask for .* work budget"):
            R.record_status("reproduced", big, 100, False)
        assert time.process_time() - t < 1.0
    assert R.record_status("reproduced", [reading] * 1000, 100, False) == ("reproduced", 1000, 1000)


def test_c7_glue_all_counts_its_values_by_the_work_budget() -> None:
    """C7: 10**6 floats were accepted and glued for ~100 CPU-s; now refused at entry, as a table of too many cells
    and a list of too many entries are."""
    import numpy as np
    import pandas as pd

    from fusion._limits import MAX_WORK, work
    from fusion.book import glue as G
    edge = MAX_WORK // G._GLUE_VALUE
    assert work((edge,), "values", weight=G._GLUE_VALUE) <= MAX_WORK   # just inside: accepted (not run: ~7 s)
    cells = (MAX_WORK - G._GLUE_VALUE - G._GLUE_TABLE) // G._GLUE_CELL
    assert G._GLUE_VALUE + G._glue_work(pd.DataFrame(np.zeros((cells, 1))).style) <= MAX_WORK
    too_big = ({f"k{i}": i / 7 for i in range(edge + 1)}, {f"k{i}": i / 7 for i in range(10**6)},
               {"k": pd.DataFrame(np.zeros((cells + 1, 1))).style},
               {"k": [0.5] * ((MAX_WORK - G._GLUE_VALUE) // G._GLUE_ENTRY + 1)})
    for values in too_big:
        t = time.process_time()
        with pytest.raises(ValueError, match=r"^values(\['k'\])? .*work budget"):
            G.glue_all(values, decimals=3)
        assert time.process_time() - t < 1.0
