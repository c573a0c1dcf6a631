"""Every reading the stability sweep runs passes its evidence function's entry checks (fix46).

``make stability`` (:mod:`fusion.book.stability`) re-runs each stochastic record's readings under fresh seeds and its
primary reading at ``runs_factor`` times its runs; ``book/ledger/stability.json`` stores each record's result and
factor. A budget that refuses one of these readings makes the stored file irreproducible: fix46 found
``thermocouples.paired_study`` refusing the primary of 8 records of Yang, Feng & Fan (2012) at 10x runs (its methods
counted at ``fuse_epochs``' own pair weight: 2e9 and 6e9 units for calls that ran 2.2 and 3.0 CPU-s). Each task is
evaluated up to its first draw (``numpy.random.default_rng`` raises), so no work runs: a refusal before it is an
entry check's. Eleven more were refused already before fix46 (chapter 06's tracking study at 3x runs, 1.28e10 units;
three lecture studies at 10x, 1.35e9 to 3e9): the book's own calls, they have entries of ``fusion._limits.STUDY_WORK``
under budget35's one rule (``tests/test_budget35.py``).
"""

from __future__ import annotations

import json
import time

import numpy as np
import pytest

from fusion.book import claims as C
from fusion.book import stability as S

class _Drawn(BaseException):
    """Raised at the first draw: the entry checks have passed."""


def _stored() -> dict[str, dict]:
    root = S._ledger_dir(None).parent.parent
    return json.loads((root / "book" / "ledger" / S.STABILITY_FILE).read_text())["records"]


_READINGS = S.stochastic_readings()
_STORED = _stored()
_SPECS = {spec.id: spec for cf in C.load_all(C.claims_dir()).values() for spec in cf.records}


def _params():
    for key in sorted(_READINGS):
        yield pytest.param(key, id=key[1])


@pytest.mark.parametrize("key", list(_params()))
def test_every_sweep_task_passes_its_entry_checks(key, monkeypatch):
    """Every task ``stability.tasks`` builds for the record (one seed, the record's stored runs factor: its primary
    at that many times the runs) reaches its first draw, or returns, within 10 CPU-s: never a ValueError."""
    rid = key[1]
    factor = _STORED[rid]["runs_factor"]
    built = S.tasks({key: _READINGS[key]}, [S.ROOT_SEED], factor)
    assert any(t.scaled for t in built) == (factor > 1)

    def drawn(*args, **kwargs):
        raise _Drawn

    monkeypatch.setattr(np.random, "default_rng", drawn)
    for task in built:
        t0 = time.process_time()
        try:
            C.evaluate(_SPECS[rid], task.reading, task.seed, task.runs)
        except _Drawn:
            pass
        assert time.process_time() - t0 < 10, f"{task}: no draw within 10 CPU-s"
