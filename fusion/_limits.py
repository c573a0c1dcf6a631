"""The numeric range of the package's inputs (rule 2 of :mod:`fusion._validation`, which re-exports them)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from decimal import Decimal
from fractions import Fraction

import numpy as np

from fusion._frozen import constant


#: Largest magnitude accepted for a finite input entry: a product of two entries stays finite.
MAX_MAGNITUDE = 1e150
#: Smallest positive normal float.
MIN_NORMAL = float(np.finfo(float).tiny)
#: Smallest non-zero magnitude accepted for an input entry (``1e-150``, the mirror of
#: :data:`MAX_MAGNITUDE`): a product of two entries, a square or a variance, is still a normal float.
#: Subnormals and tiny normals below it (``3e-308``, ``1e-300``) are refused.
MIN_MAGNITUDE = 1e-150
#: Smallest non-zero variance on a covariance's diagonal: a product of two variances stays a normal float.
MIN_VARIANCE = float(np.sqrt(np.finfo(float).tiny))
#: Largest array argument, in elements (``2**25``, 256 MiB of float64: an eighth of the memory budget
#: ``MAX_ELEMENTS``, since a function's work makes several temporaries of its inputs' size). Checked by
#: ``fusion._validation.input_size`` on the argument's shape *before* any copy or conversion (rule 9): a
#: zero-stride view (``np.broadcast_to(0.5, (10**10,))``, 8 bytes) would convert to 80 GB, and a stack of
#: ``10**8`` rows would copy for seconds before its first check. The book's largest inputs hold ``8e6``.
MAX_INPUT_ELEMENTS = 2**25
#: Work budget of one call (rule 17 of :mod:`fusion._validation`): the product of the counts that set a
#: function's loops (runs x steps, problems x particles x iterations x dimension, ...), checked by :func:`work`
#: before any work. ``10**9`` units are at most about 10 CPU-s on one core of this machine: one unit is about
#: 10 ns, one element of a vectorised numpy operation (1 to 10 ns); a Python-level iteration of a loop costs
#: :data:`LOOP_STEP` units on top of its vectorised work (:func:`loop_work`, heavier steps weighted by a multiple
#: of it), and a counted element that costs more weighs its measured cost in units (``weight`` of :func:`work`;
#: chapter 07's table, ``fusion.scenarios._time_registration_work``, fuzz 30b D2), never hours. A particle swarm
#: of 33,000 iterations, its largest accepted, ran 6 s here with other jobs. A sequence argument whose
#: entries each run a loop body (seeds, sizes, grids of scales or periods) counts its length, or the sum of
#: its entries when each entry is a size. The book's requests stay well inside (chapter 02's 20,000 runs x
#: 100 samples x 4 sensors are 8e6 units; its belief study, 8 params x 803 loop steps, about 7e6).
MAX_WORK = 10**9
#: The one rule for a budget above :data:`MAX_WORK` (budget35): only a function whose OWN book call counts more than
#: ``MAX_WORK`` gets one, twice that call's count rounded up to a whole ``MAX_WORK``, kept here and named in the
#: refusal (:func:`work`'s ``limit``): the book's request, the key, is what the entry serves. The book's own calls are
#: a chapter's and those of the reseeding sweep (``make stability``, :mod:`fusion.book.stability`), whose results the
#: Verdicts page shows: each stochastic record's primary reading at the runs factor ``book/ledger/stability.json``
#: stores for it (fix46's test found 11 of them refused, so the stored file could not be re-derived). The largest call
#: of a function serves its entry. ``tests/test_budget35.py`` counts each served call against its entry, and
#: ``tests/test_stability_entries46.py`` runs every sweep task up to its first draw. Chapter 06's tracking study
#: (``range_bearing.monte_carlo`` of the default scenario, 30 frames) counts 4.26e9 units at the chapter's 100 runs
#: (about 45 CPU-s measured) and 1.28e10 at the sweep's 300 (its 8 records at 3x): 26 x ``MAX_WORK``, so a request of
#: hours is refused at once. A larger single ``MAX_WORK`` would loosen every other function's edge.
#: The key of chapter 06's tracking study in :data:`STUDY_WORK`.
TRACKING_STUDY = ("chapter 06's tracking study at the reseeding sweep's 3x runs (300 runs of the default range-bearing "
                  "scenario)")
#: The key of the lecture's AWF study (``lecture_weighting.estimators.awf_study``) in :data:`STUDY_WORK`.
AWF_STUDY = "the reseeding sweep's primary of lec-awf-estimated at 10x runs (awf_study, 3,000 runs)"
#: The key of the lecture's regime study (``lecture_weighting.regime.regime_study``) in :data:`STUDY_WORK`.
REGIME_STUDY = "the reseeding sweep's primary of lec-awf-adapts at 10x runs (regime_study, 1,000 runs)"
#: The key of the lecture's readings benchmark (``lecture_weighting.readings_benchmark.benchmark``).
READINGS_BENCHMARK = "the reseeding sweep's primary of lec-belief-accuracy at 10x runs (benchmark, 5,000 runs)"
#: The key of chapter 06's designed networks (``fusion.book.chapters.chernoff.premise.premise_studies``, the six
#: networks counted at its entry, fuzz 42b C5): 4.5e9 units at the sweep's 1,000 runs a network (about 46 CPU-s).
PREMISE_STUDY = ("the reseeding sweep's primaries of chf-premise-eps and chf-premise-mixture at 10x runs "
                 "(premise_study, 1,000 runs of each designed network)")
#: The key of the two-sensor architecture study (``two_sensor.architecture.architecture_study``): chapter 05's
#: identical pair at the reseeding sweep's 10x (ci-fig4-convex-part, 2,000 path and 2,000 NEES runs, 7 filter banks of
#: fixed weights) counts 1.08e9 units and ran 10.9 CPU-s (fuzz 42b D1); its entry, 3e9, equals the readings
#: benchmark's, so its refusal names it by ``work``'s ``served``.
ARCHITECTURE_STUDY = ("the reseeding sweep's primary of ci-fig4-convex-part at 10x runs (architecture_study, 2,000 runs "
                      "and 2,000 NEES runs)")
#: The key of chapter 05's two architecture studies (``fusion.book.chapters.ci.architecture.architecture_studies``,
#: which ``studies.arch_study`` runs: the identical pair with 7 filter banks and the anisotropic pair with 2, summed at
#: its entry, fuzz 57a C5: each was checked alone against :data:`ARCHITECTURE_STUDY`'s entry, so 6,738 runs were
#: accepted and ran 68.9 CPU-s): the reseeding sweep's 10x reading of ci-fig4-convex-part (2,000 runs and 2,000 NEES
#: runs of each pair) counts 1.97e9 units (the studies ran 10.9 and 9.0 CPU-s: fuzz 42b D1), 2.08e9 since fuzz 66b C1
#: (a bank's step of a path run counted, ``two_sensor.architecture._PATH_BANK``); by budget35's rule its entry is 5e9.
ARCHITECTURE_STUDIES = ("the reseeding sweep's primary of ci-fig4-convex-part at 10x runs (architecture_studies, both "
                        "pairs, 2,000 runs and 2,000 NEES runs)")
#: The key of chapter 05's infrared + radar readings (``fusion.book.chapters.ci.infrared_readings.ir_readings``: on
#: both azimuth axes every tracker reading's simulation or Cartesian tracks and their errors, the many-scan bounds and
#: the 26 Cartesian readings of the sigma_a levels and scan, summed at its entry, the audit after fuzz 57a: each was
#: checked alone as it came): the reseeding sweep's 10x reading of ci-fig10-x-below-y (2,000 runs of 101 scans)
#: counts 1.99e9 units (the chapter's 200 runs, 3.7e8, ran 2.9-3.1 CPU-s, 600 runs, 7.3e8, 4.9 CPU-s:
#: OPENBLAS_NUM_THREADS=1, the shared machine); by budget35's rule its entry is 4e9, named by ``work``'s ``served``.
IR_READINGS_STUDY = ("the reseeding sweep's primary of ci-fig10-x-below-y at 10x runs (ir_readings, 2,000 runs of "
                     "101 scans)")
#: The key of chapter 05's stochastic records' evidence (``fusion.book.chapters.ci.studies.record_evidence``: the
#: studies a record reads, each summed by its own budget, summed again at its entry, the audit after fuzz 57a: they
#: were checked one by one, so a run count the paired study refuses first ran both architecture studies): the
#: reseeding sweep's 10x reading of ci-fig4-convex-part (2,000 runs: both architecture studies, the paired study and
#: Fig. 6's periods) counts 3.17e9 units; by budget35's rule its entry is 7e9, which equals the AWF study's, so its
#: refusal names it by ``work``'s ``served``.
RECORD_EVIDENCE = ("the reseeding sweep's primary of ci-fig4-convex-part at 10x runs (record_evidence: "
                   "arch_study, paired_study and fig6_periods, 2,000 runs)")
#: The key of chapter 01's membership study (``fusion.book.chapters.ofs.studies.membership_study``: two scale sweeps,
#: three membership families and the equal-weight ablation on the same draws, counted together at its entry, fuzz 54a
#: C2): 1.47e9 units at the sweep's 5,000 runs (ran 22.1 CPU-s, niced on the shared machine).
MEMBERSHIP_STUDY = ("the reseeding sweep's primaries of yang-membership-free and yang-weights-reasonable at 10x runs "
                    "(membership_study, 5,000 runs)")
#: The key of chapter 05's ledger studies (``fusion.book.chapters.ci.studies.ledger_studies``: the architecture, paired,
#: Fig. 6 period and infrared studies at one run count, summed at its entry, fuzz 55 C4): 1.18e9 units at the
#: notebook's 200 runs (16.6 CPU-s of studies after a 1.5-2.2 CPU-s import, a fresh process and study cache,
#: OPENBLAS_NUM_THREADS=1, nothing else running); by budget35's rule its entry is 3e9, whose edge, 1,840 runs (3.0e9
#: units), ran 42.8 CPU-s of studies there (fuzz 56 C3): the rule's factor of two over a book call that is itself
#: 1.2 x MAX_WORK, kept as for every entry. The audit after fuzz 57a counted its infrared readings by what
#: ``ir_readings`` runs (``infrared_readings._readings_parts``: 3.7e8 units at 200 runs, which ran 2.9-3.1 CPU-s; they
#: had been counted 2.2e6), so the notebook's call counts 1.55e9 and the entry, by the same rule, is 4e9 (its edge
#: 1,424 runs). It equals the regime study's, so its refusal names it by ``work``'s ``served``.
LEDGER_STUDIES = ("chapter 05's notebook call of ledger_studies (arch, paired, Fig. 6 period and infrared studies, "
                  "200 runs)")
#: The key of chapter 06's appendix study of the sigma-point first-order mixture
#: (``fusion.book.chapters.chernoff_first_order.sigma_first_order_study``, the appendix notebook's 100 random problems
#: on a 401 x 401 grid and the two-mixture example on 601 x 601): 2.47e9 units (about 12.4 CPU-s measured, 120 ms a
#: problem, weighed twice; book audit 76: it had no budget, 10**7 problems were accepted); by budget35's rule its
#: entry is 5e9 (its edge about 205 problems), which equals chapter 05's two architecture studies', so its refusal
#: names it by ``work``'s ``served``.
SIGMA_FIRST_ORDER_STUDY = ("chapter 06's appendix call of sigma_first_order_study (100 random problems and the "
                           "two-mixture example)")
STUDY_WORK: Mapping[str, int] = constant({TRACKING_STUDY: 26 * MAX_WORK, AWF_STUDY: 7 * MAX_WORK,
                                          REGIME_STUDY: 4 * MAX_WORK, READINGS_BENCHMARK: 3 * MAX_WORK,
                                          PREMISE_STUDY: 9 * MAX_WORK, ARCHITECTURE_STUDY: 3 * MAX_WORK,
                                          MEMBERSHIP_STUDY: 3 * MAX_WORK, LEDGER_STUDIES: 4 * MAX_WORK,
                                          ARCHITECTURE_STUDIES: 5 * MAX_WORK, IR_READINGS_STUDY: 4 * MAX_WORK,
                                          RECORD_EVIDENCE: 7 * MAX_WORK,
                                          SIGMA_FIRST_ORDER_STUDY: 5 * MAX_WORK})
#: Units of one Python-level iteration of a loop of a few numpy calls (their interpreter and call overhead, a
#: few to ~30 us on this machine when loaded, ~10**3 to 10**4 vectorised elements): :func:`loop_work` adds it
#: to each step's vectorised work, a multiple of it for heavier steps (a particle swarm's iteration).
LOOP_STEP = 10**3
#: Two numbers are tied, equal up to round-off, when they differ by at most ``ROUND_OFF_TIE`` times the larger
#: magnitude: the one tie rule of the rulebook (R2, ``fusion.book.rulebook``) and of the benchmark's ranks of methods
#: (``fusion.scenarios.lecture_weighting.readings_benchmark.seed_stability``).
ROUND_OFF_TIE = 1e-9


#: Relative tolerance of a parameter the caller gives against the one a study records (the swaps checks: the noise
#: SDs, the sampling period of a study passed with its settings): the same value computed another way is off by
#: round-off (``np.arange(3, 13) / 6`` is 1 ulp off the chapter's SDs; fuzz 31b D1), a swapped one by far more.
RECORDED_RTOL = 1e-12


def recorded_as(given: object, recorded: object) -> bool:
    """Whether ``given`` is the value ``recorded`` to :data:`RECORDED_RTOL` (an array broadcast to ``recorded``'s
    shape, a scalar for every entry; False for shapes that do not broadcast): the one rule of the swaps checks."""
    r = np.asarray(recorded, dtype=float)
    try:
        g = np.broadcast_to(np.asarray(given, dtype=float), r.shape)
    except ValueError:
        return False
    return bool(np.allclose(g, r, rtol=RECORDED_RTOL, atol=0.0))


def count_text(n: int) -> str:
    """``n`` to three significant digits (``1.01e+09``), also beyond a float's range (``1e+400``), where formatting
    the integer as a float raises OverflowError."""
    if n < 10**300:
        return f"{n:.3g}"
    return f"{int(str(n)[:3]) / 100:.3g}e+{len(str(n)) - 1}"


def work(shape: tuple[int, ...], names: str, weight: float = 1, limit: int = MAX_WORK,
         served: str | None = None) -> int:
    """Refuse a call whose work, ``weight`` times the product of the counts in ``shape``, is beyond :data:`MAX_WORK`
    (rule 17).

    The style of :func:`fusion._validation.allocation` for memory: a function whose loops grow as a product of
    counts calls this at its entry, once its counts are validated, so that a valid but huge request is refused
    by name at once rather than running for more than about 10 CPU-s (minutes or hours).

    Parameters
    ----------
    shape : tuple of int
        The counts whose product is the number of units of work (each at least 1).
    names : str
        The arguments setting them (``"runs, k and sigma"``), named in the message.
    weight : int or float
        The units of one counted element: its measured CPU time over the unit's (about 10 ns, :data:`MAX_WORK`),
        rounded up; 1 for a vectorised element; a fraction of a unit for an element cheaper than 10 ns (a
        ``d**3`` term of a dense factorisation, :func:`dense_work`).
    limit : int
        The budget (:data:`MAX_WORK`; a larger one only from :data:`STUDY_WORK`, where the book's own call counts
        more, as the tracking study of ``fusion.scenarios.range_bearing``, named in the message).
    served : str, optional
        The key of :data:`STUDY_WORK` whose entry ``limit`` is, named in the message (by default the first key whose
        entry equals ``limit``: two entries may be equal).

    Returns
    -------
    int
        The units of work, ``weight`` times the product (rounded up).

    Raises
    ------
    ValueError
        If the product is beyond :data:`MAX_WORK`, naming ``names`` and the budget.
    """
    n = 1
    for s in shape:
        n *= int(s)
    # exact integers (fuzz 38a: a product beyond 1.8e308 raised OverflowError as a float)
    n = n * int(weight) if float(weight).is_integer() else math.ceil(n * Fraction(float(weight)))
    if n > limit:
        dims = " x ".join(f"{int(d):,}" for d in shape) + (
            "" if weight == 1 else f", {int(weight):,} units each" if float(weight).is_integer()
            else f", {float(weight):.3g} units each")
        served = [served] if served else [k for k, v in STUDY_WORK.items() if v == limit]
        budget = ("fusion._validation.MAX_WORK, about 10 CPU-s" if limit == MAX_WORK
                  else f"about {limit / MAX_WORK * 10:.0f} CPU-s"
                  + (f", fusion._limits.STUDY_WORK: {served[0]}" if served else ""))
        raise ValueError(f"{names} ask for {count_text(n)} units of work ({dims}), beyond the work budget "
                         f"(at most {limit:.0e}, {budget})")
    return n


def loop_work(steps: tuple[int, ...], per_step: int, names: str, step: int = LOOP_STEP, limit: int = MAX_WORK) -> int:
    """Refuse a Python-level loop of ``prod(steps)`` iterations of ``per_step`` vectorised units each (rule 17).

    The work of a loop is ``prod(steps) x (LOOP_STEP + per_step)`` units (:data:`LOOP_STEP`): a loop over the
    entries of a sequence argument (10**6 seeds of one run each) is refused by its length even when each
    entry's vectorised work is small, as :func:`work` refuses a product of counts.

    Parameters
    ----------
    steps : tuple of int
        The counts of the loop's iterations (``(len(seeds), len(levels))``), each at least 0.
    per_step : int
        The vectorised units of one iteration (``runs * samples * n``).
    names : str
        The arguments setting them (``"seeds, runs and samples"``), named first in the message.
    step : int
        The units of one iteration's overhead: :data:`LOOP_STEP` for a step of a few numpy calls, a
        multiple of it for a heavier step (a particle swarm's iteration, some thirty numpy calls, weighs
        ``30 * LOOP_STEP``), so that a unit costs about the same time in every function.
    limit : int
        The budget, as :func:`work`'s.

    Returns
    -------
    int
        The units of work.

    Raises
    ------
    ValueError
        If the work is beyond :data:`MAX_WORK`, naming ``names``.
    """
    return work(tuple(steps) + (int(step) + int(per_step),), names, limit=limit)


#: The step of :func:`dense_work`'s weights, 0.01 units (0.1 ns) a ``d**3``: dense ``d x d`` linear algebra on one
#: core (LAPACK inverses, Cholesky factors, determinants, matrix products) measured 0.1 to 1.2 ns a ``d**3`` per
#: matrix over a whole call, so a function's weight is 1.5 to 12 of it (fuzz 36a C3).
DENSE_CUBE = 0.01


def dense_work(count: int, d: int, names: str, weight: float) -> int:
    """Refuse a call whose dense linear algebra on ``count`` matrices of ``d x d`` is beyond :data:`MAX_WORK`
    (rule 17; fuzz 36a C3).

    The dimension of a caller's covariance costs ``d**3`` per inverse, factorisation or product, which no count
    argument holds: within the input budget a stack of two covariances has ``d = 4,096`` (a Chernoff weight search
    there ran about 100 CPU-s). A function doing such work weighs ``count x d**3`` by ``weight`` units, its
    measured CPU time per ``d**3`` per matrix (a multiple of :data:`DENSE_CUBE`, from its whole call at
    ``d = 250`` to ``750``), so that its accepted edge costs about 10 CPU-s; it calls this before its covariances'
    own ``O(d**3)`` checks where the dimension is known before them.

    Parameters
    ----------
    count : int
        The number of ``d x d`` matrices (or of weights a search evaluates, each one inverse).
    d : int
        Their dimension.
    names : str
        The arguments setting them, named in the message.
    weight : float
        The measured units of one matrix's ``d**3``.

    Returns
    -------
    int
        ``weight x count x d**3``, rounded up.

    Raises
    ------
    ValueError
        Beyond :data:`MAX_WORK`: :func:`work`'s message, naming ``names``, the count, ``d`` three times and the weight.
    """
    return work((count, d, d, d), names, weight=weight)


#: Relative round-off of a float64 computation of a decimal (``0.1 * 3``, ``12.3 / 100``: within one or two ulps of
#: it), the float64 part of :func:`written_as`.
F64_ROUND_OFF = 4 * float(np.finfo(np.float64).eps)


def written_as(p: float, q: float) -> bool:
    """Whether ``p`` is the number ``q`` up to the binary round-off of writing it down: ``q`` itself, within a few
    float64 ulps of it (``0.1 * 3`` for 0.3), or the float32 nearest it (``np.float32(0.3)``, a table read as float32).

    The one rule of the package for "the value given is that decimal" (``PublishedValues``' printed decimals,
    fuzz 24e F1 / 26a D1; a shift of ``table_shift_weight``'s grid, fuzz 26d DB7): bound by the value's own
    precision, never a fixed relative share of it.

    Parameters
    ----------
    p : float
        The value given.
    q : float
        The number it should be.

    Returns
    -------
    bool
        True when ``p`` is ``q`` as written down.
    """
    return bool(p == q or abs(q - p) <= F64_ROUND_OFF * abs(p) or p == float(np.float32(q)))



def _entries(values: object) -> list[object]:
    """The numbers of ``values`` in flat (C) order, as the caller gave them: the entries of a (nested) list or tuple
    before any conversion (a list mixing ints and floats converts to float64, rounding the ints), an array's
    ``tolist()`` (object arrays: their objects)."""
    if not isinstance(values, (list, tuple)):
        a = np.asarray(values)
        return [] if a.dtype.kind not in "iuO" or (a.dtype.kind in "iu" and a.dtype.itemsize < 8) else a.ravel().tolist()
    out: list[object] = []
    stack = [iter(values)]
    while stack:  # iterative, in order: a deeply nested list is read without recursion
        for v in stack[-1]:
            if isinstance(v, (list, tuple)):
                stack.append(iter(v))
                break
            out.extend(_entries(v) if isinstance(v, np.ndarray) else [v])
        else:
            stack.pop()
    return out


def _object_entries(values: object) -> object:
    """An object array's (or Series') entries as a list, as the caller gave them (fuzz 35a C4: its numbers have their
    own dtypes, as in a list); anything else as it is."""
    dtype = getattr(values, "dtype", None)
    if isinstance(dtype, np.dtype) and dtype.kind == "O":
        try:
            return np.asarray(values, dtype=object).ravel().tolist()
        except (TypeError, ValueError):
            return values
    return values


def integer_entries(values: object, n: int) -> list[bool]:
    """Per entry of the ``n`` numbers ``values``, whether it was given as an integer (a Python or numpy int, not a bool):
    an exact number even where its list's array is float64 (``[0.5, 2**53]``); an object array is read as a list."""
    values = _object_entries(values)
    if not isinstance(values, (list, tuple)):
        return [np.asarray(values).dtype.kind in "iu"] * n
    given = _entries(values)
    if len(given) != n:
        return [False] * n
    return [isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_)) for v in given]


def entry_dtypes(values: object, n: int) -> list[np.dtype]:
    """Per entry of the ``n`` numbers ``values``, the dtype whose precision it has: a numpy scalar's own (an
    ``np.float16`` beside Python numbers is a float16 number, fuzz 31a C1), an array entry's, float64 for a Python
    number; an array's dtype for every entry of an array. ``fusion._validation.given_dtype`` is the same rule for a
    whole list (its least precise entry). An object array is read as a list."""
    values = _object_entries(values)
    if not isinstance(values, (list, tuple)):
        return [np.asarray(values).dtype] * n
    out: list[np.dtype] = []
    stack = [iter(values)]
    while stack:  # iterative, in order, as _entries
        for v in stack[-1]:
            if isinstance(v, (list, tuple)):
                stack.append(iter(v))
                break
            if isinstance(v, (np.generic, np.ndarray)):
                out.extend([v.dtype] * int(np.size(v)))
            else:
                out.append(np.dtype(np.float64))
        else:
            stack.pop()
    return out if len(out) == n else [np.asarray(values).dtype] * n


def _inexact(v: object) -> bool:
    """Whether ``v`` is an integer (a Python or numpy int, an integral Decimal or Fraction) that float64 does not
    hold exactly."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, np.integer, Decimal, Fraction)):
        return False
    if isinstance(v, Decimal) and not v.is_finite():
        return False
    iv = int(v)  # a Python int: compared with its float exactly (an np.int64 would compare as a float64)
    try:
        return iv == v and float(iv) != iv
    except OverflowError:
        return True


def inexact_integer(values: object) -> int | None:
    """The index of the first integer of ``values`` that float64 cannot hold exactly, or None.

    The integers' counterpart of "a value its dtype cannot hold" (``PublishedValues``' float32/float16 rule, fuzz 27a
    F5): an integer beyond 2**53 in magnitude that is not a multiple of a large enough power of two (``2**53 + 1``)
    becomes another number as a float64, so a comparison at printed decimals (R1) would compare another number
    (9007199254740993 as ...992, fuzz 29a C6). Every integer up to 2**53 in magnitude is held. Each entry is
    checked as given, before any conversion: an integer beside a float in a list (whose array is float64, the
    integer already rounded), a numpy int scalar, an integral ``Decimal`` or ``Fraction`` (fuzz 30a C1).

    Parameters
    ----------
    values : array_like
        Numbers: an array, or a (nested) sequence of numbers (entries that are not integers are skipped).

    Returns
    -------
    int or None
        The flat index of the first integer whose float64 conversion is another number (or overflows).
    """
    for i, v in enumerate(_entries(values)):
        if _inexact(v):
            return i
    return None
