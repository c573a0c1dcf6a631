"""Work budgets of :mod:`fusion.book.chapters.ofs_audit`'s functions whose work grows with their arguments (rule 17).

Book audit 76: :func:`~fusion.book.chapters.ofs_audit.run_program`, :func:`~fusion.book.chapters.ofs_audit.corrections`
and :func:`~fusion.book.chapters.ofs_audit.joint_audit` had no budget. Every weight below was measured with
``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the minimum of 2 runs, on a shared 2-core machine (loaded by
other jobs: the times err high), and is about twice its measurement.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fusion._counts import allocation
from fusion._limits import LOOP_STEP, loop_work, work

# run_program: the correct values (set members and eqs. 6-12 on every row of every table) cost 31-52 ns a pair of
# readings (t1 (1000, 6, 30): 0.17 CPU-s; (1000, 6, 100): 3.1 CPU-s): 10 units a pair. A stateful program's Python
# loop (passes x n_obs steps) cost 104 us a step (t1 (1, 10000, 3), "buffer, previous pass": 2.08 CPU-s; "set not
# reset" 70 us) and 0.42 us a row of a step (t1 (10**5, 6, 3): 0.50 CPU-s), 1.7 ns a pair at n = 100: a step
# 20 * LOOP_STEP, a row of it 80 units plus one a pair. Before: t1 (1, 10**7, 3) was accepted, about 2,000 CPU-s.
_PAIR = 10
_PROGRAM_STEP = 20 * LOOP_STEP
_PROGRAM_ROW = 80
# corrections: 20-22 us a Correction (t1 (3, 200), window 20: 240,600 in 4.8 CPU-s; the printed table at window
# 1000: 360,000 in 8.0 CPU-s): 4,000 units a grid value. Before: no budget, t1 (3, 2000) at window 20 about 48 CPU-s.
# A reading's slips and swaps grow with its printed form f"{v:.1f}" (about 10 candidates a character, each a string
# operation and a Correction; fuzz 68b C3: (2, 1000) readings of 1.2e149, 152 characters each, were weighed a flat
# 80,000 units and ran 25.8 CPU-s): 0.32 ms a reading of 5 characters (t1 (3, 200) of 850-950 °C, slips_only:
# 0.19 CPU-s), 0.92 ms of 8 (1e5), 2.7 ms of 23 (1e20), 13.8 ms of 152 (1.2e149; (2, 50) each), i.e. 64 to 120 us a
# character: 25,000 units (250 us) a printed character.
_CORRECTION = 4000
_PRINTED_CHAR = 25_000
# joint_audit: 0.86, 3.2 and 5.9 CPU-s at window 20, 100 and 200 (0.3 CPU-s plus 80 us a correction of the 18
# printed readings: 16,000 units each); "slips" 12.7 CPU-s at window 20, its 720 orders of ~670 slips counted
# 6 * 10**8 units (its measured cost, loaded, is beyond twice: the default window stays accepted, its edge ~14 CPU-s).
# Before: window up to 1000 (MAX_WINDOW), about 28 CPU-s ("mean-consistent") and 40 CPU-s ("slips").
_JOINT_CORRECTION = 16_000
_JOINT_FIXED = {"mean-consistent": 60_000_000, "slips": 600_000_000}


def grid_values(window: float) -> int:
    """The "other value" corrections of one reading: the 0.1 °C grid within ``window`` of it."""
    return 2 * round(window * 10) + 1


def program_budget(shape: tuple[int, int, int], passes: int, stateful: bool) -> None:
    """Refuse :func:`run_program` on a ``(H, n_obs, n)`` table beyond the work budget, naming ``t1``."""
    H, n_obs, n = shape
    allocation((H * n_obs, n, n), "t1", arrays=2)
    units = work((H * n_obs, n, n), "t1", weight=_PAIR)
    if stateful:
        units += loop_work((passes, n_obs), H * (_PROGRAM_ROW + n * n), "t1", step=_PROGRAM_STEP)
    work((units,), "t1")


def printed_characters(t: ArrayLike) -> int:
    """The characters of every reading of ``t`` printed as ``f"{v:.1f}"`` (sign, integer digits, point, tenth).

    Read from the magnitudes, vectorised (a reading of 9.96 prints as "10.0": the tenth's rounding is counted).
    """
    m = np.abs(np.asarray(t, dtype=float))
    digits = np.floor(np.log10(np.maximum(m + 0.05, 1.0))) + 1.0
    return int(np.sum(digits + 2.0 + (np.asarray(t, dtype=float) < 0)))


def corrections_budget(t: ArrayLike, window: float, slips_only: bool) -> None:
    """Refuse :func:`corrections` of the readings ``t`` beyond the work budget, naming ``t1 and window``.

    Each reading's slips and swaps are weighed by its printed characters (``_PRINTED_CHAR`` units each, fuzz 68b
    C3), its "other values" by the grid's size (``_CORRECTION`` units a value).
    """
    units = work((printed_characters(t),), "t1 and window", weight=_PRINTED_CHAR)
    if not slips_only:
        units += work((int(np.size(t)), grid_values(window)), "t1 and window", weight=_CORRECTION)
    work((units,), "t1 and window")


def joint_budget(readings: int, window: float, order_search: str) -> None:
    """Refuse :func:`joint_audit` beyond the work budget, naming ``window``."""
    work((_JOINT_FIXED[order_search] + readings * grid_values(window) * _JOINT_CORRECTION,), "window")
