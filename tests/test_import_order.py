"""The shared validation modules import first, in a fresh interpreter (their re-export cycle is lazy, PEP 562).

``fusion._validation`` re-exports the rules of ``fusion._selections`` and ``fusion._covariances``, which import it:
an eager re-export made ``import fusion._covariances`` fail on the cycle, and with it every module that imported
it before ``fusion._validation`` (``fusion.scenarios.range_bearing_batch``, in the integration of fuzz 28a C5).
A sweep of all 187 modules of the package, each imported first, found no other failure (14 CPU-s; not run here).
"""
from __future__ import annotations

import subprocess
import sys

import pytest

FIRST = ("fusion._covariances", "fusion._selections", "fusion._validation", "fusion.scenarios.range_bearing_batch")


@pytest.mark.parametrize("module", FIRST)
def test_module_imports_first(module: str) -> None:
    done = subprocess.run([sys.executable, "-c", f"import {module}"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-600:]


def test_reexported_rules_are_the_defining_modules_objects() -> None:
    import fusion._covariances as C
    import fusion._selections as S
    import fusion._validation as V
    for module, names in ((C, V._REEXPORTED["fusion._covariances"]), (S, V._REEXPORTED["fusion._selections"])):
        for name in names:
            assert getattr(V, name) is getattr(module, name)
    with pytest.raises(AttributeError):
        V.no_such_rule  # noqa: B018
