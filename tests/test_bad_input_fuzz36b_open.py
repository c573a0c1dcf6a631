"""Fuzz 36b's open debatable cases (D1-D4) and the caller's mappings read twice, decided by fixing (issue 35).

Each test builds only what it needs (small studies or hand-built objects), never a chapter registry.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pytest


# --- D1: a default the caller never passed is refused naming the caller's study, not the default ----------------

def _d1_calls():
    """(label, call, study name) of chapter functions whose default does not fit a small valid input."""
    from fusion.book.chapters import ci, time_registration as tr
    from fusion.book.chapters.lecture_wavelets import e26
    from fusion.scenarios import time_registration as trs, wavelet_sensors as ws
    from fusion.scenarios.two_sensor import NeesRule

    sim, rmse = ci.ir_study(0.1, 1, 3, duration=1.5)   # a valid 1.5-s flight: the default t_min = 2 s is after it
    nees = {r: np.ones(10) for r in NeesRule}           # 10 steps of 1 s: the default t_steady = 20 s leaves none after
    e2 = ws.signal_study(runs=10, gains=(1.0, 1.5), sigma=(0.1, 0.2), length=256)   # 2 sensors, 10 runs
    e4 = ws.signal_study(runs=10, length=256)                                        # 4 sensors, 10 runs
    mc = trs.monte_carlo(list(trs.METHODS), 1.0, 4, 0)                               # 4 runs: default block = 20
    return [("ir_table", lambda: ci.ir_table(rmse, sim.t), "t"),
            ("ir_figure", lambda: ci.ir_figure(sim.t, rmse), "t"),
            ("sensitivity_table", lambda: ci.sensitivity_table([0.1], 1, 3, duration=1.5), "duration"),
            ("ir_readings", lambda: ci.ir_readings(0.1, 1, 3, duration=1.5), "duration"),
            ("nees_start_table", lambda: ci.nees_start_table(nees, nees, 10), "true_start"),
            ("nees_start_numbers", lambda: ci.nees_start_numbers(nees, nees, 10, {}), "true_start"),
            ("table_seeds sensors", lambda: e26.table_seeds(e2), "e26"),
            ("table_seeds block", lambda: e26.table_seeds(e4), "e26"),
            ("glue_seeds block", lambda: e26.glue_seeds(e4), "e26"),
            ("noise_level_table", lambda: tr.noise_level_table({1.0: mc}, axis_max=4.0), "mcs")]


def test_unpassed_default_named_by_the_study():
    """36b D1: ``ir_table(rmse, sim.t)`` on a valid 1.5-s flight said "t_min = 2 s is after the last scan"; a passed
    ``t_min`` keeps its own name."""
    for label, call, study in _d1_calls():
        with pytest.raises(ValueError, match=rf"^{study} does not fit \w+'s default") as info:
            call()
        assert "pass " in str(info.value), label
    from fusion.book.chapters import ci   # a passed argument keeps its own name (the caller passed it)
    sim, rmse = ci.ir_study(0.1, 1, 3, duration=1.5)
    with pytest.raises(ValueError, match=r"^t_min = 2 s is after the last scan"):
        ci.ir_table(rmse, sim.t, t_min=2.0)
    assert ci.ir_table(rmse, sim.t, t_min=1.0).shape[1] == 4   # valid input keeps working


# --- D2: record ids become glue-key parts by the glue-key rule (ASCII identifiers), refused by the caller's record --

def test_record_ids_as_glue_key_parts():
    """36b D2: ``robustness_glue([{"id": "lec-a b", ...}])`` glued under the key ``lec_rob_a b``; an id composed
    or decomposed gave two keys that print alike."""
    from fusion.book.chapters.lecture_weighting.records import reseeding_glue, robustness_glue
    for rid in ("lec-a b", "lec-a.b", "lec-{x}", "lec-a\nb", "lec-a`b", "lec-\u00e9", "lec-e\u0301", "lec-\uff58"):
        with pytest.raises(ValueError, match=r"records\[1\]\['id'\] must be a record id of ASCII"):
            robustness_glue([{"id": "lec-ok", "robustness": "holds"}, {"id": rid, "robustness": "holds"}])
        with pytest.raises(ValueError, match=r"records\[0\]\['id'\] must be a record id of ASCII"):
            reseeding_glue([{"id": rid, "status": "reproduced", "runs": 300}])
    assert robustness_glue([{"id": "lec-a-b_2", "robustness": "holds"}]) == {"lec_rob_a_b_2": "holds"}


# --- D3: stability.json's fields checked for sense, as make stability writes them --------------------------------

_REC = {"committed": "contradicted", "reseeds": ["contradicted"] * 5, "scaled": "contradicted", "k": 5, "K": 5,
        "flag": False, "failed": [], "runs_factor": 10}


def test_stability_fields_checked_for_sense(tmp_path):
    """36b D3: a record of k > K glued "stable in 9 of 5 reseeds", K = 0 "5 of 0", runs_factor -3 "at -3× the
    runs"; statuses not the rulebook's were glued as written."""
    import json
    from fusion.book.chapters.lecture_weighting.records import reseeding_glue
    (tmp_path / "_toc.yml").write_text("format: jb-book\n")
    (tmp_path / "book" / "ledger").mkdir(parents=True)
    stab = tmp_path / "book" / "ledger" / "stability.json"
    recs = [{"id": "lec-awf-estimated", "status": "contradicted", "runs": 300}]
    stab.write_text(json.dumps({"records": {"lec-awf-estimated": _REC}, "runs_factor": 3}))
    assert "stable in 5 of 5 reseeds and at 10× the runs" in reseeding_glue(recs, tmp_path)["lec_rs_awf_estimated"]
    bad = [dict(k=9), dict(k=-1), dict(K=0, k=0), dict(K=6), dict(runs_factor=0), dict(runs_factor=-3),
           dict(runs_factor=0.5), dict(runs_factor=2.5), dict(scaled="bogus"),
           dict(reseeds=["contradicted"] * 4 + ["maybe"])]
    for change in bad:
        stab.write_text(json.dumps({"records": {"lec-awf-estimated": {**_REC, **change}}, "runs_factor": 3}))
        with pytest.raises(ValueError, match=r"^root: book/ledger/stability.json records\['lec-awf-estimated'\]"):
            reseeding_glue(recs, tmp_path)
    stab.write_text(json.dumps({"records": {"lec-awf-estimated": {k: v for k, v in _REC.items() if k != "runs_factor"}},
                                "runs_factor": -1}))
    with pytest.raises(ValueError, match=r"^root: book/ledger/stability.json: 'runs_factor' must be an integer >= 1"):
        reseeding_glue(recs, tmp_path)


# --- D4: an object array takes the type of its entries, as its list does, where integer or boolean arrays are read --

def test_object_arrays_of_ints_and_bools():
    """36b D4: ``run_program(t1, order=np.array([...], dtype=object))`` was refused "order must hold integers, got
    dtype object" while the list of the same ints is accepted; a boolean mask as an object array likewise."""
    from fusion._selections import as_mask
    from fusion.book.chapters import ofs_audit
    rng = np.random.default_rng(0)
    t1 = 900.0 + rng.normal(size=(6, 4))
    order = [5, 0, 3, 1, 4, 2]
    for program in ("buffer, clean start", "buffer, previous pass"):
        want = ofs_audit.run_program(t1, program, order=order)
        got = ofs_audit.run_program(t1, program, order=np.array(order, dtype=object))
        np.testing.assert_array_equal(got, want)
    c = ofs_audit.Correction(0, 0, float("nan"), "none")   # Table 1 as printed
    want = ofs_audit.explain(c, "buffer, clean start", order=order)
    assert ofs_audit.explain(c, "buffer, clean start", order=np.array(order, dtype=object)).equals(want)
    with pytest.raises(TypeError, match="^order must hold integers"):   # floats stay refused, as in a list
        ofs_audit.run_program(t1, "buffer, clean start", order=np.array([float(i) for i in order], dtype=object))
    mask = [True, False, True]
    np.testing.assert_array_equal(as_mask(np.array(mask, dtype=object), "m"), mask)
    with pytest.raises(TypeError, match="^m must be an array of bools"):
        as_mask(np.array([1, 0, 1], dtype=object), "m")


# --- A caller's mapping read once (decision 31a C2's read_mapping), where it was checked and then read again -------

class _OnePass(Mapping):
    """A mapping that may be read once: a second pass over its keys or a second read of a key raises (a mapping
    whose ``__getitem__`` changes between reads would have one value checked and another used)."""

    def __init__(self, data):
        self._data, self._iters, self._read = dict(data), 0, set()

    def __iter__(self):
        self._iters += 1
        if self._iters > 1:
            raise RuntimeError("read twice")
        return iter(self._data)

    def __getitem__(self, key):
        if key in self._read:
            raise RuntimeError(f"{key!r} read twice")
        value = self._data[key]
        self._read.add(key)
        return value

    def __len__(self):
        return len(self._data)


def test_ofs_mappings_read_once():
    """``mc_table``/``mc_numbers`` read ``studies`` and ``sigmas``, ``closing_numbers`` read ``judged``, once to
    check and again to compute."""
    from fusion.book.chapters import ofs
    from fusion.book.ledger import Comparison
    from fusion.scenarios import thermocouples
    hs, eq = ofs.study(0, 2), ofs.study(1, 2, "equal")
    studies, sigmas = {"hs": hs, "eq": eq}, {"hs": thermocouples.DEFAULT_SIGMAS, "eq": 1.0}
    mc = ofs.mc_table(studies, sigmas)
    assert ofs.mc_table(_OnePass(studies), _OnePass(sigmas)).equals(mc)
    assert ofs.mc_numbers(mc, _OnePass(studies), _OnePass(sigmas), 2) == ofs.mc_numbers(mc, studies, sigmas, 2)
    a = np.arange(100.0) + 1
    cmp = Comparison(a, a + 1, "A", "B", "less", "m")
    judged = {("yang-fig4-unaffected", "equal-noise"): cmp, ("yang-weights-reasonable", "primary"): cmp,
              ("yang-weights-reasonable", "failure"): cmp, ("yang-membership-free", "scale"): cmp}
    ws = ofs.weight_study(0, 2)
    assert (ofs.closing_numbers(hs, eq, ws, _OnePass(judged), 0.05)
            == ofs.closing_numbers(hs, eq, ws, judged, 0.05))


def test_lecture_ledger_values_read_st_once():
    """Chapters 02 and 03's ``ledger_values(st)`` checked ``st[key]`` and read it again (a checked study and another
    used); read once, a study of the wrong type is refused naming it."""
    from fusion.book.chapters.lecture_wavelets import records as wr
    from fusion.book.chapters.lecture_weighting import records as lr
    with pytest.raises(TypeError, match=r"^st\['s23'\]"):
        lr.ledger_values(_OnePass({"s23": 1, "sreg": 1, "s21": 1}))
    with pytest.raises(TypeError, match=r"^st\['\w+'\]"):
        wr.ledger_values(_OnePass({k: 1 for k in wr.STUDIES}))
