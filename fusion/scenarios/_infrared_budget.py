"""The work and memory budgets of the readers and bounds of ``fusion.scenarios.infrared_radar`` (fuzz 40a C3-C5), kept
here so that the module stays within its size: each weight measured, as stated."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from fusion._counts import allocation, input_allocation
from fusion._covariances import COVARIANCE_RTOL
from fusion._frozen import constant
from fusion._limits import LOOP_STEP, loop_work, work
from fusion._shown import shown
from fusion.filtering.tracks import _fuse_tracks_units

__all__: list[str] = []

#: Units of one scan of ``simulate``'s filters' Python loop (three tracks, each step a few numpy calls): 77-82 us a
#: scan measured at 1 run of 10,001 and 30,001 scans (the least of two calls, ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, machine shared; fix72e: weighed ``3 * LOOP_STEP``, 30 us, the edge of 1 run, 327,976
#: scans, would run 25-27 CPU-s), weighed about twice that: 1 run is accepted up to 62,313 scans (about 5 CPU-s).
_SIMULATE_SCAN_UNITS = 16 * LOOP_STEP


def _simulate_budget(runs: int, K: int, names: tuple[str, str] = ("runs, T and duration",
                                                                   "T and duration (with runs)")) -> int:
    """Rules 17 and 9 of ``simulate`` on ``runs`` runs of ``K`` scans, before any draw; its units, which a chapter study
    that runs several simulations sums at its entry (fuzz 57a C3, C4). A filter step per run and scan (rule 17); each
    sensor's measurements ``(runs, K, 2)`` as ``local_track``'s input (fuzz 24c SZ: a MemoryError at runs = 10**7, a
    refusal naming the filter's inputs after seconds at 10**6); the filters' Python loop over the scans (three tracks,
    a few numpy calls a step each), named ``names[1]`` (``names[0]`` the others), weighed ``_SIMULATE_SCAN_UNITS`` a
    scan."""
    units = work((runs, K), names[0])
    input_allocation((runs, K, 2), names[0])
    return units + loop_work((K,), 3 * 16 * runs, names[1], step=_SIMULATE_SCAN_UNITS)


#: Units of work of one scan of ``many_scan_bound`` (its vectorised (K, 6, 6) products, sums and solves): 3.8 to
#: 4.8 us measured, 7.5 in fuzz 40a's run at 3e6 scans.
_BOUND_SCAN_UNITS = 750


def _scan_budget(K: int, names: str) -> int:
    """Rules 17 and 9 of ``many_scan_bound`` on a path of ``K`` scans, refused by ``names``: 3.8-4.8 us a scan measured
    at K = 1e5 and 3e5 (the minimum of two calls, ``OPENBLAS_NUM_THREADS=1``, machine shared; 7.5 in the fuzz at 3e6),
    weighed ``_BOUND_SCAN_UNITS``; tracemalloc's peak is 5.1-6.1 arrays of (K, 6, 6), counted as 7. Returns its units."""
    units = work((K,), names, weight=_BOUND_SCAN_UNITS)
    allocation((K, 6, 6), names, arrays=7)
    return units


#: Units of work of one run and scan of ``cartesian_tracks`` (two 6-state Kalman filters and the conversions): 0.96
#: us measured at 10,000 runs of 101 scans (the least of two calls, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``,
#: machine shared; 1.8 us in fuzz 40a's run of 110,000), weighed 150: the edge, 6.7 million, runs 6-12 CPU-s.
_TRACKS_UNITS = 150
#: Units of one scan of ``cartesian_tracks`` whatever its runs (the Python steps of its two filters): 222-260 us a scan
#: measured at 1 run of 20,001 and 40,001 scans (fuzz 41a C3: 0.29 ms; 1 run of 120,001 scans, counted 1.8e7 units by
#: the run-and-scan weight alone, ran 30-35 CPU-s), with 1.2 us a run and scan at 10,000 runs of 101 scans and 100 of
#: 4,001 (the least of two calls, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine shared): 25,000 units, so
#: that 1 run is accepted up to 39,761 scans (about 9-10 CPU-s).
_TRACKS_SCAN_UNITS = 25 * LOOP_STEP


def _tracks_budget(runs: int, K: int, names: str) -> int:
    """Rules 17 and 9 of ``cartesian_tracks`` on ``runs`` runs of ``K`` scans, refused by ``names``:
    ``_TRACKS_SCAN_UNITS`` a scan and ``_TRACKS_UNITS`` a run and scan; tracemalloc's peak 52 float64 a run and scan
    (9 arrays of 6). Returns its units, which a chapter study that runs several trackers sums (fuzz 57a audit)."""
    units = work((K, _TRACKS_SCAN_UNITS + runs * _TRACKS_UNITS), names)
    allocation((runs, K, 6), names, arrays=9)
    return units


#: Units of work per run and scan of ``rule_errors`` and ``cartesian_errors`` (``"base"``: the local tracks'
#: positions and errors; a rule: its ``fuse_tracks`` and its errors), 1.5 times the least of two calls measured at
#: 10,000 runs of 101 scans (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, machine shared with other jobs):
#: rule_errors 23 ns, and 17 (ci), 24 (split), 14 (convex), 99 (fuzzy) a rule; cartesian_errors 15 ns, and 22, 51, 28
#: and 116 a rule (each call with every rule: 2.7 and 2.4 us a run and scan). Fuzz 40a C4, C5.
_READER_UNITS = constant({
    "rule_errors": constant({"base": 35, "ci": 25, "split": 35, "printed": 35, "convex": 25, "fuzzy": 150}),
    "cartesian_errors": constant({"base": 25, "ci": 35, "split": 75, "printed": 75, "convex": 45, "fuzzy": 175}),
})


def _reader_budget(reader: str, runs: int, K: int, n: int, rules: Mapping[str, str], names: str) -> int:
    """Rules 9 and 17 of a reader of a simulation (``rule_errors``, ``cartesian_errors``), at its entry, naming its own
    arguments (fuzz 40a C4, C5: a valid ``simulate`` of 110,000 runs was refused by ``position``'s input budget,
    naming ``angle_est``, after 18 CPU-s, and by ``fuse_tracks``' budget, naming ``a and b``, after 9): the sum of
    its rules' ``fuse_tracks`` (``_fuse_tracks_units``, ``n``-state tracks; fuzz 41a C2) and the reader's measured work
    (``_READER_UNITS``), the (runs, K, 4) arrays it holds at once (tracemalloc's peak: 5 + 2 a rule for
    ``rule_errors``, 3.8 + 2.5 a rule for ``cartesian_errors``) and the input budget of the (runs, K, 4) and
    (runs, K, 3) tracks it passes to ``position`` and ``cartesian_to_spherical``. Returns its units, which a chapter
    study that runs the reader beside its simulation sums at its entry (fuzz 57a C3)."""
    units = _READER_UNITS[reader]
    # the rules' fuse_tracks summed with the reader's own work (fuzz 41a C2: each rule was checked alone, so the five
    # rules on 1 run of 38,901 scans, each just inside, ran 33-37 CPU-s, 0.95 ms a scan): their Python steps and
    # per-step matrix work (``_fuse_tracks_units`` of no run: 117,000 units a scan with every rule), their work per run
    # and scan being in ``_READER_UNITS``' measured weights
    fused = sum(_fuse_tracks_units(K, 0, n, rule) for rule in rules.values())
    total = work((fused + runs * K * (units["base"] + sum(units[rule] for rule in rules.values())),), names)
    arrays = 5 + 2 * len(rules) if reader == "rule_errors" else 4 + (5 * len(rules) + 1) // 2
    allocation((runs, K, 4), names, arrays=arrays)
    input_allocation((runs, K, 4), names)
    return total


#: The relative eigenvalue tolerance of the reader's semidefinite check (``fusion._covariances.as_semidefinite``'s
#: default ``rtol``): a part with an eigenvalue below ``-_SEMIDEFINITE_RTOL`` times its largest entry is refused there.
_SEMIDEFINITE_RTOL = COVARIANCE_RTOL


def _semidefinite_tracks(tracks: Sequence[object], sigma_range: float) -> None:
    """Refuse Cartesian tracks whose covariance parts the reader ``fuse_tracks`` would refuse as not semidefinite
    (fuzz 44 C2), naming ``sim`` and its range noise. At a range noise far beyond the angles' (sigma_range = 2e5 m,
    the book's 5 m), the recursion's round-off leaves the infrared's shared part ``Pd`` an eigenvalue of -3.6e-7 of
    its largest entry (-1.1e-11 at 1e5 m, accepted), and ``cartesian_errors`` refused the producer's output as "P1d
    must be positive semidefinite", an internal name. The same rule as the reader's, on each step (101 eigenvalue
    problems of 6 x 6 a part at the book's path: well under a millisecond); tracks the reader accepts are unchanged."""
    for label, track in zip(("radar", "infrared"), tracks):
        for part in ("Pd", "Pi"):
            P = np.asarray(getattr(track, part))
            S = 0.5 * (P + np.swapaxes(P, -1, -2))
            scale = np.maximum(np.abs(S).max(axis=(-2, -1)), np.finfo(float).tiny)
            worst = float((np.linalg.eigvalsh(S).min(axis=-1) / scale).min())
            if worst < -_SEMIDEFINITE_RTOL:
                raise ValueError(
                    f"sim (its sigma_range = {shown(sigma_range)} m) gives Cartesian tracks that cannot be fused: the "
                    f"{label} track's covariance part {part} has an eigenvalue of {worst:.2g} of its largest entry "
                    f"(round-off of a range noise far beyond the angle noise; the fusion reads at least "
                    f"{-_SEMIDEFINITE_RTOL:g}); simulate with a smaller sigma_range")
