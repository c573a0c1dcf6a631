"""Fuzz 28b, chapter 07's work budget (C4-C7, D3) and chapter 06's slice bounds (D4).

Chapter 07: every function whose cost grows with a length the caller gives (times, instants, a list of levels,
periods or latencies) is held to the work budget by one rule, ``fusion.scenarios.time_registration.
_registration_work``, checked before any work and naming the caller's argument (never an inner ``t_query and t``,
``period_2`` or ``t_dst``). A slice argument's bounds are integers or None: a bool is refused wherever a slice is
validated (``fusion._selections``). Each refusal test runs under a short deadline, so that the code before the fix
(which ran for minutes) fails it rather than hangs.
"""

from __future__ import annotations

import re
import signal
from collections.abc import Iterator

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fusion._limits import LOOP_STEP, MAX_WORK
from fusion._validation import frame_slice, selection
from fusion.book.chapters import time_registration as ch
from fusion.book.chapters import time_registration_ledger as trl
from fusion.book.chapters import time_registration_robustness as rob
from fusion.scenarios import time_registration as sc

R = sc.RegMethod
T1, T2 = sc.instants()


@pytest.fixture
def deadline() -> Iterator[None]:
    """Fail a call that starts its work instead of refusing it (2 s of wall time: the refusals take milliseconds)."""
    def expired(signum: int, frame: object) -> None:
        raise TimeoutError("the call ran instead of being refused before its work")

    old = signal.signal(signal.SIGALRM, expired)
    signal.setitimer(signal.ITIMER_REAL, 2.0)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)


def _refused_naming(call, arg: str) -> None:
    """``call`` raises a ValueError whose message starts with the caller's ``arg`` (the budget's subject)."""
    with pytest.raises(ValueError) as exc:
        call()
    msg = str(exc.value)
    assert msg.startswith(arg + " ") or msg.startswith(arg + "["), msg
    assert not re.search(r"\bt_query\b|\bperiod_2\b|\bz0\b", msg), msg


def _dense(n: int) -> np.ndarray:
    """The chapter's instants with ``n - 1`` between the second and the last (valid: increasing, in the record)."""
    return np.concatenate([T2[:1], np.linspace(T2[1], T2[-1], n - 1)])


# --------------------------------------------------------------------------- C4: t2 / t_dst counted
def test_study_counts_t2(deadline: None) -> None:
    _refused_naming(lambda: trl.study(T1, _dense(20000), 1.0, 2, 0), "t2")


def test_monte_carlo_counts_t_dst(deadline: None) -> None:
    _refused_naming(lambda: sc.monte_carlo(list(sc.METHODS), 1.0, 100, 0, t_dst=np.linspace(3.0, 38.0, 20000)),
                    "names, t_src and t_dst")


# --------------------------------------------------------------------------- C5, C6, C7: the caller's names
def test_noise_gain_by_instant_has_a_budget(deadline: None) -> None:
    _refused_naming(lambda: trl.noise_gain_by_instant(np.linspace(1.0, 39.0, 1000), np.linspace(3.0, 38.0, 1000)),
                    "t1 and t2")


def test_noise_free_table_names_t1_and_t2(deadline: None) -> None:
    _refused_naming(lambda: ch.noise_free_table(np.linspace(1.0, 39.0, 30000), np.linspace(3.0, 38.0, 30000)),
                    "t1 and t2")


def test_ratio_sweep_names_periods(deadline: None) -> None:
    _refused_naming(lambda: ch.ratio_sweep((1e-6,), 1.0, (R.TWO_POINT,)), "periods")
    _refused_naming(lambda: ch.ratio_sweep((3.0, 1e-3), 1.0, (R.LEAST_SQUARES,)), "periods")


def test_figs23_fits_names_end(deadline: None) -> None:
    for direction in ("fast onto slow", "slow onto fast"):
        _refused_naming(lambda: trl.figs23_fits(1.0, 1e6, direction), "end")


# --------------------------------------------------------------------------- D3: linear sweeps, the same rule
def test_sweeps_have_the_budget(deadline: None) -> None:
    _refused_naming(lambda: rob.delay_table(list(np.linspace(-0.5, 0.5, 2000)), [1.0]), "delays and sigmas")
    _refused_naming(lambda: ch.sigma_sweep(list(np.linspace(0.1, 5.0, 5000)), [R.TWO_POINT]), "sigmas and names")
    _refused_naming(lambda: trl.cost_values(T1, T2, np.linspace(13.0, 38.0, 30000), 1.0), "t2_ratio")
    _refused_naming(lambda: ch.tuning_by_noise([0.5, 1.0], 10**7, 0), "sigmas and runs")


def test_scenario_entries_name_their_times(deadline: None) -> None:
    t1, t2 = np.linspace(0.5, 39.0, 1000), np.linspace(3.0, 38.0, 1000)
    for call in (lambda: sc.expected(R.LEAST_SQUARES, 1.0, t1, t2),
                 lambda: sc.mse_coefficients(R.LEAST_SQUARES, 1.0, t1, t2),
                 lambda: sc.noise_free_mse(R.LEAST_SQUARES, np.linspace(0.5, 39.0, 10**5),
                                           np.linspace(3.0, 38.0, 10**5))):
        _refused_naming(call, "t_src and t_dst")


def test_the_chapters_sizes_stay_inside() -> None:
    """Valid input keeps working: the book's largest requests are far inside the budget (no refusal of them)."""
    n1, n2 = T1.size, T2.size
    assert sc._registration_work(list(sc.METHODS), n1, n2, (n1 + 1) * 5, "sigmas", period_change=False) < MAX_WORK / 10
    sc._monte_carlo_work(list(sc.METHODS), 10**5, n1, n2, "runs", "t_dst")
    assert ch.ratio_sweep((3.0, 10.0), 1.0, (R.LEAST_SQUARES,)).shape == (2, 1)
    assert trl.noise_gain_by_instant(T1, T2).shape == (n2, 4)


@settings(max_examples=30, deadline=None)
@given(n_src=st.integers(3, 10**6), n_dst=st.integers(1, 10**6))
def test_the_rule_is_at_least_the_inner_budget(n_src: int, n_dst: int) -> None:
    """Whenever least squares' own loop budget refuses (naming its t_query and t), the chapter's rule refuses first."""
    inner = n_dst * (10 * LOOP_STEP + 4 * n_src)
    try:
        outer = sc._registration_work([R.LEAST_SQUARES], n_src, n_dst, 1, "t1 and t2")
    except ValueError as exc:
        assert str(exc).startswith("t1 and t2 ")
        return
    assert outer >= inner and inner <= MAX_WORK


# --------------------------------------------------------------------------- D4: no bool slice bound
_BOOLS = st.sampled_from([True, False, np.True_, np.False_])


@settings(max_examples=40, deadline=None)
@given(part=st.sampled_from(["start", "stop", "step"]), b=_BOOLS)
def test_slice_bounds_refuse_bools(part: str, b: object) -> None:
    bounds = {"start": None, "stop": None, "step": None, part: b}
    s = slice(bounds["start"], bounds["stop"], bounds["step"])
    for call in (lambda: frame_slice(s, "frames", 10), lambda: selection(s, "frames", 10)):
        with pytest.raises(TypeError, match=r"^frames "):
            call()
    # the same slices with integer bounds still select (a bool refused, never its integer)
    ints = slice(*(None if v is None else 1 if k == "step" else int(v) + 1 for k, v in bounds.items()))
    assert len(frame_slice(ints, "frames", 10)) >= 1 and selection(ints, "frames", 10) == ints
    assert list(frame_slice(slice(1, None), "frames", 4)) == [1, 2, 3]
    assert list(frame_slice(slice(np.int64(-2), None, 1), "frames", 4)) == [2, 3]
    assert selection(slice(0, 3), "runs", 5) == slice(0, 3)
