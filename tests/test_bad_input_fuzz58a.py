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

#: Fuzz 58a C1: structured arrays whose fields are subarrays, as broadcast views costing nothing to hold; glued in a
#: child under a 3 GiB address-space limit (converting one raised MemoryError, or ran 46.7 CPU-s and was accepted).
_C1_CASES = {
    "one_field": "np.broadcast_to(np.zeros(1, dtype=[('a', 'f8', (10**5,))]), (10**5,))",
    "twelve_fields": "np.broadcast_to(np.zeros(1, dtype=[(f'f{i}', 'f8', (10**5,)) for i in range(12)]), (4 * 10**4,))",
    "nested": "np.broadcast_to(np.zeros(1, dtype=[('b', [('a', 'f8', (10**3,))], (10**3,))]), (10**3,))",
    "scalar_in_list": "[np.zeros(1, dtype=[('a', 'f8', (6 * 10**7,))])[0]]",
}

_C1_CHILD = textwrap.dedent("""
    import resource, sys, time
    resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    import numpy as np
    from fusion.book.glue import glue_all
    glue_all({"k": 0.5})   # imports (IPython's formatters) outside the timing
    value = eval(sys.argv[1])
    t = time.process_time()
    try:
        glue_all({"k": value})
        print("ACCEPTED")
    except BaseException as e:
        print(type(e).__name__, time.process_time() - t, str(e)[:300].replace("\\n", " "))
""")


@pytest.mark.parametrize("case", sorted(_C1_CASES))
def test_c1_subarray_fields_are_counted_before_conversion(case: str) -> None:
    out = subprocess.run([sys.executable, "-c", _C1_CHILD, _C1_CASES[case]], capture_output=True, text=True,
                         timeout=300).stdout.split(" ", 2)
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
