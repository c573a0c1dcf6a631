"""Fuzz 26b (chapter 06), classes R1, FW, NS, VA, SP and GU: valid tracking studies at the edge of the chapter's tables.

One check of a run list (``fusion.book.chapters.chernoff.settings._check_study``), each helper asking for what it
reads: ``window`` (a helper averaging frames 5 on refuses runs of fewer than 5 frames, FW; ``per_run_mse`` as
``per_run_nees``), ``nodes`` (a helper showing every node refuses more than the 3 nodes of ``METHODS``; two nodes are
shown, NS), ``variants`` (a helper reading the variants refuses runs computed without them, VA), ``least`` (a paired
interval needs 2 runs, R1; the readings returning a comparison refuse ``runs = 1`` before their study). Helpers that
read none of these accept such runs. SP: ``method_table`` shows the NEES of a covariance singular to working
precision as undefined (NaN, "—"); GU: the guard's glue leaves out the values of repaired runs when none was.
"""

from __future__ import annotations

import dataclasses
import functools
import re
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from test_bad_input_calls_ch06 import _o


def _sc(**kw: Any) -> Any:
    return dataclasses.replace(_o()["sc"], **kw)


@functools.cache
def _two_nodes() -> Any:
    from fusion.scenarios import range_bearing as dist

    sc = _sc(sensors=_sc().sensors[:2])
    return sc, dist.monte_carlo(sc, 3, 2, workers=1)


def _refuses(call: Any, name: str, what: str) -> None:
    with pytest.raises(ValueError) as exc:
        call()
    msg = str(exc.value)
    assert re.match(rf"^{re.escape(name)}(\[\d+\])? ", msg), msg
    assert what in msg, msg


# ---- FW: no frame of the window "frames 5 on" ------------------------------------------------------------------


def _window_calls(runs: list, sc: Any, crb: Any) -> dict[str, tuple[str, Any]]:
    from fusion.book.chapters import chernoff as chc

    return {"per_run_mse": ("runs", lambda: chc.per_run_mse(runs, "chernoff_pso")),
            "method_table": ("runs", lambda: chc.method_table(runs, crb, runs)),
            "gain_values": ("runs", lambda: chc.gain_values(runs)),
            "collapse_values": ("plain", lambda: chc.collapse_values(runs, sc)),
            "double_count_values": ("runs", lambda: chc.double_count_values(runs, sc)),
            "guard_usability": ("guarded", lambda: chc.guard_usability(runs, runs, sc)),
            "eps_figure": ("runs", lambda: chc.eps_figure(runs, sc)),
            "gm_yardstick": ("runs", lambda: chc.gm_yardstick(np.random.default_rng(0), runs, sc, 3)),
            "review_values": ("runs", lambda: chc.review_values(runs, crb, sc, 1)),
            "stopping_values": ("runs", lambda: chc.stopping_values(runs, sc)),
            "diagnostics": ("runs", lambda: chc.diagnostics(runs, sc, 1))}


def test_fw_runs_of_4_frames_are_refused_by_every_helper_averaging_frames_5_on() -> None:
    from fusion.book.chapters import chernoff as chc

    runs, sc = _o()["frames4"], _sc(frames=4)
    crb = chc.crb_position(sc, runs)  # the bound of every frame: valid
    for fn, (name, call) in _window_calls(runs, sc, crb).items():
        _refuses(call, name, "has 4 frames")
    _refuses(lambda: chc.ev_tracking({"a": "chernoff_pso", "b": "chernoff_uniform"}, seed=1, runs=2, sc=sc),
             "runs", "has 4 frames")


def test_fw_runs_of_4_frames_are_accepted_where_no_window_is_averaged() -> None:
    from fusion.book.chapters import chernoff as chc

    runs, sc = _o()["frames4"], _sc(frames=4)
    crb = chc.crb_position(sc, runs)
    assert crb.shape == (4,) and np.all(np.isfinite(crb))
    plt.close(chc.rmse_figure(runs, crb))
    plt.close(chc.consistency_figure(runs, runs, sc))
    plt.close(chc.pso_figure(runs, frame=3)[0])
    assert chc.readings_values(runs)["chf_rd_frames"] == 4 * len(runs)
    assert chc.any_collapsed(runs, sc).shape == (len(runs),)
    assert chc.guard_values(runs, sc)["chf_n_guarded"] == 0
    assert 0 <= chc.typical_run(runs, sc.n_particles) < len(runs)


# ---- NS: two or four sensors -----------------------------------------------------------------------------------


def test_ns_four_nodes_are_refused_where_every_node_is_shown() -> None:
    from fusion.book.chapters import chernoff as chc

    runs, sc = _o()["nodes4"], _sc(sensors=_sc().sensors + ((500.0, 500.0),))
    crb = chc.crb_position(sc, runs)
    calls = {"method_table": ("runs", lambda: chc.method_table(runs, crb)),
             "rmse_figure": ("runs", lambda: chc.rmse_figure(runs, crb)),
             "double_count_values": ("runs", lambda: chc.double_count_values(runs, sc)),
             "guard_usability": ("guarded", lambda: chc.guard_usability(runs, runs, sc)),
             "consistency_figure": ("runs", lambda: chc.consistency_figure(runs, runs, sc))}
    for fn, (name, call) in calls.items():
        _refuses(call, name, "has 4 nodes")
    # helpers showing no node keep accepting them
    assert np.isfinite(chc.gain_values(runs)["chf_gain_uni"])
    assert np.isfinite(chc.review_values(runs, crb, sc, 1)["chf_prev_d"])


def test_ns_two_nodes_every_node_is_drawn() -> None:
    from fusion.book.chapters import chernoff as chc
    from fusion.book.style import METHOD_LABELS

    sc, runs = _two_nodes()
    crb = chc.crb_position(sc, runs)
    fig = chc.rmse_figure(runs, crb)
    labels = [ln.get_label() for ln in fig.axes[0].get_lines()]
    assert METHOD_LABELS["local1"] in labels and METHOD_LABELS["local2"] in labels
    assert METHOD_LABELS["local3"] not in labels
    rows = chc.method_table(runs, crb).index
    assert METHOD_LABELS["local2"] in rows and METHOD_LABELS["local3"] not in rows


# ---- VA: runs computed without the variants --------------------------------------------------------------------


def test_va_runs_without_the_variants_are_refused_by_name_where_they_are_read() -> None:
    from fusion.book.chapters import chernoff as chc

    runs, sc = _o()["novariants"], _sc(variants=False)
    crb = chc.crb_position(sc, runs)
    calls = {"method_table": lambda: chc.method_table(runs, crb, runs), "gain_values": lambda: chc.gain_values(runs),
             "stopping_values": lambda: chc.stopping_values(runs, sc), "readings_values": lambda: chc.readings_values(runs),
             "equal_kl_g_values": lambda: chc.equal_kl_g_values(runs), "eps_figure": lambda: chc.eps_figure(runs, sc),
             "pso_figure": lambda: chc.pso_figure(runs, frame=3), "diagnostics": lambda: chc.diagnostics(runs, sc, 1),
             "review_values": lambda: chc.review_values(runs, crb, sc, 1)}
    for fn, call in calls.items():
        _refuses(call, "runs", "variants=True")
    # helpers that do not read the variants keep accepting them
    plt.close(chc.rmse_figure(runs, crb))
    assert np.isfinite(chc.double_count_values(runs, sc)["chf_lin_nees_1"])


# ---- R1: one run -----------------------------------------------------------------------------------------------


def test_r1_one_run_paired_readings_name_runs() -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    _refuses(lambda: chc.stopping_values(o["guarded"][:1], o["sc"]), "runs", "at least 2")
    for call in (lambda: chc.ev_tracking({"a": "chernoff_pso", "b": "chernoff_uniform"}, seed=1, runs=1, sc=o["sc"]),
                 lambda: chc.ev_is({"r": 50}, seed=1, runs=1)):
        _refuses(call, "runs", ">= 2")


def test_r1_gain_values_of_one_run_has_no_standard_error() -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    one = chc.gain_values(o["guarded"][:1])
    assert not any(k.endswith("_se") for k in one)
    assert all(np.isfinite(v) for v in one.values())
    two = chc.gain_values(o["guarded"][:2])
    assert {"chf_gain_uni_se", "chf_gain_ci_se", "chf_gain_prev_se"} <= set(two)
    assert {k: v for k, v in two.items() if not k.endswith("_se")}.keys() == one.keys()


# ---- SP: a covariance singular to working precision ------------------------------------------------------------


@settings(max_examples=8, deadline=None)
@given(run=st.integers(0, 2), frame=st.integers(0, 5))
def test_sp_singular_covariance_gives_an_undefined_nees_cell(run: int, frame: int) -> None:
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters.chernoff.tracking import RMSE_LATE
    from fusion.book.style import METHOD_LABELS

    o = _o()
    runs = list(o["guarded"])
    P = np.array(runs[run].covariances["chernoff_prev"])
    v = np.array([1.0, 0.0, 1.0, 0.0])
    P[frame] = 100.0 * np.outer(v, v) + np.diag([0.0, 1.0, 0.0, 1.0])  # rank 3: singular, positive semidefinite
    runs[run] = dataclasses.replace(runs[run], covariances={**runs[run].covariances, "chernoff_prev": P})
    table = chc.method_table(runs, o["crb"], o["plain"])
    row = METHOD_LABELS["chernoff_prev"]
    early, late = "NEES, frames 1-4", "mean NEES (4-D), frames 5-6"  # the study's 6 frames (fuzz 27b D3)
    undefined, defined = (early, late) if frame < 4 else (late, early)
    assert np.isnan(table.loc[row, undefined])
    assert table.loc[row, defined] == o["table"].loc[row, defined]
    assert table.loc[row, RMSE_LATE] == o["table"].loc[row, RMSE_LATE]
    others = table.drop(index=row)
    assert others.equals(o["table"].drop(index=row))


# ---- GU: the guard acted in no run -----------------------------------------------------------------------------


def test_gu_no_guarded_run_leaves_out_the_values_of_repaired_runs() -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    g, p, sc = o["guarded"], o["plain"], o["sc"]
    assert not any(r.guarded for r in g)  # the registry's study: the guard acts in no run
    v = chc.guard_usability(g, p, sc)
    assert v["chf_gu_runs"] == 0
    absent = {"chf_gu_worst_run", "chf_gu_worst_nees", "chf_gu_worst_node", "chf_gu_worst_repaired",
              "chf_gu_nees_max", "chf_gu_nees_rank", "chf_gu_mse_max", "chf_gu_mse_rank", "chf_gu_own_ratio_max"}
    assert not absent & set(v)
    assert v["chf_gu_usable"] is True and v["chf_gu_own_usable"] is True
    perm = [2, 0, 1]
    assert chc.guard_usability([g[i] for i in perm], [p[i] for i in perm], sc) == v  # no order-dependent value
    gv = chc.guard_values(g, sc)
    assert gv["chf_n_guarded"] == 0 and not {"chf_guard_ess_min", "chf_guard_central_min"} & set(gv)


def test_gu_a_guarded_run_gives_the_values_of_repaired_runs() -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    sc = o["sc"]
    g = [dataclasses.replace(o["guarded"][0], guarded=((2, 1),)), *o["guarded"][1:]]
    v = chc.guard_usability(g, o["plain"], sc)
    assert v["chf_gu_runs"] == 1 and v["chf_gu_worst_run"] == 1 and v["chf_gu_worst_repaired"] == "node 2"
    assert {"chf_gu_nees_max", "chf_gu_mse_max", "chf_gu_own_ratio_max"} <= set(v)
    gv = chc.guard_values(g, sc)
    assert {"chf_guard_ess_min", "chf_guard_central_min"} <= set(gv)


@pytest.mark.parametrize("reading", ["runs", "guard"])
def test_gu_the_filter_design_reading_of_a_study_without_repaired_runs(reading: str) -> None:
    """ev_filter_design reads guard_usability: with no repaired run it says so (no value of a repaired run to quote)."""
    from fusion.book.chapters import chernoff as chc
    from fusion.book.ledger import Conjunction, Proposition

    o = _o()
    r = chc.ev_filter_design({"reading": reading}, seed=1, runs=3, sc=o["sc"])
    parts = [r] if isinstance(r, Proposition) else [p for _, p in r.parts]
    assert isinstance(r, (Proposition, Conjunction))
    assert any("0 repaired" in p.ours for p in parts)
