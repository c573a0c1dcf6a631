"""Fuzz 58a: a structured array's subarray fields counted by one field each (C1), a Sequence of records copied
before its length was checked (C2), every target of ``fruit_fly_step_targets`` converted before the summed budget
(C3), and ``delay_table`` budgeting and looping over the caller's objects instead of the checked items (D1)."""

import subprocess
import sys
import textwrap
import time
from collections.abc import Sequence

import numpy as np
import pytest

from _helpers import glued_in_child

#: Fuzz 58a C1: structured arrays whose fields are subarrays, as broadcast views costing nothing to hold; glued in a
#: child under a 3 GiB address-space limit (converting one raised MemoryError, or ran 46.7 CPU-s and was accepted).
_C1_CASES = {
    "one_field": "np.broadcast_to(np.zeros(1, dtype=[('a', 'f8', (10**5,))]), (10**5,))",
    "twelve_fields": "np.broadcast_to(np.zeros(1, dtype=[(f'f{i}', 'f8', (10**5,)) for i in range(12)]), (4 * 10**4,))",
    "nested": "np.broadcast_to(np.zeros(1, dtype=[('b', [('a', 'f8', (10**3,))], (10**3,))]), (10**3,))",
    "scalar_in_list": "[np.zeros(1, dtype=[('a', 'f8', (6 * 10**7,))])[0]]",
}

@pytest.mark.parametrize("case", sorted(_C1_CASES))
def test_c1_subarray_fields_are_counted_before_conversion(case: str) -> None:
    out = glued_in_child(tuple(_C1_CASES.items()))[case]
    assert out[0] == "ValueError", out
    assert float(out[1]) < 1.0, out
    assert out[2].startswith("values['k'] "), out


def test_c1_subarray_entries_edge() -> None:
    """A field's subarray entries (nested structured fields alike) count in the logical size and the units: at the
    input budget's edge accepted by the check, one element more refused; a NaN inside a subarray still refused."""
    from fusion._limits import MAX_INPUT_ELEMENTS
    from fusion.book import glue as G
    dt = np.dtype([("a", "f8", (2**10,)), ("b", [("c", "c16", (2,)), ("d", "i4")], (3,))])
    assert G._dtype_entries(dt) == 2**10 + 3 * 3
    per = 2**10 + 9
    n = MAX_INPUT_ELEMENTS // per
    G._logical_check(np.broadcast_to(np.zeros(1, dt), (n,)), "k")
    assert G._numeric_units(np.broadcast_to(np.zeros(1, dt), (n,))) == n * per * G._GLUE_NUMBER
    with pytest.raises(ValueError, match=r"^values\['k'\] holds a ndarray of .* input budget"):
        G._logical_check(np.broadcast_to(np.zeros(1, dt), (n + 1,)), "k")
    bad = np.zeros(2, dt)
    bad["b"]["c"][1, 2, 1] = np.nan
    with pytest.raises(ValueError, match=r"values\['k'\]"):
        G.glue_all({"k": bad})
    G.glue_all({"k": np.zeros(2, dt)})   # a small one is glued


_C2_CHILD = textwrap.dedent("""
    import resource, sys, time
    resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    from fusion.book.chapters.lecture_weighting.records import reseeding_glue, robustness_glue
    f = {"robustness_glue": robustness_glue, "reseeding_glue": reseeding_glue}[sys.argv[1]]
    value = eval(sys.argv[2])
    t = time.process_time()
    try:
        f(value)
        print("ACCEPTED")
    except BaseException as e:
        print(type(e).__name__, time.process_time() - t, str(e)[:300].replace("\\n", " "))
""")


@pytest.mark.parametrize("reader", ["robustness_glue", "reseeding_glue"])
@pytest.mark.parametrize("records", ["range(10**12)", "range(10**8)"])
def test_c2_records_counted_before_any_copy(reader: str, records: str) -> None:
    """Fuzz 58a C2: ``records_of`` copied the caller's Sequence (``list(value)``) before any check: a raw MemoryError
    for ``range(10**12)``, a TypeError after ~3 CPU-s of copying for ``range(10**8)``; now refused by its length."""
    out = subprocess.run([sys.executable, "-c", _C2_CHILD, reader, records], capture_output=True, text=True,
                         timeout=300).stdout.split(" ", 2)
    assert out[0] == "ValueError", out
    assert float(out[1]) < 1.0, out
    assert out[2].startswith("records has ") and "ceiling" in out[2], out


class _Lying(Sequence):
    """A Sequence whose ``__len__`` disagrees with its one record."""

    def __init__(self, n: int) -> None:
        self.n = n

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, i: int) -> dict:
        if i >= 1:
            raise IndexError(i)
        return {"id": "lec-a", "status": "supported", "runs": 100, "robustness": None}


def test_c2_records_len_must_agree_with_the_items() -> None:
    from fusion._structures import records_of
    with pytest.raises(ValueError, match=r"^records has 1152921504606846976 items, beyond the ceiling"):
        records_of(_Lying(2**60), "records")   # list() preallocated from __len__: a raw MemoryError
    with pytest.raises(ValueError, match=r"^records has len\(\) 3 but 1 items"):
        records_of(_Lying(3), "records")
    assert records_of(_Lying(1), "records", ("id",)) == [_Lying(1)[0]]
    with pytest.raises(TypeError, match=r"^records\[0\] must be a mapping"):
        records_of(range(5), "records")


def test_c3_targets_counted_before_conversion() -> None:
    """Fuzz 58a C3: every target was converted and checked for repeats before the summed budget, which then built a
    part per batch: 2,000,000 targets were refused after 10.7-14.9 CPU-s. Now one batch's units times the batches
    (``repeated``), before any target is converted: the edge by the budget alone, a count past it refused at once."""
    from fusion._limits import MAX_WORK
    from fusion.book.chapters.ci.fruit_fly_step import FRUIT_FLY_STEP_RULES, _step_budget, fruit_fly_step_targets
    from fusion.optimise.scalar import batch_budget
    one = len(FRUIT_FLY_STEP_RULES) * batch_budget(100, 30, 200, "seeds")
    edge = MAX_WORK // one
    assert _step_budget(100, edge, "targets and seeds") == edge * one   # the same units as a part per batch
    with pytest.raises(ValueError, match="^targets and seeds ask for studies beyond the budget"):
        _step_budget(100, edge + 1, "targets and seeds")
    for targets in (np.linspace(0.01, 0.99, 2 * 10**6), [0.5] * (edge + 1), ["not a number"] * (edge + 1)):
        t = time.process_time()
        with pytest.raises(ValueError, match="^targets and seeds ask for studies beyond the budget"):
            fruit_fly_step_targets(0, targets, 100)
        assert time.process_time() - t < 1.0


def test_c3_scan_levels_counted_as_one_part() -> None:
    """The same class in ``ir_sigma_band``'s parts (a part per level of the caller's scan): one part, its units
    the levels' sum."""
    from fusion.book.chapters.ci.infrared_readings import _sigma_parts
    parts = _sigma_parts(4, 11, 10**6, "scan")
    assert len(parts) == 1
    assert parts[0]() == 10**6 * _sigma_parts(4, 11, 1, "scan")[0]()


class _Flip(list):
    """A list whose second iteration gives other items (fuzz 58a D1)."""

    def __init__(self, first: list, then: list) -> None:
        super().__init__(first)
        self.first, self.then, self.n = first, then, 0

    def __iter__(self):  # noqa: ANN204
        self.n += 1
        return iter(self.first if self.n == 1 else self.then)


def test_d1_delay_table_uses_the_checked_items() -> None:
    """Fuzz 58a D1: ``delay_table`` budgeted ``len(delays)`` and looped over the caller's objects again: a list
    whose second iteration gave 20,000 latencies ran unbudgeted (> 120 s). The checked floats are used."""
    from fusion.book.chapters.time_registration_robustness import delay_table
    t = time.process_time()
    out = delay_table(_Flip([0.001], list(np.linspace(-0.9, 0.9, 20000))), _Flip([1.0, 2.0], [3.0] * 5000))
    assert time.process_time() - t < 30.0
    assert out.shape == (1, 2)
    assert out.equals(delay_table([0.001], [1.0, 2.0]))


def test_d1_named_crossings_uses_the_checked_pairs() -> None:
    """The same class in ``named_crossings``: the caller's pairs were iterated again for the rows."""
    import pandas as pd
    from fusion.book.chapters.time_registration_closed import BETTER_ABOVE, BETTER_BELOW, SIGMA_STAR, named_crossings
    table = pd.DataFrame({BETTER_BELOW: ["a", "c"], BETTER_ABOVE: ["b", "d"], SIGMA_STAR: [1.0, 2.0]})
    out = named_crossings(table, _Flip([("a", "b")], [("c", "d")] * 3))
    assert out[BETTER_BELOW].tolist() == ["a"]
