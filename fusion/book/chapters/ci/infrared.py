"""The infrared + radar case (Figs. 9-11): the study, its tables and figures, and the sensitivity to the period.

The trackers' readings, x/y ratios and bounds are in ``infrared_readings``."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from fusion._counts import seed as check_seed
from fusion import data
from fusion._limits import work
from fusion._shown import shown
from fusion._validation import as_array, count, given_number, instance_of, scalar
from fusion.book.style import METHOD_LABELS, color, new_figure
from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.filtering.tracks import fuse_tracks
from fusion.scenarios import infrared_radar as ir
from fusion.book.chapters.ci.constants import IR_DURATION, IR_FZ, IR_IMP, IR_T
from fusion._docstrings import reads_results
from fusion.book.chapters.ci.text import _glue_doc
from fusion.book.chapters.ci.checks import _averaging_start, _entries, _frame, _periods, _start_on, _step_index
from fusion.book.glue import _glued_cell
from fusion.book.chapters._defaults import study_defaults

__all__ = ["ir_flown_numbers", "ir_numbers", "ir_study", "ir_table", "ir_figure", "fig11", "sensitivity_table",
           "sensitivity_numbers", "IR_BOUND_LABEL", "IR_SHOWN"]


def _ir_budget(T: object, duration: object, runs: object, names: tuple[str, str, str] = ("T", "duration", "runs"),
               reader: bool = False) -> tuple[float, float, int]:
    """The sizes of an infrared + radar study checked before any draw (fuzz 24c SZ/WN): ``T`` and ``duration``
    positive, ``runs`` a count, the scans ``duration / T + 1`` a grid within the sample ceiling, every sensor's
    measurements ``runs × scans × 2`` within the input budget of the filters (``fusion._limits.MAX_INPUT_ELEMENTS``,
    a MemoryError at 10**7 runs otherwise) and the work and memory of what the study runs (``_ir_units``: the
    simulation, and with ``reader`` the readings of every rule that :func:`ir_study` runs next), summed within the
    work budget before the simulation. A ValueError names ``names`` (the caller's arguments: ``distance`` where the
    duration is a distance flown).
    """
    from fusion._counts import grid_points, input_allocation
    from fusion._validation import positive_scalar

    t_name, d_name, r_name = names
    T = positive_scalar(T, t_name) if t_name else float(T)   # type: ignore[arg-type]
    duration = positive_scalar(duration, d_name)
    runs = count(runs, r_name)
    both = f"{d_name} and {t_name}" if t_name else d_name
    n = grid_points(duration, T, both)
    input_allocation((runs, n, 2), f"{r_name}, {both}")
    _ir_units(n, runs, f"{both} (with {r_name})", reader)
    return T, duration, runs


def _ir_units(n: int, runs: int, names: str, reader: bool = False) -> int:
    """Rules 9 and 17 of an infrared + radar study of ``n`` scans and ``runs`` runs (``_ir_budget``'s count), refused
    naming ``names``; its units. The simulation by ``simulate``'s own budget (``_simulate_budget``: its filters'
    scan re-weighed by fix72e, ``_SIMULATE_SCAN_UNITS``, 77-82 us a scan measured) and, with ``reader``, the readings
    of every rule that :func:`ir_study` runs next (``rmse_by_rule``: ``rule_errors``' own ``_reader_budget``, about
    117,000 units a scan and 305 a run and scan), summed before the simulation (``studies_first``; fix73c, fuzz 65a
    C1: the reader was checked only after the simulation had run, so ``ir_study(0.1, 1, 150_000)`` was refused
    after 11.8 CPU-s and ``ir_study(0.001, 1, 1, duration=62.0)`` after 5.5, both naming ``sim`` and ``rules``)."""
    from fusion.book._study_budget import studies_first
    from fusion.scenarios._infrared_budget import _reader_budget, _simulate_budget

    parts = [lambda: _simulate_budget(runs, n, (names, names))]
    if reader:
        parts.append(lambda: _reader_budget("rule_errors", runs, n, 4, ir.RULES, names))
    return studies_first(parts, names)


def _sensitivity_budget(periods: Sequence[float], runs: int, duration: float) -> int:
    """Rules 9 and 17 of :func:`sensitivity_table` before any simulation: each period's ``simulate`` and the improved
    CI's ``rule_errors``, each by its own budget (``_simulate_budget``, ``_reader_budget``), summed
    (``fusion.book._study_budget.studies_first``), refused naming ``periods, runs and duration``. Fuzz 57a C3: the
    reader's budget was checked only after the simulation (160,000 runs at T = 0.1 refused after 9.6 CPU-s naming
    ``sim`` and ``rules``); C4: the periods were not summed (8 periods at 83,000 runs ran 55.9 CPU-s)."""
    from fusion._counts import grid_points
    from fusion.book._study_budget import studies_first
    from fusion.scenarios._infrared_budget import _reader_budget, _simulate_budget

    names = "periods, runs and duration"

    def period(T: float) -> int:
        K = grid_points(duration, T, names)
        if K < 3:   # simulate's own refusal, before any period runs
            raise ValueError(f"the period {shown(T)} s leaves fewer than three scans in {shown(duration)} s")
        return (_simulate_budget(runs, K, (names, names))
                + _reader_budget("rule_errors", runs, K, 4, {IR_IMP: ir.RULES[IR_IMP]}, names))

    return studies_first([lambda T=T: period(T) for T in periods], names)


def _sensitivity_floor(periods: object, known: Mapping, runs: int, duration: float) -> None:
    """A lower bound of :func:`_sensitivity_budget` by the number of periods alone, before any is read (fix69g, fuzz
    61a C1's class: 10**6 periods were each read, compared and printed first, refused after 3.7 CPU-s): every
    period not in ``known`` (at least their count less ``known``'s size) costs at least a period of three scans,
    the fewest ``simulate`` takes (the longest allowed period). The exact budget, by each period's value, follows."""
    from fusion.book._study_budget import studies_first
    from fusion.scenarios._infrared_budget import _reader_budget, _simulate_budget

    if not isinstance(periods, (list, tuple, range)) and not (isinstance(periods, np.ndarray) and periods.ndim == 1):
        return   # a scalar or another sequence: the exact budget alone
    n, names = len(periods) - len(known), "periods, runs and duration"
    if n <= 0:
        return   # every period may be known: none simulated
    one = studies_first([lambda: _simulate_budget(runs, 3, (names, names))
                         + _reader_budget("rule_errors", runs, 3, 4, {IR_IMP: ir.RULES[IR_IMP]}, names)], names)
    work((n, one), names)


def ir_study(T: float, seed: int, runs: int, duration: float = 10.0,
             azimuth_from: str = "x") -> tuple[ir.IrRadarRuns, dict[str, np.ndarray]]:
    r"""Simulate the infrared + radar case with the printed parameters at sampling period ``T`` (s).

    Parameters
    ----------
    T : float
        Sampling period (s).
    seed : int
        Seed of the :class:`numpy.random.Generator`.
    runs : int
        Monte-Carlo runs.
    duration : float
        Length of the track (s).
    azimuth_from : {"x", "y"}
        Axis the printed azimuth :math:`\pi/5` is measured from: the x axis (counter-clockwise, our
        default) or the y axis (clockwise, the navigation convention), i.e. :math:`\pi/2 - \pi/5` from x.
        The velocities stay as printed (300 m/s in x, 100 m/s in y).

    Returns
    -------
    sim : IrRadarRuns
        The true path, the infrared and radar measurements and the three local tracks of every run, at period ``T``.
    rmse : dict of str to ndarray, shape (K, 4)
        :func:`fusion.scenarios.infrared_radar.rmse_by_rule`.

    Raises
    ------
    ValueError
        ``T`` or ``duration`` not positive, ``runs`` not a count, or ``T``, ``duration`` and ``runs`` whose simulation
        and readings of every rule together hold or run beyond the memory or work budget, before the simulation.
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    from fusion._validation import one_of

    azimuth_from = one_of(azimuth_from, ("x", "y"), "azimuth_from")
    T, duration, runs = _ir_budget(T, duration, runs, reader=True)   # the simulation and its readings (fix73c)
    p = data.WANG2024_IR_RADAR
    sim = ir.simulate(np.random.default_rng(seed), runs=runs, T=T, duration=duration, sigma_ir=p["sigma_ir"],
                      sigma_angle=p["sigma_angle"], sigma_range=p["sigma_range"], r0=p["range"],
                      az0=p["azimuth"] if azimuth_from == "x" else np.pi / 2 - p["azimuth"], el0=p["elevation"],
                      velocity=p["velocity"])
    return sim, ir.rmse_by_rule(sim)


def ir_flown_numbers(seed: int, runs: int, chapter_means: Mapping[str, float], distance: float = 1000.0,
                     t_min: float = 2.0) -> GlueValues:
    """Source §3.5's "目标运动的距离为1 km" read as the distance flown, not the initial range (appendix robustness row).

    The target of :func:`ir_study` (printed parameters, :data:`IR_T`) then flies ``distance`` at its printed
    speed, so the track lasts ``distance / speed`` s instead of :data:`IR_DURATION`; the initial range stays
    the printed one. Only the scans with ``t >= t_min`` enter the means, as in the chapter's Figs. 9-10.

    Parameters
    ----------
    seed : int
        Seed of the simulation (the chapter's infrared + radar seed).
    runs : int
        Monte-Carlo runs.
    chapter_means : mapping of str to float
        The improved CI's late means of the chapter's reading (:func:`fusion.scenarios.infrared_radar.late_means`).
    distance : float
        Distance flown (m).
    t_min : float
        Start of the time average (s).

    Returns
    -------
    dict
        Glue key -> value: the table (``ci_tab_ir_flown``: the improved CI's late means under both readings
        and the published values; the source's 1 km read as the initial range, and ``distance`` in km flown), the flight's length (s), its scans in the average, and the improved CI's
        x and y errors (m) and their order under the distance-flown reading.

    Raises
    ------
    TypeError
        ``chapter_means`` not a mapping, or a mean not a number.
    ValueError
        ``chapter_means`` lacks a column of the table, ``distance`` not positive, ``t_min`` negative or after the
        flight.
    """
    seed = check_seed(seed)
    distance = scalar(distance, "distance", lo=0.0, lo_open=True)
    duration = distance / float(np.linalg.norm(data.WANG2024_IR_RADAR["velocity"]))
    _ir_budget(IR_T, duration, runs, ("", "distance", "runs"), reader=True)   # the flight's study, by distance
    t_min, _ = _averaging_start(t_min, duration)
    chapter_means = _entries(chapter_means, "chapter_means", (ir.AZIMUTH_MRAD, ir.ELEVATION_MRAD, ir.X_M, ir.Y_M),
             "infrared_radar.late_means (the improved CI's entry)", nonnegative=True)
    sim, rmse = ir_study(IR_T, seed, count(runs, "runs"), duration=duration)
    flown = ir.late_means(dict(rmse), sim.t, t_min)[IR_IMP]
    pub = data.WANG2024_IR_RADAR_RMSE.columns
    cols = list(flown)
    table = pd.DataFrame({f"1 km = initial range ({IR_DURATION:g} s, the chapter)": [chapter_means[c] for c in cols],
                          # the label says the distance given (fuzz 26c q1: "1 km" whatever distance)
                          f"{distance / 1000:g} km = distance flown ({duration:.2f} s)": [flown[c] for c in cols],
                          "published": [1e3 * pub["azimuth_rad"][0], 1e3 * pub["elevation_rad"][0], pub["x_m"][0],
                                        pub["y_m"][0]]}, index=cols).T.map(lambda v: float(f"{v:.3g}"))
    x, y = (flown[c] for c in cols if c.startswith(("x", "y")))
    return {"ci_tab_ir_flown": table, "ci_flown_duration": rounded(duration, 2),
            "ci_flown_scans": int((sim.t >= t_min).sum()), "ci_flown_x": float(f"{x:.3g}"), "ci_flown_y": float(f"{y:.3g}"),
            "ci_flown_order": "x above y" if x > y else "x below y"}


def _ir_methods(rmse: object, name: str, read: tuple[str, ...]) -> None:
    """RMSE per scan by method (:func:`ir_study`): a non-empty mapping whose keys are methods (labels of
    METHOD_LABELS), holding those of ``read``; TypeError/ValueError naming ``name``."""
    if isinstance(rmse, Mapping) and not rmse:
        raise ValueError(f"{name} is empty (it must map each method to its RMSE per scan, as ir_study returns)")
    _entries(rmse, name, read, "ir_study", width=None, numbers=False)
    unknown = [k for k in rmse if not isinstance(k, str) or k not in METHOD_LABELS]
    if unknown:
        raise ValueError(f"{name} holds keys that are not methods: {shown(unknown, 120)}")


def _scan_times(t: object, rmse: Mapping, name: str, read: Sequence[str] | None = None
                ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Scan times ``t`` (finite, 1-D, increasing: the late means are over the last scans) and the arrays of ``rmse``
    read (all when ``read`` is None), each one finite non-negative row of four per scan; TypeError/ValueError naming
    ``t`` or ``name[method]``, never numpy's or matplotlib's. Returns ``t`` and those arrays, read as arrays (a
    list or a DataFrame of the rows is array_like: fuzz 26c A4), for the caller to use instead of ``rmse``."""
    t = as_array(t, "t", ndim=1)
    if (np.diff(t) <= 0).any():
        i = int(np.flatnonzero(np.diff(t) <= 0)[0])
        raise ValueError(f"t must increase (scan times, s), got t[{i + 1}] = {shown(float(t[i + 1]))} after "
                         f"t[{i}] = {shown(float(t[i]))}")
    arrays = {}
    for k in (rmse if read is None else read):
        arr = arrays[k] = as_array(rmse[k], f"{name}[{shown(k)}]", ndim=2, nonnegative=True)
        if arr.shape != (t.size, 4):
            raise ValueError(f"{name}[{shown(k)}] must hold one row of four per scan of t ({t.size}, 4), got "
                             f"{arr.shape}")
    return t, arrays


@study_defaults("t", "t_min")  # a default the study does not fit, named by the study (fuzz 36b D1)
def ir_table(rmse: Mapping[str, np.ndarray], t: ArrayLike, t_min: float = 2.0) -> pd.DataFrame:
    """Time-averaged RMSE (``t >= t_min``) of every method and the published improved CI (Figs. 9-10), 3 significant digits.

    Parameters
    ----------
    rmse : mapping of str to ndarray, shape (K, 4)
        RMSE per scan by method (:func:`ir_study`).
    t : array_like, shape (K,)
        Scan times (s).
    t_min : float
        Start of the time average (s).

    Returns
    -------
    pandas.DataFrame
        One row per method and one for the published improved CI, columns azimuth and elevation (mrad), x and y (m).

    Raises
    ------
    TypeError
        ``rmse`` not a mapping.
    ValueError
        ``rmse`` empty or holding a key that is not a method, or an array of it negative; ``t`` not increasing;
        ``t_min`` negative or after the last scan; as :func:`fusion.scenarios.infrared_radar.late_means` for the
        arrays and ``t``.
    """
    _ir_methods(rmse, "rmse", ())
    t_read, arrays = _scan_times(t, rmse, "rmse")
    t_min = _start_on(t_min, t_read)
    pub = data.WANG2024_IR_RADAR_RMSE.columns
    table = pd.DataFrame(ir.late_means(arrays, t, t_min)).T
    table.index = [METHOD_LABELS[m] for m in table.index]
    table.loc["published: improved CI (Figs. 9-10)"] = [1e3 * pub["azimuth_rad"][0], 1e3 * pub["elevation_rad"][0],
                                                        pub["x_m"][0], pub["y_m"][0]]
    return table.map(lambda v: float(f"{v:.3g}"))


@study_defaults("t", "t_min")  # a default the study does not fit, named by the study (fuzz 36b D1)
def ir_figure(t: ArrayLike, rmse: Mapping[str, np.ndarray], bound: ArrayLike | None = None, t_min: float = 2.0) -> Figure:
    """The source's Figs. 9 and 10 recomputed: RMSE per scan of azimuth, elevation, x and y (log scale).

    Parameters
    ----------
    t : array_like, shape (K,)
        Scan times (s).
    rmse : mapping of str to ndarray, shape (K, 4)
        RMSE per scan by method (:func:`ir_study`).
    bound : array_like, shape (K, 4), optional
        The many-scan bound of the simulated flight, both sensors
        (:func:`fusion.scenarios.infrared_radar.many_scan_bound`), drawn dash-dotted from ``t_min``: finite there
        (before ``t_min`` it is not read, and it is undefined, NaN, at the first scan).
    t_min : float
        Start of the drawn bound (s): after the start-up, where the filters' prior on the rates,
        which the bound does not count, and the sampling noise of the RMSE could put a curve below it.

    Returns
    -------
    matplotlib.figure.Figure
        Four log-scale panels (azimuth, elevation in rad; x, y in m): each shown method's RMSE against time, the
        published value and the optional bound.

    Raises
    ------
    TypeError
        ``rmse`` not a mapping.
    ValueError
        ``rmse`` lacks a method drawn (:data:`IR_SHOWN`) or holds a key that is not a method, an array of it or
        ``bound`` is not one finite non-negative row of four per scan of ``t``, ``t`` not finite and increasing,
        ``t_min`` negative or after the last scan.
    """
    _ir_methods(rmse, "rmse", IR_SHOWN)
    t, rmse = _scan_times(t, rmse, "rmse", IR_SHOWN)
    t_min = _start_on(t_min, t)
    if bound is not None:   # undefined (NaN) at the first scan, t = 0: only the scans drawn must be finite
        bound = as_array(bound, "bound", ndim=2, finite=False)
        if bound.shape != (t.size, 4):
            raise ValueError(f"bound must hold one row of four per scan of t ({t.size}, 4), got {bound.shape}")
        as_array(bound[t >= t_min], "bound (its scans from t_min)", nonnegative=True)
    pub = data.WANG2024_IR_RADAR_RMSE.columns
    shown = IR_SHOWN
    styles = ["-", "-", "--", "-", ":", "-"]
    fig, axes = new_figure(2, 2, figsize=(7.5, 7.5), sharex=True)
    panels = [(axes[0, 0], 0, "source Fig. 9(a): azimuth", "rad", pub["azimuth_rad"][0]),
              (axes[0, 1], 1, "source Fig. 9(b): elevation", "rad", pub["elevation_rad"][0]),
              (axes[1, 0], 2, "source Fig. 10(a): x", "m", pub["x_m"][0]),
              (axes[1, 1], 3, "source Fig. 10(b): y", "m", pub["y_m"][0])]
    b = None if bound is None else np.asarray(bound, dtype=float)
    tt = np.asarray(t, dtype=float)
    drawn = tt >= t_min
    for ax, comp, title, unit, published in panels:
        for name, ls in zip(shown, styles):
            ax.plot(t, rmse[name][:, comp], ls, color=color(name), lw=1.1, label=METHOD_LABELS[name])
        if b is not None:
            ax.plot(tt[drawn], b[drawn, comp], "-.", color=color("floor"), lw=1.2, label=IR_BOUND_LABEL)
        ax.axhline(published, color=color("published"), ls=":", lw=1.0, label="published, improved CI")
        ax.set(title=title, ylabel=f"RMSE ({unit})", yscale="log")
    for ax in axes[1]:
        ax.set_xlabel("time (s)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    return fig


#: Methods drawn in :func:`ir_figure`, in legend order.
IR_SHOWN = (ir.IrMethod.RADAR_ALONE, ir.IrMethod.IR_ALONE, ir.IrMethod.CI, ir.IrMethod.SPLIT_CI, ir.IrMethod.CONVEX,
            ir.IrMethod.FUZZY)

#: Legend label of the many-scan bound in :func:`ir_figure`.
IR_BOUND_LABEL = "many-scan bound: both sensors, straight flight"


@reads_results("sim")
@study_defaults("sim", "run", "t_min")  # a default the study does not fit, named by the study (fuzz 34b D2)
def fig11(sim: ir.IrRadarRuns, run: int = 0, t_min: float = 2.0) -> tuple[Figure, float]:
    """The panels of the source's Fig. 11 on the simulated case: one run of the improved CI and its ±2σ band.

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`fusion.scenarios.infrared_radar.simulate`.
    run : int
        Run drawn (0-based).
    t_min : float
        Start of the counted scans (s).

    Returns
    -------
    fig : Figure
        Three panels against time: the improved CI's range (m), elevation and azimuth (rad) errors in run ``run``, with
        the ±2σ band.
    inside : float
        Smallest, over the three panels, share of scans with ``t >= t_min`` whose error lies inside ±2σ.

    Raises
    ------
    TypeError
        ``sim`` not an IrRadarRuns, ``run`` not an integer, ``t_min`` not a number.
    ValueError
        ``run`` not a run of ``sim``, ``t_min`` negative or after the last scan.
    """
    instance_of(sim, ir.IrRadarRuns, "sim")
    run = _step_index(run, "run", sim.radar_range.est.shape[0])
    t_min = _start_on(t_min, sim.t)
    late = sim.t >= t_min
    f_imp = fuse_tracks(sim.ir, sim.radar, "split")
    p_imp = ir.position(sim.radar_range.est[run], f_imp.est[run])
    panels = [("(a) range error (m)", np.linalg.norm(p_imp, axis=-1) - sim.sph[:, 0], np.sqrt(sim.radar_range.gains.P[:, 0, 0])),
              ("(b) elevation error (rad)", f_imp.est[run, :, 2] - sim.sph[:, 2], np.sqrt(f_imp.P[:, 2, 2])),
              ("(c) azimuth error (rad)", f_imp.est[run, :, 0] - sim.sph[:, 1], np.sqrt(f_imp.P[:, 0, 0]))]
    fig, axes = new_figure(3, 1, figsize=(7.0, 6.6), sharex=True)
    for ax, (title, e, sd) in zip(axes, panels):
        ax.plot(sim.t, e, "-", color=color(IR_IMP), lw=1.0,
                label=f"error, improved CI (run {run + 1})")
        ax.fill_between(sim.t, -2 * sd, 2 * sd, color="0.85", label="±2σ reported")
        ax.set(title=title, ylim=(-4 * sd[late].max(), 4 * sd[late].max()))
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2)
    axes[-1].set_xlabel("time (s)")
    inside = min(float(np.mean(np.abs(e[late]) <= 2 * sd[late])) for _, e, sd in panels)
    return fig, inside


def _known_means(known: object) -> dict[float, dict]:
    """``known`` of :func:`sensitivity_table` (fuzz 24c, KN): a mapping of periods (positive numbers) to mappings
    holding the azimuth, x and y means as finite non-negative numbers (RMSEs); TypeError/ValueError naming
    ``known``. Returned by float period, the means read as floats (the other entries as given)."""
    if not isinstance(known, Mapping):
        raise TypeError(f"known must be a mapping of period -> improved-CI means, got {type(known).__name__}")
    out = {}
    for k, v in known.items():
        T = scalar(k, f"known's period {shown(k)}", 0.0, lo_open=True)
        read = _entries(v, f"known[{shown(k)}]", (ir.AZIMUTH_MRAD, ir.X_M, ir.Y_M),
                        "infrared_radar.late_means (the improved CI's entry)", nonnegative=True)
        if T in out:
            raise ValueError(f"known holds the period {shown(T)} twice")
        out[T] = read   # the floats read, not the caller's 0-d arrays (fuzz 26c q4, the rule of fuzz 22b FR)
    return out


@study_defaults("duration", "t_min")  # a default the study does not fit, named by the study (fuzz 36b D1)
def sensitivity_table(periods: ArrayLike, seed: int, runs: int, duration: float = 10.0,
                      t_min: float = 2.0, known: Mapping[float, Mapping[str, float]] | None = None,
                      ) -> tuple[pd.DataFrame, dict[float, dict[str, float]]]:
    """Improved CI's time-averaged RMSE in the infrared + radar case against the sampling period.

    Parameters
    ----------
    periods : array_like
        Sampling periods (s).
    seed : int
        Seed of each period's simulation.
    runs : int
        Monte-Carlo runs per period.
    duration : float
        Length of the track (s).
    t_min : float
        Start of the time average (s).
    known : mapping of float to mapping, optional
        Improved-CI means already computed with the same seed, runs and duration (e.g. the chapter's
        main study), by period; those periods are not simulated again.

    Returns
    -------
    table : pandas.DataFrame
        Azimuth (mrad), x (m), y (m) per period, 3 significant digits.
    means : dict of float to dict
        The unrounded :func:`fusion.scenarios.infrared_radar.late_means` of the improved CI per period (those of
        ``known``: its azimuth, x and y means read as floats).

    Raises
    ------
    TypeError
        ``periods``, ``duration`` or ``t_min`` not numbers; ``known`` not a mapping of mappings, or a period or a
        mean of it not a number.
    ValueError
        ``periods`` empty, repeated or not positive; ``t_min`` negative or after ``duration``; ``known`` with a
        period that is not positive, or without the azimuth, x or y mean, or one not finite and non-negative;
        ``periods``, ``runs`` and ``duration`` whose simulations and readings, summed over the periods not in
        ``known``, hold or run beyond the memory or work budget, before any simulation.
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    t_min, duration = _averaging_start(t_min, duration)
    imp = IR_IMP
    known = {} if known is None else _known_means(known)
    runs = count(runs, "runs")
    _sensitivity_floor(periods, known, runs, duration)   # by their number, before any period is read (fix69g)
    periods = _periods(periods)
    _sensitivity_budget([float(T) for T in periods if float(T) not in known], runs, duration)
    means = {}
    for T in periods:
        if float(T) in known:
            means[float(T)] = known[float(T)]
            continue
        p = data.WANG2024_IR_RADAR
        sim = ir.simulate(np.random.default_rng(seed), runs=runs, T=float(T), duration=duration, sigma_ir=p["sigma_ir"],
                          sigma_angle=p["sigma_angle"], sigma_range=p["sigma_range"], r0=p["range"], az0=p["azimuth"],
                          el0=p["elevation"], velocity=p["velocity"])
        rmse = {name: np.sqrt(np.mean(e**2, axis=0)) for name, e in ir.rule_errors(sim, (imp,)).items()}
        means[float(T)] = ir.late_means(rmse, sim.t, t_min)[imp]
    table = pd.DataFrame({T: {k: v[k] for k in (ir.AZIMUTH_MRAD, ir.X_M, ir.Y_M)} for T, v in means.items()}).T
    table = table.map(lambda v: float(f"{v:.3g}"))
    table.index.name = "sampling period (s), improved CI"
    return table, means


@_glue_doc("rounded as the prose shows it")
def ir_numbers(ir_table: pd.DataFrame, t_ir: float, duration: float) -> GlueValues:
    """The numbers the prose quotes from the infrared + radar study (glue keys ``ci_ir_*``, ``ci_r0``, ...).

    Parameters
    ----------
    ir_table : pandas.DataFrame
        :func:`ir_table` of the study.
    t_ir : float
        Sampling period (s).
    duration : float
        Duration (s).

    Raises
    ------
    TypeError
        ``ir_table`` is not a DataFrame, or ``t_ir`` or ``duration`` not a number.
    ValueError
        ``ir_table`` lacks a row or a column read here or a cell read is not finite and non-negative, or ``t_ir`` or
        ``duration`` is not finite and positive.
    """
    instance_of(ir_table, pd.DataFrame, "ir_table")
    rows = [METHOD_LABELS[k] for k in (IR_IMP, ir.PER_SCAN, IR_FZ, ir.IrMethod.IR_ALONE)]
    cols = [ir.AZIMUTH_MRAD, ir.X_M, ir.Y_M]
    missing = [r for r in rows if r not in ir_table.index] + [c for c in cols if c not in ir_table.columns]
    if missing:
        raise ValueError(f"ir_table lacks the rows or columns {missing} (it must be the ir_table of the study)")
    for r in rows:   # every cell glued: a finite number (the glue rule), named; the values glued as they are
        for c in cols:
            _glued_cell(ir_table, r, c, "ir_table", lo=0.0)   # an RMSE: non-negative (fuzz 24c, NG)
    # glued as the plain numbers given (fuzz 22b, FR: never the caller's Fraction, Decimal or 0-d array)
    t_ir, duration = given_number(t_ir, "t_ir", lo=0.0, lo_open=True), given_number(duration, "duration", lo=0.0,
                                                                                     lo_open=True)
    P_IR = data.WANG2024_IR_RADAR
    ir_pub = data.WANG2024_IR_RADAR_RMSE.columns
    imp, raw_row = ir_table.loc[METHOD_LABELS[IR_IMP]], ir_table.loc[METHOD_LABELS[ir.PER_SCAN]]
    fuzzy_row = ir_table.loc[METHOD_LABELS[IR_FZ]]
    return {"ci_ir_sigma": P_IR["sigma_ir"], "ci_radar_sigma": P_IR["sigma_angle"], "ci_range_sigma": P_IR["sigma_range"],
            "ci_r0": P_IR["range"], "ci_ir_T": t_ir, "ci_ir_duration": duration,
            "ci_ir_az_imp": imp[ir.AZIMUTH_MRAD], "ci_ir_x_imp": imp[ir.X_M], "ci_ir_y_imp": imp[ir.Y_M],
            "ci_ir_az_ir": ir_table.loc[METHOD_LABELS[ir.IrMethod.IR_ALONE], ir.AZIMUTH_MRAD],
            "ci_ir_az_fuzzy": fuzzy_row[ir.AZIMUTH_MRAD], "ci_ir_x_fuzzy": fuzzy_row[ir.X_M], "ci_ir_y_fuzzy": fuzzy_row[ir.Y_M],
            "ci_ir_x_raw": raw_row[ir.X_M], "ci_ir_y_raw": raw_row[ir.Y_M],
            "ci_ir_az_pub": 1e3 * ir_pub["azimuth_rad"][0], "ci_ir_x_pub": ir_pub["x_m"][0], "ci_ir_y_pub": ir_pub["y_m"][0]}


def sensitivity_numbers(sens_table: pd.DataFrame) -> GlueValues:
    """The numbers the prose quotes from :func:`sensitivity_table` (glue keys ``ci_ir_az_best``, ``ci_ir_pub_ratio``, ...).

    Parameters
    ----------
    sens_table : pandas.DataFrame
        The table of :func:`sensitivity_table` (column ``"azimuth (mrad)"``).

    Returns
    -------
    dict
        ``ci_ir_az_best``: smallest azimuth RMSE over the periods (mrad); ``ci_ir_pub_ratio``: the published
        azimuth RMSE over the infrared sensor's σ; ``ci_ir_sigma_mrad``: that σ (mrad); ``ci_ir_scans``: the
        independent scans the published ratio needs, 1/ratio² (2 decimals).

    Raises
    ------
    TypeError
        ``sens_table`` is not a DataFrame.
    ValueError
        ``sens_table`` lacks the column ``"azimuth (mrad)"``, is empty or holds a value there that is not finite and
        non-negative.
    """
    _frame(sens_table, "sens_table", (ir.AZIMUTH_MRAD,), maker="sensitivity_table", nonnegative=(ir.AZIMUTH_MRAD,))
    ir_data = data.WANG2024_IR_RADAR
    ratio = float(data.WANG2024_IR_RADAR_RMSE.columns["azimuth_rad"][0]) / ir_data["sigma_ir"]
    return {"ci_ir_az_best": sens_table[ir.AZIMUTH_MRAD].min(), "ci_ir_pub_ratio": ratio,
            "ci_ir_sigma_mrad": 1e3 * ir_data["sigma_ir"], "ci_ir_scans": rounded(1 / ratio**2, 2)}
