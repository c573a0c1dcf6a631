r"""Chapter 07 (time registration, Shi, Suo & Ma 2023): tables and figure recipes (the claims ledger's evidence is
in :mod:`fusion.book.chapters.time_registration_ledger`).

The computations live in :mod:`fusion.scenarios.time_registration` and
:mod:`fusion.registration`; this module only assembles what the chapter shows.
"""

from __future__ import annotations

import string
from collections.abc import Mapping, Sequence
from enum import StrEnum

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._frozen import constant
from fusion._counts import seed as check_seed
from fusion import data
from fusion._validation import (as_array, as_times, distinct, grid_points, instance_of, one_of, record, scalar,
                                read_mapping, sequence, shown, std_scalar, text)
from fusion._validation import template as format_template
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.glue import GlueValues, _glued_cell
from fusion.book.tables import _display_labels, _frame, integral_index
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod
# the robustness studies (and the paired interval they share with the benchmark) live in their own module
from fusion.book.chapters.time_registration_robustness import (RobustnessReading, _paired, delay_break_even,
                                                               delay_table, robustness_readings, robustness_table)
from fusion.book.chapters.time_registration_robustness import CI_HIGH, CI_LOW, IMPROVED_IS
# Fig. 4's compatibility study (which noise levels could give the published figure) lives in its own module
from fusion.book.chapters.time_registration_fig4 import (_noise_levels, _tuning_work, fig4_compatibility,
                                                          fig4_reading_table)
# the closed form E[MSE] = b + g·σ², its crossings and the Kalman methods' exact transient live in their own module
from fusion.book.chapters.time_registration_closed import B_OFFSET, BETTER_ABOVE, BETTER_BELOW, SIGMA_STAR  # noqa: F401
from fusion.book.chapters import time_registration_closed as _closed
from fusion.book.chapters.time_registration_closed import (_method_names, closed_form_table, crossing_table,
                                                           named_crossings, transient_end, transient_table)
from fusion._counts import count
from fusion.book.chapters._defaults import study_defaults

# named by this module, as before the split (the API page, its back-links to the chapter, the registries)
for _f in (robustness_table, delay_table, delay_break_even, robustness_readings, RobustnessReading,
           fig4_compatibility, fig4_reading_table, closed_form_table, crossing_table, named_crossings, transient_table,
           transient_end):
    _f.__module__ = __name__
del _f

#: The four crossings the chapter names (method better below σ*, method better above), in its order.
NAMED_CROSSINGS = _closed.NAMED_CROSSINGS
#: The Kalman methods of the source's §3 and §4 and their two-point ablation.
KALMAN_METHODS = _closed.KALMAN_METHODS

__all__ = [
    "labelled",
    "FUSION_ALONE",
    "FUSION_UNREGISTERED",
    "exact_numbers",
    "benchmark_numbers",
    "RobustnessReading",
    "robustness_readings",
    "S3_READINGS",
    "delay_break_even",
    "delay_table",
    "fig4_reading_table",
    "TWO",
    "IMPROVED",
    "CAUSAL_IMPROVED",
    "FIG4",
    "noise_free_table",
    "axes_tables",
    "registration_figure",
    "fig4_figure",
    "mc_table",
    "sigma_sweep",
    "sigma_figure",
    "ratio_sweep",
    "ratio_figure",
    "noise_level_table",
    "BenchClass",
    "CLASSES",
    "closed_form_table",
    "crossing_table",
    "benchmark_table",
    "period_change_table",
    "fusion_table",
    "fig4_compatibility",
    "robustness_table",
    "NAMED_CROSSINGS",
    "named_crossings",
    "TUNING_READINGS",
    "tuning_by_noise",
    "KALMAN_METHODS",
    "transient_table",
    "transient_end",
]

TWO = RegMethod.TWO_POINT
IMPROVED = RegMethod.IMPROVED
CAUSAL_IMPROVED = RegMethod.CAUSAL_IMPROVED
#: Row keys of :func:`fusion_table` besides the registration methods: sensor 2 alone, and sensor 2 fused with sensor 1's
#: last sample unregistered (labels in :data:`fusion.book.style.METHOD_LABELS`).
FUSION_ALONE = "reg_sensor_2_alone"
#: Row key of :func:`fusion_table`: sensor 2 fused with sensor 1's last sample, unregistered.
FUSION_UNREGISTERED = "reg_fused_unregistered"
#: Column headers that one function of this module writes and another (or the ledger's values) reads, named once
#: (issue 36): the exact and Monte-Carlo MSEs of a method (the closed form's columns are named in
#: ``time_registration_closed``).
EXACT_MSE = "exact E[MSE] (m²)"
MC_MSE = "Monte Carlo (m²)"
#: Methods of the source's Fig. 4 (and of the headline claim).
FIG4 = (TWO, IMPROVED)
#: The six methods the noise-level figure shows (the table shows every method).
FIGURE_METHODS = (TWO, RegMethod.THREE_POINT, IMPROVED, RegMethod.KALMAN_TWO_POINT, RegMethod.KALMAN_PREDICT,
                  RegMethod.LEAST_SQUARES)


class BenchClass(StrEnum):
    """Keys of the fair benchmark's classes (:data:`CLASSES`); display labels in :data:`fusion.book.style.METHOD_LABELS`.

    Attributes
    ----------
    REAL_TIME
        Methods that use only samples not later than the instant (causal).
    OFFLINE
        Methods that also use the next sample or the whole record.
    """

    REAL_TIME = "reg_real_time"
    OFFLINE = "reg_offline"


def _exact_mses(exact: object, name: str, methods: Sequence[str]) -> Mapping[str, float]:
    """A copy of ``exact``, its MSEs the floats read, when it maps each of ``methods`` to an exact expected MSE, a
    finite number >= 0 (m²): a mapping lacking one is a ValueError naming ``name`` (not a KeyError), a NaN or
    negative MSE is refused by ``name[method]`` (it would fill a table or a line with NaN)."""
    record(exact := read_mapping(exact, name), name, tuple(str(n) for n in methods), extra=True)  # read once
    out = dict(exact)  # type: ignore[call-overload]
    for n in methods:  # the floats read, which the caller computes with (fuzz 22b, FR)
        out[n] = scalar(out[n], f"{name}[{str(n)!r}]", lo=0.0)
    return out


def _runs_of(mc: object, name: str, methods: Sequence[str]) -> sc.MonteCarlo:
    """``mc`` when it is a :class:`~fusion.scenarios.time_registration.MonteCarlo` holding the runs of each of
    ``methods``: a TypeError or a ValueError naming ``name`` otherwise (not a KeyError)."""
    instance_of(mc, sc.MonteCarlo, name)
    lacking = [str(n) for n in methods if n not in mc.per_run]
    if lacking:
        raise ValueError(f"{name} lacks the runs of the methods {lacking} (it holds {[str(n) for n in mc.per_run]})")
    return mc


def _sweep_frame(frame: object, name: str, maker: str) -> pd.DataFrame:
    """``frame`` when it is what ``maker`` returns: a non-empty DataFrame whose columns are method keys, whose cells
    are finite MSEs >= 0 and whose index holds positive finite values (noise levels or periods); a TypeError or a
    ValueError naming ``name`` otherwise (an empty DataFrame would give an empty figure, an unknown column a
    KeyError)."""
    instance_of(frame, pd.DataFrame, name)
    if frame.empty:
        raise ValueError(f"{name} is empty (shape {frame.shape}): it must be the output of {maker}, one method at least")
    unknown = [c for c in frame.columns if not (isinstance(c, str) and c in sc.METHODS)]
    if unknown:
        raise ValueError(f"{name} has columns that are not registration methods: {[shown(c) for c in unknown[:5]]} "
                         f"(it must be the output of {maker})")
    _frame(frame, name, list(dict.fromkeys(frame.columns)), maker=maker, unique=True)  # one row, one column each
    as_array(frame.to_numpy(), name, nonnegative=True)
    if np.any(as_array(frame.index, f"{name}.index") <= 0):
        raise ValueError(f"{name}.index must hold positive values (the output of {maker}), got {list(frame.index)[:5]}")
    return frame


def _label(key: object, template: str = "{}") -> object:
    """Display label of a method key of :class:`~fusion.scenarios.time_registration.RegMethod` (``template``
    filled with it), of :data:`FUSION_ALONE` / :data:`FUSION_UNREGISTERED` or of a :class:`BenchClass`; anything else
    unchanged."""
    if isinstance(key, str) and key in sc.METHODS:
        return template.format(METHOD_LABELS[key])
    if isinstance(key, str) and key in (FUSION_ALONE, FUSION_UNREGISTERED, *BenchClass):
        return METHOD_LABELS[key]
    return key


def _label_template(template: object) -> str:
    """``template`` when it formats one method label (``fusion._validation.template``'s rule, one field ``{}`` or
    ``{0}``, distinct visible labels: ``{:.1}`` gave two methods one label), else a ValueError naming it."""
    template = format_template(template, "template", "label")
    fields = [f for _, f, _, _ in string.Formatter().parse(template) if f is not None]
    if fields not in ([""], ["0"]):
        raise ValueError(f"template = {shown(template)} does not format a method label: it must hold exactly one "
                         f"replacement field, {{}}, for the label; got the fields {fields}")
    _display_labels({k: _label(k, template) for k in (*sc.METHODS, FUSION_ALONE, FUSION_UNREGISTERED, *BenchClass)},
                    "template")  # distinct visible labels (fuzz 30b D3)
    return template


def labelled(table: pd.DataFrame, template: str = "{}") -> pd.DataFrame:
    """A table for display: method (and class) keys replaced by their labels in the index, the columns and the cells.

    Parameters
    ----------
    table : pandas.DataFrame
        A table of this module, keyed by :class:`~fusion.scenarios.time_registration.RegMethod` (in any level of
        its index or columns, or as cell values).
    template : str
        Format of a method's label, ``"{}"`` for the label itself (``"fused, {}"`` for :func:`fusion_table`).

    Returns
    -------
    pandas.DataFrame
        A copy with the labels of :data:`fusion.book.style.METHOD_LABELS`; other entries unchanged.

    Raises
    ------
    TypeError
        If ``table`` is not a DataFrame, or ``template`` not a str.
    ValueError
        If ``template`` does not hold exactly one field ``{}`` (or ``{0}``) whose format applies to a str label
        (``"x"``), holds a width above 99 (``{:>5000000}`` made 5 MB labels), or gives two labels alike (``"{:.1}"``),
        an empty one (``"{:.0}"``) or one with a control or format character (NUL, a direction override).
    """
    if not isinstance(table, pd.DataFrame):
        raise TypeError(f"table must be a pandas DataFrame, got {type(table).__name__}")
    _label_template(template)
    out = table.rename(index=lambda k: _label(k, template), columns=lambda k: _label(k, template))
    keys = [*sc.METHODS, FUSION_ALONE, FUSION_UNREGISTERED]
    for i in range(out.shape[1]):               # by position: labels may repeat
        col = out.iloc[:, i]
        if not pd.api.types.is_numeric_dtype(col) and col.isin(keys).any():
            out.iloc[:, i] = col.map(lambda k: _label(k, template))
    return out


def _record_times(t1: ArrayLike, t2: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Sensor 1's sample times and the registration instants of one record, checked by name.

    ``t1``: at least three strictly increasing samples (the three-point formula's nodes); ``t2``: strictly increasing
    instants within the record, ``t1[0] <= t2 <= t1[-1]`` (an instant outside is an extrapolation, which neither
    the cost count nor the noise gains of the record describe), and neither so far from the flight's start t = 0
    that the true positions there lose the precision of the registration errors (``sc._precise_times``: about
    6e4 s at the source's 2 s sampling).

    Parameters
    ----------
    t1, t2 : array_like
        Sample times and registration instants (s).

    Returns
    -------
    tuple of ndarray
        ``(t1, t2)`` as float arrays.

    Raises
    ------
    ValueError
        Too few samples, times not strictly increasing, an instant outside ``[t1[0], t1[-1]]``, or times too far from
        the flight's start for the precision, naming the argument.
    """
    t1, t2 = as_times(t1, "t1", min_len=3), as_times(t2, "t2")  # strictly increasing times, named
    if t2[0] < t1[0] or t2[-1] > t1[-1]:
        raise ValueError(f"t2 must lie within the record of t1, [{t1[0]:g}, {t1[-1]:g}] s, got instants from "
                         f"{t2[0]:g} to {t2[-1]:g} s (an extrapolation)")
    sc._precise_times(t1, t2, "t1", "t2")  # times whose positions lose the precision (fuzz 24d C): named
    return t1, t2


def _scenario_instants(t2: ArrayLike, min_len: int, why: str) -> np.ndarray:
    """Instants ``t2`` that a function registers onto the scenario's sensor-1 samples (``sc.instants()``), checked
    by name (fuzz 24d W, D3: refused inside by ``monte_carlo``'s names, or extrapolated 1e6 s past the record to a
    gain of 9e22): at least ``min_len`` strictly increasing instants (``why`` says what needs them) in its record."""
    t2 = as_times(t2, "t2")
    if t2.size < min_len:
        raise ValueError(f"t2 must hold at least {min_len} instants ({why}), got {t2.size}")
    s1 = sc.instants()[0]
    if t2[0] < s1[0] or t2[-1] > s1[-1]:
        raise ValueError(f"t2 must lie within the record of the scenario's sensor-1 samples, [{s1[0]:g}, {s1[-1]:g}] "
                         f"s, onto which it is registered; got instants from {t2[0]:g} to {t2[-1]:g} s")
    return t2


def _least_squares_windows(t1: np.ndarray, t2: np.ndarray, name: str = "t2") -> None:
    """Refuse, naming ``t2[i]``, an instant whose least-squares window (sensor 2's period before it, ``(t - 5, t]``
    s in the source) holds fewer than two samples of ``t1``: the straight line through them is undefined there."""
    w = float(sc.SCENARIO["period_2"])
    held = np.searchsorted(t1, t2, side="right") - np.searchsorted(t1, t2 - w, side="right")
    short = np.flatnonzero(held < 2)
    if short.size:
        i = int(short[0])
        raise ValueError(f"{name}[{i}] = {t2[i]:g} s: least squares fits the samples of t1 in the {w:g} s before it, "
                         f"({t2[i] - w:g}, {t2[i]:g}] s, which hold {int(held[i])} (at least 2 are needed)")


def noise_free_table(t1: ArrayLike, t2: ArrayLike) -> pd.DataFrame:
    """Noise-free registration error (m) of two-point, least squares and three-point at each instant.

    Parameters
    ----------
    t1, t2 : array_like
        Sensor-1 sample times and registration instants (s).

    Returns
    -------
    DataFrame
        Index the instants, one column per method (rounded to mm) and the derived two-point remainder
        :func:`fusion.scenarios.time_registration.two_point_remainder`.

    Raises
    ------
    TypeError
        ``t1`` or ``t2`` is not numeric.
    ValueError
        ``t1`` holds fewer than three samples, or the times are not finite and strictly increasing; an instant of
        ``t2`` lies outside the record of ``t1`` (an extrapolation, refused as by
        :func:`~fusion.book.chapters.time_registration_ledger.cost_count`) or has fewer
        than two samples of ``t1`` in the least-squares window before it; records beyond the work budget
        (``fusion._limits.MAX_WORK``, chapter 07's rule ``_registration_work``: 30,000 instants on 30,000 samples).
    """
    t1, t2 = _record_times(t1, t2)    # sample times, the instants within the record: named
    _least_squares_windows(t1, t2)
    methods = (TWO, RegMethod.LEAST_SQUARES, RegMethod.THREE_POINT)
    sc._registration_work(methods, t1.size, t2.size, 1, "t1 and t2")  # rule 17 (fuzz 28b C6: named t_query and t)
    x1, x2 = sc.truth(t1), sc.truth(t2)
    table = pd.DataFrame({n: sc.register(n, t1, x1, t2, 1.0) - x2 for n in methods},
                         index=pd.Index(t2, name="sensor-2 instant (s)")).round(3) + 0.0
    table["derived two-point error"] = sc.two_point_remainder(t1, t2)
    return integral_index(table)


def axes_tables(t1: ArrayLike, t2: ArrayLike) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Published sample counts and axis maxima of Figs. 2-3 beside the scenario's.

    Parameters
    ----------
    t1 : array_like
        Sample times of sensor 1 (s).
    t2 : array_like
        Sample times of sensor 2 (s), the registration instants.

    Returns
    -------
    counts : DataFrame
        Published and computed (``reproduced``: samples in the 40 s window) numbers of measurements of each
        sensor, as integers, in the shape :func:`fusion.book.tables.highlight_mismatches` reads.
    axes : DataFrame
        Published axis maximum (m) of each panel and the largest value it should show (m).

    Raises
    ------
    TypeError
        ``t1`` or ``t2`` is not numeric.
    ValueError
        ``t1`` holds fewer than three samples, the times are not finite and strictly increasing, or an instant of
        ``t2`` lies outside the record of ``t1`` (an extrapolation, refused as by
        :func:`~fusion.book.chapters.time_registration_ledger.cost_count`).
    """
    t1, t2 = _record_times(t1, t2)    # sample times, the instants within the record: named
    x1, x2 = sc.truth(t1), sc.truth(t2)
    ax = data.SHI2023_AXES.columns
    counts = pd.DataFrame({"published": np.asarray(data.SHI2023_CLAIMED_SAMPLES.values).round().astype(int),
                           "reproduced": [int(np.size(t1)), int(np.size(t2))]},
                          index=pd.Index(["sensor 1", "sensor 2"],
                                         name="number of measurements (reproduced: in the 40 s window)"))
    axes = pd.DataFrame(
        {"published axis maximum (m)": [ax[k][0] for k in ("fig2_before_y", "fig2_after_y",
                                                              "fig3_before_y", "fig3_after_y")],
         "largest value in the scenario (m)": [x1.max(), x2.max(), x1.max(), x2.max()]},
        index=pd.Index(["Fig. 2 before", "Fig. 2 after", "Fig. 3 before", "Fig. 3 after"], name="panel"))
    if np.all(axes.to_numpy() == np.round(axes.to_numpy())):   # whole metres: shown as integers
        axes = axes.round().astype(int)
    return counts, axes


#: Line style of each information class in the sweep figures (solid: causal; dashed: look-ahead;
#: dotted: whole record).
_CLASS_LINE = {sc.Information.CAUSAL: "-", sc.Information.LOOK_AHEAD: "--", sc.Information.WHOLE_RECORD: ":"}


def registration_figure(t1: ArrayLike, t2: ArrayLike, method: str, label: str) -> Figure:
    """Figs. 2-3 redrawn against time: noise-free samples before, registered values after (closed figure).

    Parameters
    ----------
    t1 : array_like
        Sample times of sensor 1 (s).
    t2 : array_like
        Registration instants (s).
    method : str
        Registration method (see :func:`fusion.scenarios.time_registration.register`).
    label : str
        Legend label of the method.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).

    Raises
    ------
    TypeError
        ``t1`` or ``t2`` is not numeric, or ``label`` not a str.
    ValueError
        ``t1`` holds fewer than three samples, the times are not finite and strictly increasing, or an instant of
        ``t2`` lies outside the record of ``t1`` (an extrapolation, refused as by
        :func:`~fusion.book.chapters.time_registration_ledger.cost_count`), or (least
        squares) has fewer than two samples of ``t1`` in the window before it; ``method`` is not a method.
    """
    t1, t2 = _record_times(t1, t2)
    method, label = one_of(method, tuple(sc.METHODS), "method"), text(label, "label")
    if method == RegMethod.LEAST_SQUARES:
        _least_squares_windows(t1, t2)
    fig, (a1, a2) = new_figure(1, 2, figsize=(7.5, 3.6))
    a1.plot(t1, sc.truth(t1), "o", ms=4, color=color("sensor 1"), label="sensor 1")
    a1.plot(t2, sc.truth(t2), "s", ms=5, color=color("sensor 2"), label="sensor 2")
    a1.set(title="before registration", xlabel="time (s)", ylabel="x (m)")
    a1.legend(loc="upper left")
    a2.plot(t2, sc.register(method, t1, sc.truth(t1), t2, 1.0), "o", ms=4, color=color("sensor 1"),
            label=f"sensor 1, {label}")
    a2.plot(t2, sc.truth(t2), "s", ms=5, mfc="none", color=color("sensor 2"), label="sensor 2")
    a2.set(title="after registration", xlabel="time (s)")
    a2.legend(loc="upper left")
    plt.close(fig)
    return fig


def fig4_figure(mc: sc.MonteCarlo, exact: Mapping[str, float], axis_max: float) -> Figure:
    """Fig. 4 redrawn: per-run MSE and running mean of two-point and improved (closed figure).

    Parameters
    ----------
    mc : MonteCarlo
        Runs holding both Fig. 4 methods.
    exact : mapping
        Exact expected MSE (m²) of each method (dotted lines); as for :func:`mc_table`, its pairing with ``mc`` is
        the caller's.
    axis_max : float
        Top of the published y-axis (m², dashed line).

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).

    Raises
    ------
    TypeError
        ``mc`` is not a MonteCarlo, ``exact`` not a mapping, or ``axis_max`` not a number.
    ValueError
        ``mc`` lacks the runs of a Fig. 4 method, ``exact`` lacks one or holds an MSE that is not a finite number
        >= 0, or ``axis_max`` is not finite and positive.
    """
    _runs_of(mc, "mc", FIG4)
    exact = _exact_mses(exact, "exact", FIG4)
    axis_max = scalar(axis_max, "axis_max", lo=0.0, lo_open=True)
    fig, (a1, a2) = new_figure(1, 2, figsize=(7.5, 3.3), sharey=True)
    runs = np.arange(1, mc.runs + 1)
    for name, style in zip(FIG4, ("o-", "s-")):
        a1.plot(runs, mc.per_run[name], style, ms=3, color=color(name), label=METHOD_LABELS[name])
        a2.plot(runs, np.cumsum(mc.per_run[name]) / runs, style, ms=3, color=color(name), label=METHOD_LABELS[name])
        a2.axhline(exact[name], color=color(name), lw=0.8, ls=":")
    a1.axhline(axis_max, color=color("published"), lw=0.8, ls="--")
    a1.set(title="per run (dashed: top of\nthe published axis)", xlabel="Monte-Carlo run",
           ylabel="registration MSE (m²)")
    a2.set(title="running mean (dotted:\nexact expectation)", xlabel="Monte-Carlo run")
    handles, labels = a1.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    plt.close(fig)
    return fig


def mc_table(mc: sc.MonteCarlo, exact: Mapping[str, float]) -> pd.DataFrame:
    """Exact expected MSE beside the mean of genuinely simulated runs, for every method.

    Parameters
    ----------
    mc : MonteCarlo
        Simulated runs of every method.
    exact : mapping of str to float
        Exact expected MSE (m²) of each method. The mapping does not record its noise level or instants:
        pairing it with ``mc`` (``mc.sigma``, the default instants) is the caller's, and a mapping of another
        noise level is shown as given, its mismatch appearing as a large ``difference / s.e.`` (fuzz 24d D1).

    Returns
    -------
    DataFrame
        Columns: information used, exact E[MSE] (m²), Monte-Carlo mean (m²), its standard
        error, and (mean - exact) / standard error; rounded to 4 decimals.

    Raises
    ------
    TypeError
        ``mc`` is not a MonteCarlo or ``exact`` not a mapping.
    ValueError
        ``exact`` lacks a method of ``mc`` or holds an MSE that is not a finite number >= 0.
    """
    instance_of(mc, sc.MonteCarlo, "mc")
    exact = _exact_mses(exact, "exact", list(mc.per_run))
    rows = {}
    for name, v in mc.per_run.items():
        se = v.std(ddof=1) / np.sqrt(v.size)
        rows[name] = {"information": METHOD_LABELS[sc.METHODS[name]], EXACT_MSE: exact[name],
                      MC_MSE: v.mean(), "standard error": se,
                      "difference / s.e.": (v.mean() - exact[name]) / se}
    return pd.DataFrame(rows).T.infer_objects().round(4)


def sigma_sweep(sigmas: Sequence[float], names: Sequence[str]) -> pd.DataFrame:
    """Exact expected MSE (m²) of each method (columns) at each noise level (index, m).

    Parameters
    ----------
    sigmas : sequence of float
        Noise standard deviations (m).
    names : sequence of str
        Registration methods.

    Returns
    -------
    pandas.DataFrame
        Index the noise levels σ (m), one column per method of ``names``: the exact expected MSE (m²).

    Raises
    ------
    ValueError
        An entry empty, repeated or invalid, or the sweep beyond the work budget (``fusion._limits.MAX_WORK``, rule
        ``_registration_work``: 54 levels of all fifteen methods, 4,748 of two-point alone).
    """
    sigmas, names = _noise_levels(sigmas, "sigmas"), _method_names(names, "names")   # the checked lists (61a C4)
    sc._exact_work(names, {sc.instants()[1].size: len(sigmas)}, "sigmas and names", period_change=False)  # rule 17
    return pd.DataFrame({n: [sc.expected(n, s) for s in sigmas] for n in names},
                        index=pd.Index(np.asarray(sigmas, dtype=float), name="σ (m)"))


def sigma_figure(sweep: pd.DataFrame) -> Figure:
    """Log-log plot of :func:`sigma_sweep`, the methods of ``FIGURE_METHODS`` only (closed figure).

    Parameters
    ----------
    sweep : pandas.DataFrame
        Output of :func:`sigma_sweep`, holding at least one method of ``FIGURE_METHODS``.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).

    Raises
    ------
    TypeError
        ``sweep`` is not a DataFrame.
    ValueError
        ``sweep`` is not an output of :func:`sigma_sweep` (empty, a column that is not a method, an MSE that is not
        finite and >= 0, a noise level that is not positive) or holds none of the figure's methods (an empty
        figure).
    """
    _sweep_frame(sweep, "sweep", "sigma_sweep")
    if not any(n in sweep for n in FIGURE_METHODS):
        raise ValueError(f"sweep holds none of the figure's methods {[str(n) for n in FIGURE_METHODS]}")
    fig, ax = new_figure(figsize=(7.0, 6.0))
    for name in [n for n in FIGURE_METHODS if n in sweep]:
        ax.loglog(sweep.index, sweep[name], "o", ls=_CLASS_LINE[sc.METHODS[name]], ms=3, color=color(name),
                  label=f"{METHOD_LABELS[name]} [{METHOD_LABELS[sc.METHODS[name]]}]")
    ax.set(xlabel="measurement noise σ (m)", ylabel="expected registration MSE (m²)")
    fig.legend(loc="outside lower center", ncols=1)     # below the axes, which keep the full width
    plt.close(fig)
    return fig


def ratio_sweep(periods: Sequence[float], sigma: float, names: Sequence[str]) -> pd.DataFrame:
    """Exact expected MSE (m²) against sensor 2's period (index, s); sensor 1 keeps 2 s, least squares fits over
    one sensor-2 period, at least the source's 5 s (so that the window holds two samples).

    Parameters
    ----------
    periods : sequence of float
        Periods of sensor 2 (s).
    sigma : float
        Noise standard deviation (m).
    names : sequence of str
        Registration methods, none repeated.

    Returns
    -------
    pandas.DataFrame
        Index sensor 2's period (s), one column per method of ``names``: the exact expected MSE (m²) at ``sigma``.

    Raises
    ------
    TypeError
        ``periods`` or ``names`` is not a sequence, or ``sigma`` not a number.
    ValueError
        ``periods`` is empty, repeats a period (its rows are keyed by the period) or holds one that is not finite
        and positive, or its instants are too many for a record (below about 4e-6 s) or beyond the work budget
        (``fusion._limits.MAX_WORK``, chapter 07's rule ``_registration_work``: with least squares, below about
        0.008 s); ``names`` is empty, repeats a method or holds an unknown one; ``sigma`` is not a valid
        standard deviation.
    """
    items = sequence(periods, "periods")
    if not items:
        raise ValueError("periods is empty (it must hold at least one period of sensor 2)")
    items = [scalar(p, f"periods[{i}]", lo=0.0, lo_open=True) for i, p in enumerate(items)]  # floats (fuzz 22b, FR)
    distinct(items, "periods")
    sigma, names = std_scalar(sigma, "sigma"), _method_names(names, "names")
    span = float(sc.SCENARIO["duration"] - sc.SCENARIO["on_2"])  # rule 17 before any work (fuzz 28b C7: period_2)
    sc._exact_work(names, [grid_points(span, p, f"periods[{i}]") for i, p in enumerate(items)], "periods", False)
    rows = {}
    for p2 in items:
        t1, t2 = sc.instants(p2)
        rows[float(p2)] = {n: sc.expected(n, sigma, t1, t2, window=max(float(p2), 5.0)) for n in names}
    out = pd.DataFrame(rows).T
    out.index.name = "sensor-2 period (s)"
    return integral_index(out)


def ratio_figure(ratio: pd.DataFrame) -> Figure:
    """Plot of :func:`ratio_sweep` (closed figure).

    Parameters
    ----------
    ratio : pandas.DataFrame
        Output of :func:`ratio_sweep`.

    Returns
    -------
    matplotlib.figure.Figure
        Closed (displayed by the chapter).

    Raises
    ------
    TypeError
        ``ratio`` is not a DataFrame.
    ValueError
        ``ratio`` is not an output of :func:`ratio_sweep`: empty (an empty figure), a column that is not a method,
        an MSE that is not finite and >= 0, or a period that is not positive.
    """
    _sweep_frame(ratio, "ratio", "ratio_sweep")
    fig, ax = new_figure(figsize=(7.5, 3.6))
    for name in ratio:
        ax.plot(ratio.index, ratio[name], "o", ls=_CLASS_LINE[sc.METHODS[name]], ms=3, color=color(name),
                label=METHOD_LABELS[name])
    ax.set(xlabel="sensor-2 period (s); sensor 1: 2 s", ylabel="expected MSE (m²)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    plt.close(fig)
    return fig


@study_defaults("mcs", "block")  # a default the study does not fit, named by the study (fuzz 36b D1)
def noise_level_table(mcs: Mapping[float, sc.MonteCarlo], axis_max: float, block: int = 20) -> pd.DataFrame:
    """What Fig. 4 would look like at each noise level, from simulated runs.

    Parameters
    ----------
    mcs : mapping of σ (m) to MonteCarlo
        Runs holding both Fig. 4 methods.
    axis_max : float
        Top of Fig. 4's published y-axis (m²).
    block : int
        Runs per figure (Fig. 4 shows 20).

    Returns
    -------
    DataFrame
        Index σ, columns: runs; fraction of runs with both methods' MSE inside ``[0, axis_max]``; P(improved <
        two-point in one run); P(all ``block`` runs so ordered) estimated as the fraction of disjoint blocks of
        ``block`` runs that are.

    Raises
    ------
    TypeError
        ``mcs`` is not a mapping of noise levels to MonteCarlo runs, or ``axis_max`` or ``block`` not a number.
    ValueError
        ``mcs`` is empty, a key is not a valid standard deviation, an entry lacks the runs of a Fig. 4 method or
        holds runs at another σ than its key;
        ``axis_max`` is not finite and positive, or ``block`` not a positive count or more than an entry's runs
        (no block of ``block`` runs: its probability would be 0/0).
    """
    instance_of(mcs := read_mapping(mcs, "mcs"), Mapping, "mcs")  # read once (fuzz 31a C2)
    if not mcs:
        raise ValueError("mcs is empty (it must map noise levels to Monte-Carlo runs)")
    for k, v in mcs.items():
        std_scalar(k, f"the noise level {shown(k)} of mcs")
        _runs_of(v, f"mcs[{k!r}]", FIG4)
        if float(v.sigma) != float(k):  # the runs carry their σ: a row must not be labelled by another (fuzz 19, E1)
            raise ValueError(f"mcs[{shown(k)}] holds runs at σ = {float(v.sigma):g} m, not at the σ = {float(k):g} m it is "
                             "keyed by")
    axis_max, block = scalar(axis_max, "axis_max", lo=0.0, lo_open=True), count(block, "block")
    fewest = min(mc.runs for mc in mcs.values())
    if block > fewest:  # no disjoint block of `block` runs: an all-NaN column (fuzz 22b, NB1)
        raise ValueError(f"block = {block} is more than the {fewest} runs of an entry of mcs (a block is {block} of "
                         "its runs)")
    rows = {}
    for s, mc in sorted(mcs.items()):
        a, b = mc.per_run[IMPROVED], mc.per_run[TWO]
        wins = a < b
        nb = mc.runs // block
        rows[float(s)] = {
            "runs": mc.runs,
            "both inside the axis": float(np.mean((a <= axis_max) & (b <= axis_max))),
            "P(improved wins a run)": float(np.mean(wins)),
            f"P(all {block} runs ordered)": float(np.mean(wins[: nb * block].reshape(nb, block).all(axis=1))),
        }
    out = pd.DataFrame(rows).T
    out.index.name = "σ (m)"
    out["runs"] = out["runs"].astype(int)
    return out.round(3)


# ---------------------------------------------------------------- issue 17: closed forms, fair benchmark, C6


#: The fair benchmark's two classes, by the information each method uses at an instant.
CLASSES: dict[BenchClass, tuple[str, ...]] = constant({
    BenchClass.REAL_TIME: (RegMethod.TWO_POINT_EXTRAPOLATION, RegMethod.KALMAN_PREDICT, CAUSAL_IMPROVED,
                           RegMethod.LEAST_SQUARES, RegMethod.QLS_CAUSAL),
    BenchClass.OFFLINE: (TWO, RegMethod.THREE_POINT, IMPROVED, RegMethod.KALMAN_TWO_POINT,
                                              RegMethod.QLS_NEXT,
                                              RegMethod.LOCAL_QLS,
                                              RegMethod.FIXED_LAG,
                                              RegMethod.RTS_SMOOTHER, RegMethod.CUBIC_SPLINE),
})




#: Keys of :func:`robustness_readings` that are tunings or initialisations of the filter (no stress test, no
#: change of scenario), with the start-up reading: the study :func:`tuning_by_noise` crosses with the noise level.
TUNING_READINGS: tuple[str, ...] = ("p0-small", "p0-large", "q-small", "q-large", "z1-once", "filter-2sigma",
                                    "start-up")


def tuning_by_noise(sigmas: Sequence[float], runs: int, seed: int) -> pd.DataFrame:
    """The headline (improved minus two-point) under each tuning reading, crossed with the noise level.

    Each reading of :data:`TUNING_READINGS` is run as in the chapter's study
    (:func:`~fusion.book.chapters.time_registration_ledger.study`: seed ``seed + 120 + i``, ``i`` its place in
    :func:`robustness_readings`), so at every σ it uses the same standard-normal draws, scaled by σ; the filter
    assumes the true σ (twice it in the reading "filter assumes 2σ"). A robustness table, not readings of a record.

    Parameters
    ----------
    sigmas : sequence of float
        Noise levels (m).
    runs : int
        Runs per reading and noise level.
    seed : int
        The chapter's seed.

    Returns
    -------
    DataFrame
        Index (choice, reading, σ (m)); exact improved minus two-point (m²), the Monte-Carlo mean paired
        difference, its 95 % interval (m², 4 decimals) and whether the improved method is better, worse or not
        distinguishable (from the interval).

    Raises
    ------
    TypeError
        ``sigmas`` is not a sequence of numbers, ``runs`` or ``seed`` not an integer.
    ValueError
        ``sigmas`` is empty or holds a level that is not a valid standard deviation; ``runs`` below 1; the two
        beyond the work budget (``fusion._limits.MAX_WORK``, chapter 07's rule ``_registration_work``).
    """
    seed, runs = check_seed(seed), count(runs, "runs")   # runs: the int read (fuzz 29a C2); reading i of a level:
    seed = check_seed(seed, span=120 + len(robustness_readings(1.0, sc.instants()[1])) - 1)  # seed + 120 + i (55 C1)
    # rule 17 before any level is read, by their count (fix69g): per level and reading a Monte Carlo, 2 exact
    sigmas = _noise_levels(sigmas, "sigmas", lambda k: _tuning_work(runs, k * len(TUNING_READINGS)))
    rows = {}
    for s in sigmas:
        s = float(s)
        readings = robustness_readings(s, sc.instants()[1])
        for i, rd in enumerate(readings):
            if rd.key not in TUNING_READINGS:
                continue
            c, r, kw = rd.choice, rd.reading, rd.options
            m = sc.monte_carlo([IMPROVED, TWO], s, runs, seed + 120 + i, **kw)  # type: ignore[arg-type]
            d, lo, hi = _paired(m.per_run[IMPROVED], m.per_run[TWO])
            ex = sc.expected(IMPROVED, s, **kw) - sc.expected(TWO, s, **kw)  # type: ignore[arg-type]
            rows[(c, r, s)] = {"exact difference (m²)": ex, "Monte-Carlo difference (m²)": d, CI_LOW: lo,
                               CI_HIGH: hi,
                               IMPROVED_IS: "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable"}
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.names = ["choice", "reading", "σ (m)"]
    num = ["exact difference (m²)", "Monte-Carlo difference (m²)", CI_LOW, CI_HIGH]
    out[num] = out[num].astype(float).round(4) + 0.0
    return out


def benchmark_table(mc: sc.MonteCarlo, exact: Mapping[str, float]) -> pd.DataFrame:
    """The fair benchmark: each class's methods with the paired 95 % interval against the source's method.

    In the real-time class the reference is the source's §3 Kalman method, offline it is the
    improved method of §4.

    Parameters
    ----------
    mc : MonteCarlo
        Runs holding every method of :data:`CLASSES`.
    exact : mapping
        Exact expected MSE (m²) of each method (as for :func:`mc_table`, its pairing with ``mc`` is the caller's).

    Returns
    -------
    DataFrame
        Index (class, method): :class:`BenchClass` and method keys (:func:`labelled` shows their labels); columns
        information, exact E[MSE], Monte-Carlo mean, mean difference from the class reference and its 95 % interval
        (m², 4 decimals), verdict.

    Raises
    ------
    TypeError
        ``mc`` is not a MonteCarlo or ``exact`` not a mapping.
    ValueError
        ``mc`` lacks the runs of a method of :data:`CLASSES`, or ``exact`` lacks one or holds an MSE that is not a
        finite number >= 0.
    """
    _needed = sorted({n for names in CLASSES.values() for n in names} | {RegMethod.KALMAN_PREDICT, IMPROVED})
    _runs_of(mc, "mc", _needed)
    exact = _exact_mses(exact, "exact", _needed)
    rows = {}
    for cls, names in CLASSES.items():
        ref = RegMethod.KALMAN_PREDICT if cls == BenchClass.REAL_TIME else IMPROVED
        for n in sorted(names, key=lambda m: exact[m]):
            d, lo, hi = _paired(mc.per_run[n], mc.per_run[ref]) if n != ref else (0.0, 0.0, 0.0)
            verdict = ("reference" if n == ref else "better" if hi < 0 else "worse" if lo > 0
                       else "not distinguishable")
            rows[(cls, n)] = {"information": METHOD_LABELS[sc.METHODS[n]], EXACT_MSE: exact[n],
                              MC_MSE: float(mc.per_run[n].mean()),
                              "minus reference (m²)": d, CI_LOW: lo, CI_HIGH: hi,
                              "vs the source's method": verdict}
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.names = ["class", "method"]
    num = out.select_dtypes("number").columns
    out[num] = out[num].round(4) + 0.0
    return out


def period_change_table(sigma: float) -> pd.DataFrame:
    """Exact E[MSE] (m²) of the §3 and §4 methods under each driving-noise reading and initialisation.

    Rows: the Q reading and whether the filter also steps to each registration instant (the
    source's change of the filter period); columns: method and initialisation.

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.

    Returns
    -------
    DataFrame
        Rounded to 4 decimals.
    """
    from fusion.registration import INITS, Q_MODELS
    rows = {}
    for qm in Q_MODELS:
        for pc in (False, True):
            rows[(qm, "yes" if pc else "no")] = {
                (m, init): sc.expected(m, sigma, kf={"q_model": qm, "period_change": pc, "init": init})
                for m in (RegMethod.KALMAN_PREDICT, IMPROVED) for init in INITS}
    out = pd.DataFrame(rows).T
    out.index.names = ["Q reading", "period changed at instants"]
    out.columns = pd.MultiIndex.from_tuples(
        [(m, "z₁ used twice (ours)" if i == "source" else "z₁ used once") for m, i in out.columns])
    return out.round(4)


def fusion_table(fr: sc.FusionRuns) -> pd.DataFrame:
    """Mean fused MSE per configuration, with the paired 95 % interval against sensor 2 alone.

    Parameters
    ----------
    fr : FusionRuns

    Returns
    -------
    DataFrame
        Index :data:`FUSION_ALONE`, :data:`FUSION_UNREGISTERED` and the registration methods (fused with sensor 2;
        displayed by :func:`labelled` with ``template="fused, {}"``); rounded to 4 decimals.
    """
    instance_of(fr, sc.FusionRuns, "fr")
    ref = fr.alone
    rows = {}
    for k, v in {FUSION_ALONE: fr.alone, FUSION_UNREGISTERED: fr.unregistered, **fr.fused}.items():
        d, lo, hi = _paired(v, ref) if k != FUSION_ALONE else (0.0, 0.0, 0.0)
        rows[k] = {"mean MSE (m²)": float(v.mean()), "minus sensor 2 alone": d, CI_LOW: lo, CI_HIGH: hi}
    return pd.DataFrame(rows).T.round(4) + 0.0


#: Readings of the §3 Kalman filter alone, compared with two-point extrapolation: (key, choice, reading, ``kf``).
S3_READINGS: tuple[tuple[str, str, str, dict[str, object]], ...] = constant((
    ("per-step-period-changed", "driving noise and filter period", "per-step Q, period changed at the instants",
     {"period_change": True}),
    ("wnj-period-changed", "driving noise and filter period", "white-noise-jerk Q(T), period changed at the instants",
     {"q_model": "white-noise jerk", "period_change": True}),
    ("z1-once", "initialisation", "first measurement used once", {"init": "once"}),
))


def exact_numbers(exact: Mapping[str, float], sigma: float, t2: ArrayLike) -> GlueValues:
    """The exact expected MSEs and noise gains chapter 07's prose quotes (glue keys ``reg_exact_*``, ``reg_gain_*``).

    Parameters
    ----------
    exact : mapping
        Method -> exact expected MSE (m²), from :func:`fusion.scenarios.time_registration.expected`, quoted as given:
        the mapping does not record its noise level, and pairing it with ``sigma`` is the caller's (as for
        :func:`mc_table`, :func:`benchmark_table` and :func:`fig4_figure`).
    sigma : float
        Measurement noise SD (m); the noise gains do not depend on it (fixed weights).
    t2 : array_like
        Registration instants (s), registered onto the scenario's sensor-1 samples: within their record
        (1 s to 39 s); the extrapolation gains use the instants from the second on.

    Returns
    -------
    dict
        Glue key -> value (m², or the dimensionless gain g of E[MSE] = b + g σ²).

    Raises
    ------
    TypeError
        ``exact`` is not a mapping, or ``sigma`` not a number.
    ValueError
        ``exact`` lacks a method quoted or holds an MSE that is not a finite number >= 0; ``sigma`` is not a valid
        standard deviation; ``t2`` holds fewer than two increasing instants or lies outside the record of the
        scenario's sensor-1 samples (an extrapolation far past the record gave gains of 1e22).

    References
    ----------
    * Shi, Suo & Ma (2023), the chapter's source (see the bibliography).
    """
    _needed = (TWO, IMPROVED, RegMethod.LEAST_SQUARES, RegMethod.KALMAN_PREDICT, CAUSAL_IMPROVED,
               RegMethod.TWO_POINT_EXTRAPOLATION, RegMethod.QLS_NEXT, RegMethod.QLS_CAUSAL)
    exact = _exact_mses(exact, "exact", _needed)
    sigma = std_scalar(sigma, "sigma")
    T2 = _scenario_instants(t2, 2, "the extrapolation gains use the instants from the second on")
    SIGMA = sigma
    return {"reg_exact_two": exact[TWO], "reg_exact_impr": exact[IMPROVED],
"reg_exact_ls": exact[RegMethod.LEAST_SQUARES],
            "reg_exact_kf": exact[RegMethod.KALMAN_PREDICT], "reg_exact_causal": exact[CAUSAL_IMPROVED],
            "reg_exact_extrap": exact[RegMethod.TWO_POINT_EXTRAPOLATION],
            "reg_exact_qls": exact[RegMethod.QLS_NEXT],
            "reg_exact_qls_causal": exact[RegMethod.QLS_CAUSAL],
            "reg_gain_three": sc.noise_gain(RegMethod.THREE_POINT), "reg_gain_two": sc.noise_gain(TWO),
            "reg_gain_three_ext": sc.mse_coefficients(RegMethod.THREE_POINT_EXTRAPOLATION, SIGMA, t_dst=T2[1:])[1],
            "reg_gain_two_ext": sc.mse_coefficients(RegMethod.TWO_POINT_EXTRAPOLATION, SIGMA, t_dst=T2[1:])[1]}


def benchmark_numbers(bench: pd.DataFrame) -> GlueValues:
    """The numbers chapter 07's prose quotes from the benchmark table (glue keys ``reg_b_*``).

    Parameters
    ----------
    bench : pandas.DataFrame
        :func:`benchmark_table` (index: information class, method).

    Returns
    -------
    dict
        Glue key -> exact E[MSE] (m²) of the offline methods and the 95 % interval of the quadratic
        least squares and of the causal improved method (m²).

    References
    ----------
    * Shi, Suo & Ma (2023), the chapter's source (see the bibliography).

    Raises
    ------
    TypeError
        ``bench`` is not a DataFrame.
    ValueError
        ``bench`` lacks a row (class, method) or a column read here, holds a row or a column read more than once,
        or a cell read here is not a finite number
        (an exact MSE not >= 0; TypeError for a non-number).
    """
    instance_of(bench, pd.DataFrame, "bench")
    rows = [(BenchClass.OFFLINE, m) for m in (RegMethod.QLS_NEXT, RegMethod.RTS_SMOOTHER, RegMethod.CUBIC_SPLINE)]
    rows.append((BenchClass.REAL_TIME, CAUSAL_IMPROVED))
    missing = [r for r in rows if r not in bench.index] + [c for c in (EXACT_MSE, CI_LOW, CI_HIGH)
                                                           if c not in bench.columns]
    if missing:
        raise ValueError(f"bench lacks the rows or columns {missing} (it must be the output of benchmark_table)")
    _frame(bench, "bench", (EXACT_MSE, CI_LOW, CI_HIGH), maker="benchmark_table", unique=True)  # fuzz 24d T
    off = bench.loc[BenchClass.OFFLINE]
    rt_ = bench.loc[BenchClass.REAL_TIME]

    def cell(part: pd.DataFrame, method: str, column: str) -> float:  # a glued cell: a finite number (the glue rule)
        return _glued_cell(part, method, column, "bench", lo=0.0 if column == EXACT_MSE else None)

    return {"reg_b_qls": cell(off, RegMethod.QLS_NEXT, EXACT_MSE),
            "reg_b_rts": cell(off, RegMethod.RTS_SMOOTHER, EXACT_MSE),
            "reg_b_spline": cell(off, RegMethod.CUBIC_SPLINE, EXACT_MSE),
            "reg_b_qls_lo": cell(off, RegMethod.QLS_NEXT, CI_LOW),
            "reg_b_qls_hi": cell(off, RegMethod.QLS_NEXT, CI_HIGH),
            "reg_b_causal_lo": cell(rt_, CAUSAL_IMPROVED, CI_LOW),
            "reg_b_causal_hi": cell(rt_, CAUSAL_IMPROVED, CI_HIGH)}
