"""The shared validation modules import first, in a fresh interpreter (their re-export cycle is lazy, PEP 562).

``fusion._validation`` re-exports the rules of ``fusion._selections`` and ``fusion._covariances``, which import it:
an eager re-export made ``import fusion._covariances`` fail on the cycle, and with it every module that imported
it before ``fusion._validation`` (``fusion.scenarios.range_bearing_batch``, in the integration of fuzz 28a C5).
A sweep of all 187 modules of the package, each imported first, found no other failure (14 CPU-s; not run here).

One interpreter imports each module of :data:`FIRST` first in turn, every ``fusion`` module dropped from
``sys.modules`` before each (the package and its cycle are executed afresh; numpy and the other libraries stay
loaded, and hold no ``fusion`` state): one start-up instead of one per module (1.2 CPU-s instead of 1.8, measured
side by side).
"""
from __future__ import annotations

import json
import subprocess
import sys

import pytest

FIRST = ("fusion._covariances", "fusion._selections", "fusion._validation", "fusion.scenarios.range_bearing_batch")

#: Run in a fresh interpreter: ``argv[1:]`` are modules; prints a JSON object, module -> the traceback of its import
#: (empty when it imported), and the ``fusion`` modules left loaded before each import (none, or the run is void).
_EACH_FIRST = """
import importlib, json, sys, traceback
out = {}
for module in sys.argv[1:]:
    for name in [m for m in sys.modules if m == "fusion" or m.startswith("fusion.")]:
        del sys.modules[name]
    left = sorted(m for m in sys.modules if m == "fusion" or m.startswith("fusion."))
    try:
        importlib.import_module(module)
        out[module] = {"error": "", "left": left}
    except BaseException:
        out[module] = {"error": traceback.format_exc(), "left": left}
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def imported_first() -> dict[str, dict[str, object]]:
    """Each module of :data:`FIRST` imported first, in one fresh interpreter: module -> its record."""
    done = subprocess.run([sys.executable, "-c", _EACH_FIRST, *FIRST], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-600:]
    return json.loads(done.stdout)


@pytest.mark.parametrize("module", FIRST)
def test_module_imports_first(module: str, imported_first: dict[str, dict[str, object]]) -> None:
    record = imported_first[module]
    assert record["left"] == [], f"fusion modules still loaded before {module}: {record['left']}"
    assert record["error"] == "", str(record["error"])[-600:]


def test_reexported_rules_are_the_defining_modules_objects() -> None:
    import fusion._covariances as C
    import fusion._selections as S
    import fusion._validation as V
    for module, names in ((C, V._REEXPORTED["fusion._covariances"]), (S, V._REEXPORTED["fusion._selections"])):
        for name in names:
            assert getattr(V, name) is getattr(module, name)
    with pytest.raises(AttributeError):
        V.no_such_rule  # noqa: B018
