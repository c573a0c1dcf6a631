"""Chapter 01 (the optimal fusion set): the figures and the Monte-Carlo table.

Figs. 1-4 of the source and the Monte-Carlo repetition.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._counts import count, sequence
from fusion._limits import recorded_as, work
from fusion._shown import shown
from fusion._structures import same_keys, within
from fusion._validation import as_array, instance_of, read_mapping, scalar, window as check_window
from fusion.book.style import METHOD_LABELS, _panels, color, new_figure
from fusion.book.tables import _frame, rounded
from fusion.scenarios import thermocouples
from fusion.scenarios.thermocouples import PairedStudy
from fusion.book.chapters.ofs.settings import METHODS, FailureCase
from fusion.book.glue import GlueValues
from fusion.book.chapters._defaults import study_defaults

__all__ = [
    "mc_numbers",
    "figure_readings",
    "figure_errors",
    "mc_table",
    "figure_mc",
    "figure_scale",
]

#: Columns of the Monte-Carlo table that its figure and glue read (issue 36: named once): the best linear
#: estimator's error bound without a failure, and the share of epochs in which the optimal set is the best method.
BOUND_CLEAN = "bound (no failure)"
OFS_BEST_SHARE = "share of epochs where the optimal set is best"

# Sensors of the chapter's bank (every study of :func:`~fusion.book.chapters.ofs.study` fuses ten thermocouples):
# a setting's noise SDs are one per sensor or one for all.
_N_SENSORS = int(np.size(thermocouples.DEFAULT_SIGMAS))


def _studies(studies: object, name: str = "studies") -> Mapping[str, PairedStudy]:
    """``studies`` when it is a non-empty mapping of noise label to PairedStudy (TypeError/ValueError naming it),
    read once (``read_mapping``: the studies checked are the ones used, decision 31a C2)."""
    studies = read_mapping(studies, name)
    instance_of(studies, Mapping, name)
    if not studies:
        raise ValueError(f"{name} must hold at least one noise setting (label -> PairedStudy), got an empty mapping")
    for label, st in studies.items():
        instance_of(st, PairedStudy, f"{name}[{shown(label)}]")
    return studies


def _bounds(sigmas: object, studies: Mapping[str, PairedStudy]) -> dict[str, float]:
    """The bound of each setting from ``sigmas`` (the keys of ``studies``; one SD, or one per sensor of the bank),
    ``sigmas`` read once (``read_mapping``)."""
    sigmas = read_mapping(sigmas, "sigmas")
    same_keys(sigmas, "sigmas", studies, "studies")
    out = {}
    for label in studies:
        where = f"sigmas[{shown(label)}]"
        sig = as_array(sigmas[label], where, ndim=(0, 1))
        if sig.ndim == 1 and sig.size != _N_SENSORS:  # one SD in a list is one sensor's, not all's (fuzz 31b D2)
            raise ValueError(f"{where} must hold one noise SD per sensor of the chapter's bank ({_N_SENSORS}) or be "
                             f"one number for all, got a sequence of {sig.size} SD{'' if sig.size == 1 else 's'}")
        recorded = getattr(studies[label], "sigma", None)   # issue 35, swaps: the noise the study records
        if recorded is not None and (recorded.shape != (_N_SENSORS,) or not recorded_as(sig, recorded)):
            raise ValueError(f"{where} must be the noise SDs of studies[{shown(label)}], which records others (the "
                             "studies or the SDs under each other's label?)")
        with within(where):
            out[label] = thermocouples.best_linear_abs_error(sig)
    return out


def _mc_frame(studies: Mapping[str, PairedStudy], bounds: Mapping[str, float] | None) -> pd.DataFrame:
    """:func:`mc_table` of validated arguments (the bound column NaN throughout when ``bounds`` is None)."""
    rows = {}
    for label, st in studies.items():
        for case in FailureCase:
            failure = case is FailureCase.FAILURE
            row: dict[str, float] = {METHOD_LABELS[m]: float(st.errors(m, failure).mean()) for m in st.clean}
            row[BOUND_CLEAN] = np.nan if failure or bounds is None else bounds[label]
            row[OFS_BEST_SHARE] = st.best_share("optimal_fusion_set", failure)
            rows[(label, METHOD_LABELS[case])] = row                # the case's label
    out = pd.DataFrame(rows).T.round(3)
    out.index.names = ["noise", "case (failure: samples 50-80)"]
    return out


# --------------------------------------------------------------------------- figures
#: Units of work of one entry of ``highlight`` of :func:`figure_readings` (read as a 1-based sensor: 1.3 us measured
#: over 10**6 entries, the shared machine; fix70c), on top of one a sensor for its membership test.
_HIGHLIGHT_UNITS = 130
#: Units of work of one sensor's line in :func:`figure_readings` (an ``ax.plot`` call): 290-390 us measured (400 to
#: 4,000 sensors of 2 to 2,000 samples, the shared machine, other helpers running; fix71d), on top of
#: ``_SAMPLE_UNITS`` a sample drawn.
_SENSOR_UNITS = 40_000
#: Units of one sample of one sensor's line in :func:`figure_readings`: 33-65 ns measured (4 to 40 sensors of 20,000
#: to 200,000 samples, fix71d).
_SAMPLE_UNITS = 7


@study_defaults("readings", "window")  # a default the study does not fit, named by the study (fuzz 34b D2)
def figure_readings(readings: ArrayLike, highlight: Sequence[int] = (), window: tuple[int, int] = (50, 80),
                    truth: float = 900.0) -> Figure:
    """The source's Figs. 1 and 3: every sensor's readings against the sample number.

    Parameters
    ----------
    readings : array_like, shape (n_samples, n_sensors)
        Readings, °C: one line a sensor, at most the work budget (``fusion._limits.MAX_WORK``, 40,000 units a sensor
        plus 7 a sample of it: about 25,000 sensors of few samples), before any is drawn.
    highlight : sequence of int
        1-based sensors drawn bold and labelled (the failing ones); the window is shaded then. At most the work
        budget (``fusion._limits.MAX_WORK``, 130 units an entry plus one a sensor: about 7 million), by their number
        before any is read.
    window : (int, int)
        1-based failure window, shaded when ``highlight`` is given.
    truth : float
        True value drawn as a dotted line, °C.

    Returns
    -------
    matplotlib.figure.Figure
        One panel: each sensor's readings (°C) against the sample, the ``highlight`` sensors in colour, the truth
        dotted, the window shaded.
    """
    z = as_array(readings, "readings", ndim=2)
    # rule 17 by the lines drawn (fuzz 63a C2: the sensors were never counted, (2, 10**5) readings were accepted after
    # 35.6 CPU-s): one ax.plot a sensor, _SENSOR_UNITS each plus _SAMPLE_UNITS a sample
    work((z.shape[1],), "readings", weight=_SENSOR_UNITS + _SAMPLE_UNITS * z.shape[0])
    items = sequence(highlight, "highlight")
    # rule 17 by len(highlight) before any entry is read (fix70c: 10**7 entries were each read, 1.3 us, a bad last
    # one refused after about 13 CPU-s): 130 units an entry read (10**6 entries, the shared machine), and one a sensor
    # for its membership test below
    work((len(items),), "highlight", weight=_HIGHLIGHT_UNITS + z.shape[1])
    hl = [count(h, f"highlight[{i}]", maximum=z.shape[1]) for i, h in enumerate(items)]
    if hl:
        window = check_window(window, "window", z.shape[0], one_based=True)  # the ints read (fuzz 31b C5)
    truth = scalar(truth, "truth")
    t = np.arange(1, z.shape[0] + 1)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    emphasis = ("#D55E00", "#0072B2", "#009E73", "#CC79A7")   # failing sensors, Okabe-Ito
    k = 0
    for i in range(z.shape[1]):
        emph = (i + 1) in hl
        colour = emphasis[k % len(emphasis)] if emph else "0.55"
        k += emph
        ax.plot(t, z[:, i], lw=1.4 if emph else 0.7, alpha=1.0 if emph else 0.7, color=colour,
                label=f"sensor {i + 1}" if emph else None)
    ax.axhline(truth, color=color("truth"), lw=0.8, ls=":")
    ax.set(xlabel="sample", ylabel="reading (°C)")
    if hl:
        ax.axvspan(*window, color="0.9", zorder=0)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def figure_errors(errors: Mapping[str, ArrayLike]) -> Figure:
    """The source's Figs. 2 and 4: absolute error of each method against the sample number.

    Parameters
    ----------
    errors : mapping of method name to array_like, shape (n_samples,)
        Absolute errors, °C; keys are method names of :data:`METHODS`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel: each method's absolute error (°C) against the sample number, with a legend below.

    Raises
    ------
    TypeError
        ``errors`` not a mapping, or an entry not numeric.
    ValueError
        ``errors`` empty, a key not a method of :data:`METHODS`, or an entry not a non-empty finite 1-D array.
    """
    instance_of(errors, Mapping, "errors")
    if not errors:
        raise ValueError("errors must hold the errors of at least one method, got an empty mapping")
    arrays = {}
    for name, e in errors.items():
        if not isinstance(name, str) or name not in METHODS:
            raise ValueError(f"errors must be keyed by methods of METHODS {list(METHODS)}, got the key {shown(name)}")
        arrays[name] = as_array(e, f"errors[{shown(name)}]", ndim=1)
    fig, ax = new_figure(figsize=(7.0, 3.4))
    for name, e in arrays.items():
        ax.plot(np.arange(1, e.size + 1), e, color=color(name), label=METHOD_LABELS[name])
    ax.set(xlabel="sample", ylabel="absolute error (°C)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2)
    return fig


def mc_table(studies: Mapping[str, PairedStudy], sigmas: Mapping[str, ArrayLike]) -> pd.DataFrame:
    """Mean absolute error of each method over runs and samples, per noise setting and case.

    Parameters
    ----------
    studies : mapping of noise label to PairedStudy
    sigmas : mapping of noise label to array_like
        Noise standard deviations (°C) of each setting, for the bound of
        :func:`fusion.scenarios.thermocouples.best_linear_abs_error`.

    Returns
    -------
    DataFrame
        Rows (noise, case: the label of a :class:`~fusion.book.chapters.ofs.FailureCase`); one column per method (°C, 3 decimals), the bound without failure
        (``NaN`` with failure) and the share of epochs at which the optimal set is best.

    Raises
    ------
    TypeError
        ``studies`` not a mapping of :class:`~fusion.scenarios.thermocouples.PairedStudy`, or ``sigmas`` not a mapping.
    ValueError
        ``studies`` empty; ``sigmas`` not holding exactly the labels of ``studies``; a setting's SDs not one
        finite positive number or one per sensor of the chapter's bank (ten; a one-element sequence is refused: one
        SD for all is a number), or not the SDs the study of its label records to a relative ``1e-12``
        (``fusion._limits.RECORDED_RTOL``: the same SDs computed another way are accepted; a study and the SDs under
        each other's label are refused), naming ``sigmas[label]``.
    """
    studies = _studies(studies)
    return _mc_frame(studies, _bounds(sigmas, studies))


def figure_mc(table: pd.DataFrame) -> Figure:
    """Bar chart of :func:`mc_table`: one panel per noise setting, bars per method and case.

    Parameters
    ----------
    table : DataFrame
        Output of :func:`mc_table`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per noise setting: per failure case a bar per method (mean absolute error, °C) and the bound without
        failure.

    Raises
    ------
    TypeError
        ``table`` not a DataFrame.
    ValueError
        ``table`` empty, lacking a column or a (setting, case) row of :func:`mc_table` of the three methods, holding
        a row or a column read more than once, more than 16 noise settings (one panel each, the book style's limit),
        or a cell drawn (a method's MAE, the bound without failure) that is not a finite number >= 0.
    """
    instance_of(table, pd.DataFrame, "table")
    if table.empty:
        raise ValueError("table must hold the rows of mc_table, got an empty table")
    lacking = [c for c in [METHOD_LABELS[m] for m in METHODS] + [BOUND_CLEAN] if c not in table.columns]
    if lacking or table.index.nlevels != 2:
        raise ValueError(f"table must be mc_table of the three METHODS: it lacks the columns {lacking} or its two "
                         f"index levels (noise, case), got {table.index.nlevels}")
    # one row per (setting, case) and one column per method read (fuzz 24d T1-T2: numpy's errors from inside)
    _frame(table, "table", [METHOD_LABELS[m] for m in METHODS] + [BOUND_CLEAN], maker="mc_table", unique=True)
    rows = [(s, METHOD_LABELS[c]) for s in dict.fromkeys(table.index.get_level_values(0)) for c in FailureCase]
    missing = [r for r in rows if r not in table.index]
    if missing:
        raise ValueError(f"table lacks the rows {missing} (mc_table gives both cases of every noise setting)")
    settings = list(dict.fromkeys(table.index.get_level_values(0)))
    _panels(len(settings), "table", "noise settings")   # one panel each (fuzz 63a C5: new_figure named ncols)
    cases = [METHOD_LABELS[c] for c in FailureCase]               # the table's rows are labelled by them
    # the bars and the bound drawn: finite MAEs >= 0 (a missing one would be drawn as no bar); the bound is NaN
    # under failure by design and read only without it
    as_array(table.loc[rows, [METHOD_LABELS[m] for m in METHODS]].to_numpy(), "table's method columns",
             nonnegative=True, subnormal=True)
    as_array(table.loc[[(s, cases[0]) for s in settings], BOUND_CLEAN].to_numpy(), f"table[{BOUND_CLEAN!r}]",
             nonnegative=True, subnormal=True)
    fig, axes = new_figure(1, len(settings), figsize=(7.5, 4.0), sharey=True)
    axes = np.atleast_1d(axes)
    for ax, s_label in zip(axes, settings):
        xpos = np.arange(len(cases))
        for j, m in enumerate(METHODS):
            ax.bar(xpos + (j - 1) * 0.26, [table.loc[(s_label, c), METHOD_LABELS[m]] for c in cases], 0.26,
                   color=color(m), label=METHOD_LABELS[m])
        ax.hlines(table.loc[(s_label, cases[0]), BOUND_CLEAN], -0.45, 0.45, color=color("bound"),
                  lw=2, label="bound (inverse-variance mean)")
        ax.set_xticks(xpos, [f"{cases[0]}\n(all samples)", f"{cases[1]}\n(samples 50-80)"])
        ax.set_title(s_label)
    axes[0].set_ylabel("mean absolute error (°C)")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    return fig


def figure_scale(scales: ArrayLike, sweep: Mapping[str, ArrayLike], default: float = 2.0) -> Figure:
    """Mean absolute error of the optimal fusion set against the scale of eq. 6.

    Parameters
    ----------
    scales : array_like, shape (k,)
        Scales of eq. 6, °C.
    sweep : mapping of case label to array_like, shape (k,) or (k, n_runs)
        Mean absolute error per scale (averaged over runs when 2-D), °C.
    default : float
        The source's scale (factor 1/2 → 2 °C), marked by a dotted line.

    Returns
    -------
    matplotlib.figure.Figure
        One panel: each case's mean absolute error (°C) against the scale of eq. 6 (log₂ axis), the default scale
        dotted.

    Raises
    ------
    TypeError
        ``sweep`` not a mapping, or an argument not numeric.
    ValueError
        ``scales`` not positive and finite; ``sweep`` empty or holding more than two cases (one line style
        each), or an entry whose first axis is not of the length of ``scales``; ``default`` not finite and positive.
    """
    scales = as_array(scales, "scales", ndim=1)
    if np.any(scales <= 0):
        raise ValueError("scales must be positive (drawn on a logarithmic axis)")
    instance_of(sweep, Mapping, "sweep")
    if not 1 <= len(sweep) <= 2:
        raise ValueError(f"sweep must hold one or two cases (label -> errors by scale), got {len(sweep)}")
    lines = {label: as_array(values, f"sweep[{shown(label)}]", ndim=(1, 2)) for label, values in sweep.items()}
    for label, v in lines.items():
        if v.shape[0] != scales.size:
            raise ValueError(f"sweep[{shown(label)}] must hold one row per scale ({scales.size}), got {v.shape[0]}")
    default = scalar(default, "default", lo=0.0, lo_open=True)
    fig, ax = new_figure(figsize=(6.0, 3.2))
    for (label, v), style in zip(lines.items(), ["-o", "--s"]):
        ax.semilogx(scales, v.mean(axis=1) if v.ndim == 2 else v, style, color=color("optimal_fusion_set"),
                    label=label, base=2)
    ax.axvline(default, color=color("truth"), lw=0.8, ls=":")
    ax.set(xlabel="scale of eq. 6 (°C)", ylabel="mean absolute error (°C)")
    ax.legend()
    return fig


def mc_numbers(mc: pd.DataFrame, studies: Mapping[str, PairedStudy], sigmas: Mapping[str, object],
               n_runs: int) -> GlueValues:
    """The numbers chapter 01's prose quotes from the Monte-Carlo table (glue keys ``ofs_mc_*``).

    Parameters
    ----------
    mc : pandas.DataFrame
        :func:`mc_table` of ``studies``.
    studies : mapping
        Noise label -> :class:`~fusion.scenarios.thermocouples.PairedStudy` (unequal noise first, then equal).
    sigmas : mapping
        The same labels -> noise SD (°C), in the same order.
    n_runs : int
        Runs of each study.

    Returns
    -------
    GlueValues
        Glue key -> value (mean absolute errors in °C, 3 decimals; shares; the direct mean-square-error ratio).

    Raises
    ------
    TypeError
        ``mc`` not a DataFrame, ``studies`` not a mapping of two PairedStudy, ``sigmas`` not a mapping, ``n_runs``
        not an integer.
    ValueError
        ``studies`` not of two settings or lacking a method of :data:`METHODS`; ``sigmas`` not of the labels of
        ``studies`` in their order; ``mc`` not :func:`mc_table` of ``studies`` and ``sigmas``; ``n_runs`` not the
        runs of every study; a setting's SDs not valid (as in :func:`mc_table`), or the first setting's SDs all
        equal or the second's not.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    _frame(mc, "mc", (), maker="mc_table")   # the readers' rule (a big-endian column named, fuzz 29b D1)
    studies, sigmas = _studies(studies), read_mapping(sigmas, "sigmas")   # each read once (decision 31a C2)
    if len(studies) != 2:
        raise ValueError(f"studies must hold two noise settings (unequal noise first, then equal), got {len(studies)}")
    for label, st in studies.items():
        lacking = [m for m in METHODS if m not in st.clean]
        if lacking:
            raise ValueError(f"studies[{shown(label)}] lacks the methods {lacking} (a study of the three METHODS)")
    same_keys(sigmas, "sigmas", studies, "studies", ordered=True)

    def differs(want: pd.DataFrame, columns: list[str]) -> bool:
        return not (mc.index.equals(want.index) and list(mc.columns) == list(want.columns)
                    and mc[columns].equals(want[columns]))

    want = _mc_frame(studies, None)
    if differs(want, [c for c in want.columns if c != BOUND_CLEAN]):
        raise ValueError("mc must be mc_table(studies, sigmas): its errors or shares differ from those of studies")
    n_runs = count(n_runs, "n_runs")
    runs = {label: st.n_runs for label, st in studies.items()}
    if any(r != n_runs for r in runs.values()):
        raise ValueError(f"n_runs = {n_runs} must be the runs of each study, got {runs}")
    if differs(_mc_frame(studies, _bounds(sigmas, studies)), [BOUND_CLEAN]):
        raise ValueError("mc must be mc_table(studies, sigmas): its bounds differ from those of sigmas")
    hs, eq = sigmas
    if np.ptp(np.atleast_1d(np.asarray(sigmas[hs], dtype=float))) == 0:
        raise ValueError(f"sigmas[{shown(hs)}] must be the unequal noise (the first setting), got equal SDs")
    if np.ptp(np.atleast_1d(np.asarray(sigmas[eq], dtype=float))) != 0:
        raise ValueError(f"sigmas[{shown(eq)}] must be the equal noise (the second setting), got unequal SDs")
    L = METHOD_LABELS
    C, F = FailureCase.NONE, FailureCase.FAILURE
    mcv = {(s, f, m): rounded(mc.loc[(s, L[f]), L[m]], 3) for s in sigmas for f in FailureCase for m in METHODS}
    share = mc[OFS_BEST_SHARE]
    return {
        "ofs_n_runs": n_runs,
        "ofs_mc_eq_clean_ofs": mcv[(eq, C, "optimal_fusion_set")], "ofs_mc_eq_clean_mean": mcv[(eq, C, "mean")],
        "ofs_mc_hs_clean_ofs": mcv[(hs, C, "optimal_fusion_set")], "ofs_mc_hs_clean_mean": mcv[(hs, C, "mean")],
        "ofs_mc_hs_clean_sup": mcv[(hs, C, "support_degree")],
        "ofs_mc_eq_bound": rounded(mc.loc[(eq, L[C]), BOUND_CLEAN], 3),
        "ofs_mc_hs_fail_ofs": mcv[(hs, F, "optimal_fusion_set")], "ofs_mc_hs_fail_mean": mcv[(hs, F, "mean")],
        "ofs_mc_hs_fail_sup": mcv[(hs, F, "support_degree")],
        "ofs_mc_eq_fail_ofs": mcv[(eq, F, "optimal_fusion_set")], "ofs_mc_eq_fail_sup": mcv[(eq, F, "support_degree")],
        "ofs_mc_best_share_max": rounded(share.max(), 3), "ofs_mc_best_share_min": rounded(share.min(), 3),
        "ofs_mc_mse_ratio": rounded(float(np.mean(studies[eq].clean["optimal_fusion_set"] ** 2)
                                          / np.mean(studies[eq].clean["mean"] ** 2)), 3),
        "ofs_set_size_hs": rounded(studies[hs].set_size.mean(), 2), "ofs_set_size_eq": rounded(studies[eq].set_size.mean(), 2),
    }
