"""Chapter 07's work budget (rule 17 of ``fusion._validation``): the one rule of every function of the chapter whose
cost grows with a length the caller gives (times, instants, runs, a list of levels, latencies or periods).

Each counted element weighs its measured cost in units of about 10 ns (:data:`fusion._limits.MAX_WORK`: ``10**9``
units are at most about 10 CPU-s on one core). Measured with ``time.process_time`` and ``OPENBLAS_NUM_THREADS=1``
at a few sizes each (fuzz 30b D2: ``transient_table(1100, 1)`` was accepted and ran some 35 CPU-s):

* a registration (a call of ``register``, ~100 us): ``10 * LOOP_STEP``;
* a Kalman method's filter, in a registration or a Monte Carlo: the filter's own rule, counted by it
  (``fusion.registration.methods._kalman_work``: per grid step ``3 * LOOP_STEP``, ``4 * LOOP_STEP`` with the
  smoother's pass, plus 15 units a run, 25 smoothed), over its grid (the samples, and every instant unless the call
  passes no ``kf``) and once per pass the call runs (:func:`_filter_work`), plus :data:`KALMAN_INSTANT` an instant
  of a registration, so that the filter's inner refusal, naming its ``t and Z``, never comes
  before the caller's (fix60a: the chapter's own ``2 * LOOP_STEP`` a step and 10 units a run of the smoother counted
  less than the inner rule, so a Monte Carlo of the smoother alone from about 2.0 million runs was refused inside);
* a least-squares fit per instant: its own inner budget (``10 * LOOP_STEP + 4 * n_src``,
  ``fusion.registration.methods.least_squares``), which counts it above its cost (1 to 1.4 ns per unit);
* a vectorised method's registration: ``n_src + n_dst``, times its :data:`REGISTRATION_WEIGHT` (the cubic spline
  solves for the whole record: 42-50 ns per unit in its weight matrix at 6,000-22,664 samples, fuzz 33a C9);
* a Monte-Carlo run over one sample or instant: :data:`RUN_WEIGHT` by method (a fixed-weight method 9-10 ns, a
  Kalman method's registration from the filtered states 10-18 ns), 1 for runs through each method's weight matrix;
  the filter's passes over all runs at once by the filter's own rule (:func:`_filter_work`);
* a run of ``fusion_runs`` through a method (one registration of the run's samples on the scenario's times, in
  Python): :data:`FUSION_RUN_WEIGHT` by method (fuzz 39a C4: its runs were not counted).

Private: the functions are re-exported by ``fusion.scenarios.time_registration``, where the chapter calls them.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping, Sequence

from fusion._limits import LOOP_STEP, work
from fusion.registration.methods import _kalman_work

#: Units of one Monte-Carlo run of a method over one sample or instant, by method; a method not listed weighs 1
#: (a fixed-weight method, 9-10 ns measured). A Kalman method's registration from the filtered states of every run
#: (the filter's passes, shared by the methods, are counted by the filter's own rule, :func:`_filter_work`):
#: ``monte_carlo`` of one Kalman method less ``kalman_runs`` of its pass measured 10-18 ns a run and sample or
#: instant (100,000 runs of the scenario's 20 samples and 8 instants, ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared with other jobs; fix60a), 2 units.
#: Keyed by the methods' values (``RegMethod`` is defined in the scenario's module, which imports this one).
RUN_WEIGHT: dict[str, int] = {"reg_kalman_predict": 2, "reg_kalman_two_point": 2, "reg_improved": 2,
                              "reg_causal_improved": 2, "reg_rts_smoother": 2, "reg_fixed_lag": 2}

#: Units of one vectorised registration per sample and instant (``n_src + n_dst``), by method; a method not listed
#: weighs 1 (9-22 ns measured in a weight matrix). The cubic spline solves for the whole record each time: 42 ns
#: at 6,000 and 12,000 samples, 34-50 ns at 22,664 (fuzz 33a C9: its largest accepted Monte Carlo ran 27-46 CPU-s).
REGISTRATION_WEIGHT: dict[str, int] = {"reg_cubic_spline": 5}
#: Units of one multiply-add of the runs through a weight matrix (``z @ W.T``: ``runs x n_src x n_dst`` a method that
#: applies one, a fixed-weight method or a Kalman method registering from its filtered states): 0.037-0.038 ns
#: measured (2,000-4,000 runs on 1,000-6,000 samples and instants, a strided ``xs[:, :, 0]`` too,
#: ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared; fix71a: uncounted, a
#: Monte Carlo of ``reg_two_point`` on 8,000 samples and instants at 16,000 runs ran 51-55 CPU-s), counted as 0.1 ns
#: (the runs' own ``n_src + n_dst`` term counts the small products, 0.4-1.1 ns a multiply-add at 20 x 8).
PRODUCT_WEIGHT = 0.01
#: Units of one instant of a Kalman method's registration from its filtered states (prediction or interpolation onto
#: the instants, vectorised; the filter's own steps are counted by its rule): ``register`` measured 23-57 ns an
#: instant (100,000 and 1,000,000 instants on the scenario's 20 samples, ``time.process_time``,
#: ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared; fix60a).
KALMAN_INSTANT = 6


#: Units of one run of ``fusion_runs`` through one method, by method, on the scenario's 20 samples and 8 instants
#: (the only times it registers): each run is registered by a Python call (``register``, or the Kalman methods'
#: registration of that run's filtered states), so a run weighs its measured time, not a vectorised element.
#: Measured with ``time.process_time`` and ``OPENBLAS_NUM_THREADS=1`` as the slope of 2 to 3,002 runs of one method
#: (the machine shared with other jobs, the least of two): the Kalman methods 43-69 us (``5 * LOOP_STEP``: 200,000
#: runs, the edge, 8.6-14 CPU-s), the other fixed-weight methods 75-100 us (``10 * LOOP_STEP``, a registration), the
#: methods fitting each instant (``_PER_INSTANT``) 245-317 us and the cubic spline 225 us (``30 * LOOP_STEP``: 33,333
#: runs, 7.5-10.6 CPU-s). A method not listed weighs ``10 * LOOP_STEP``.
FUSION_RUN_WEIGHT: dict[str, int] = {
    **{n: 5 * LOOP_STEP for n in ("reg_kalman_predict", "reg_kalman_two_point", "reg_improved", "reg_causal_improved",
                                  "reg_rts_smoother", "reg_fixed_lag")},
    **{n: 30 * LOOP_STEP for n in ("reg_least_squares", "reg_qls_next", "reg_qls_causal", "reg_local_qls",
                                   "reg_cubic_spline")}}


#: Units of one entry of ``monte_carlo``'s ``names`` beyond its runs (its check, its registration call and its MSE
#: over all runs, in Python): a Kalman method on its filtered states, whose filter pass is shared by the methods and
#: whose runs weigh 2 units a run and sample, measured 22-25 us a name (1,000 and 5,000 repeats of
#: ``reg_kalman_predict``, 2 runs, ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine
#: shared; fix70a: uncounted, so about 8.9 million names of 2 runs, some 200 CPU-s, were within the budget), counted
#: as ``3 * LOOP_STEP``. Also the bound by ``len(names)`` alone that ``monte_carlo`` checks before any entry is read.
MC_NAME_UNITS = 3 * LOOP_STEP


def _filter_work(names: Sequence[str], runs: int, steps: int, what: str) -> int:
    """The units of the Kalman filter's passes a call of ``names`` runs over ``runs`` runs and ``steps`` grid steps
    (every sample and instant: the filter's largest grid, with ``period_change``), each counted by the filter's own
    rule, ``fusion.registration.methods._kalman_work`` (the same weights, not a copy of them): one filtered pass for
    the Kalman methods on filtered states, one smoothed for ``reg_rts_smoother``, one lag-one for ``reg_fixed_lag``,
    as the scenario's ``_filtered`` runs them. A pass beyond the budget is refused naming the caller's ``what``; so
    a caller counting these units counts at least what each of its ``kalman_runs`` calls counts (fix60a)."""
    from fusion.scenarios import time_registration as sc

    passes = {sc._STATES.get(n, "filtered") for n in names if n in sc._KALMAN}
    return sum(_kalman_work(int(steps), int(runs), p != "filtered", what) for p in sorted(passes))


def _fusion_runs_work(names: Sequence[str], runs: int, n_src: int, n_dst: int, what: str, times: str) -> int:
    """Refuse (rule 17) a ``fusion_runs`` of ``runs`` runs of ``names`` before any draw, naming ``what`` (its runs
    and methods, each run of a method weighing :data:`FUSION_RUN_WEIGHT`) or ``times`` (each method's weight matrix,
    ``n_src + 1`` registrations on ``n_src`` samples and ``n_dst`` instants, :func:`_registration_work`), the rule of
    ``monte_carlo``'s :func:`_monte_carlo_work` (fuzz 39a C4); return the units of the runs."""
    _registration_work(names, n_src, n_dst, n_src + 1, times, period_change=False)
    runs_units = work((int(runs), sum(FUSION_RUN_WEIGHT.get(n, 10 * LOOP_STEP) for n in names)), what)
    # and the filter's passes over all runs at once (its grid the samples: no kf), by the filter's own rule (fix60a)
    return work((runs_units + _filter_work(names, runs, n_src, what),), what)


def _registration_work(names: Sequence[str], n_src: int, n_dst: int, calls: int, what: str, *,
                       period_change: bool = True) -> int:
    """Refuse (rule 17, :func:`fusion._limits.work`), naming the caller's ``what``, ``calls`` registrations of
    ``n_dst`` instants onto ``n_src`` samples by each method of ``names``, before any work; return the units.

    The one work rule of chapter 07's functions whose cost grows with a length the caller gives (times, instants, a
    list of levels or periods; fuzz 28b C4-C7, D3). A registration weighs ``10 * LOOP_STEP`` (a call of
    ``register``, ~100 us here), plus per instant least squares' own step (``10 * LOOP_STEP + 4 * n_src``,
    :func:`fusion.registration.methods.least_squares`) for a method that fits each instant (``_PER_INSTANT``),
    for a Kalman method the filter's own rule over its grid (:func:`_filter_work`, one run: at least what
    ``register``'s filter counts, fix60a), the samples and, unless the caller passes no ``kf`` (``period_change``
    False), every instant, plus :data:`KALMAN_INSTANT` an instant; ``n_src + n_dst`` times its
    :data:`REGISTRATION_WEIGHT` for a vectorised one: at least each inner budget of the call, so that an inner
    name is never the refusal's (about 10 ns per unit or less, the module's table).
    """
    from fusion.scenarios import time_registration as sc

    one = sum(10 * LOOP_STEP + (n_dst * (10 * LOOP_STEP + 4 * n_src) if n in sc._PER_INSTANT else
                                _filter_work([n], 1, n_src + (n_dst if period_change else 0), what)
                                + n_dst * KALMAN_INSTANT if n in sc._KALMAN else
                                (n_src + n_dst) * REGISTRATION_WEIGHT.get(n, 1)) for n in names)
    return work((int(calls), int(one)), what)


def _exact_work(names: Sequence[str], n_dsts: Sequence[int] | Mapping[int, int], what: str,
                period_change: bool = True) -> int:
    """Refuse (rule 17), naming ``what``, the exact MSEs (``expected``: ``n1 + 1`` registrations on the scenario's
    ``n1`` samples) of every method of ``names`` at each count of instants of ``n_dsts``, their sum, before any work
    (a sweep of levels, latencies or periods; fuzz 28b C7, D3); ``period_change`` False for a sweep whose exact MSEs
    pass no ``kf`` (the filter's grid is then the samples alone, :func:`_registration_work`). ``n_dsts`` is the
    counts of instants, one per sweep point, or a mapping of a count to its number of sweep points (in closed
    form: fuzz 60a C3, ``delay_table`` built a list of ``len(delays) * len(sigmas)`` counts before this rule
    refused it, 15.4 CPU-s at 20,000 x 20,000, a raw MemoryError at 100,000 x 100,000)."""
    from fusion.scenarios import time_registration as sc

    n1 = sc.instants()[0].size
    counts = n_dsts if isinstance(n_dsts, Mapping) else Counter(n_dsts)
    return work((sum(_registration_work(names, n1, n, (n1 + 1) * c, what, period_change=period_change)
                     for n, c in counts.items()),), what)


def _monte_carlo_work(names: Sequence[str], runs: int, n_src: int, n_dst: int, what: str, times: str, *,
                      filtered: bool = True, repeat: int = 1, name_units: int = 0) -> None:
    """Refuse (rule 17) a ``monte_carlo`` of ``runs`` runs of ``names`` on ``n_src`` samples and ``n_dst``
    instants before any draw, naming ``what`` (its runs) or ``times`` (its weight matrices and filter passes).

    A run of one method over one sample or instant weighs the method's :data:`RUN_WEIGHT` (1 each when not
    ``filtered``: the runs go through each method's weight matrix, as Fig. 4's levels). A fixed-weight method's
    weight matrix is ``n_src`` registrations (:func:`_registration_work`; fuzz 28b C4: ``t_dst`` was not counted
    and 20,000 instants ran unbounded), as is a filtered Kalman method's fixed-weight base; the runs through each of
    those matrices are ``runs x n_src x n_dst`` multiply-adds of :data:`PRODUCT_WEIGHT` (named ``what``). The filter's passes, all
    runs at once over the samples and instants, count by the filter's own rule (:func:`_filter_work`): their steps
    alone with the weight matrices (named ``times``), their steps and runs with the runs (named ``what``), so that
    ``what`` counts at least each ``kalman_runs`` call's own budget and is refused first (fix60a: the smoother's runs
    weighed 10 units here, 25 there, and a Monte Carlo of it alone from about 2.0 million runs was refused inside,
    naming ``t and Z``). ``name_units``: units of each entry of ``names`` beyond its runs, with the weight matrices
    (``monte_carlo``'s ``MC_NAME_UNITS``; 0 for a caller whose loop is counted otherwise).

    ``repeat`` counts ``names`` as that many ``monte_carlo`` calls of them (a sweep of levels or readings, each
    point a call), in closed form: the units of a list of ``repeat`` copies of ``names``, weight matrices and runs,
    and the filter's passes of each call, without building that list (fix69g: ``fig4_compatibility`` built a list
    of two methods a level before this rule, 10**7 levels still running at 100 s wall).
    """
    from fusion.scenarios import time_registration as sc

    repeat = int(repeat)
    weight = sum(RUN_WEIGHT.get(n, 1) for n in names) if filtered else len(names)
    kalman = [n for n in names if filtered and n in sc._KALMAN]
    matrices = [n for n in names if n not in kalman] + [sc._ON_STATES[n] for n in kalman if sc._ON_STATES[n]]
    work((_registration_work(matrices, n_src, n_dst, n_src * repeat, times)
          + repeat * _filter_work(kalman, 0, n_src + n_dst, times) + repeat * len(names) * int(name_units),), times)
    runs_units = work((int(runs), n_src + n_dst, weight, repeat), what)
    if matrices:   # the runs through each weight matrix, runs x n_src x n_dst multiply-adds (fix71a)
        runs_units += work((int(runs), n_src, n_dst, len(matrices), repeat), what, weight=PRODUCT_WEIGHT)
    work((runs_units + repeat * _filter_work(kalman, runs, n_src + n_dst, what),), what)
