r"""Chapter 04's appendix: sequential fusion, the James-Stein risk and the shrunken vector estimate.
"""

from __future__ import annotations

from fusion._validation import instance_of
from fusion._shown import shown


import math

import numpy as np
import pandas as pd

from fusion._counts import seed as check_seed
from fusion.book.chapters.lecture import _frame, _holds
from fusion.book.tables import roundoff
from fusion.readings import biased as rg
from fusion.readings import correlated as co
from fusion.book.chapters.lecture_correlated.records import SEED
from fusion.book.style import METHOD_SHORT_LABELS
from fusion.scenarios.ridge_sensors import LS, VectorStudy
from fusion.book.glue import GlueValues
from fusion.book.rulebook import MIN_RUNS
from fusion._counts import COUNT_CEILINGS, allocation, count, counts, distinct, input_allocation, sequence
from fusion._limits import LOOP_STEP, work
from fusion._validation import as_array, derived, scalar, std_scalar

#: Most readings (sensors x readings per sensor) of :func:`table_sequential`: its n x n covariance is factored.
MAX_SEQUENTIAL_READINGS = 2000
#: Largest ``ratio`` of :func:`james_stein_risk`: its Poisson sum has about ratio**2 / 2 terms.
MAX_JS_RATIO = 1000.0

__all__ = [
    "table_sequential", "glue_sequential", "james_stein_risk", "table_james_stein", "glue_james_stein",
    "table_shrunken", "glue_shrunken",
]

#: Column headers that a table of this module builds and its glue reads (issue 36: named once): the sequential
#: fusion's table, the James-Stein table's Monte-Carlo risk, and the shrunken estimators' best scaled LS and ridge.
M_LARGEST = "largest |M| on later readings"
FULL_M = "with a full M"
VS_BATCH = "vs batch GLS of sensors 1..i"
MONTE_CARLO = "Monte Carlo"
BEST_SCALED_LS = "best c·LS"
BEST_RIDGE = "best ridge"


# The work of table_sequential (book audit 76: 2,000 sensors of one reading were accepted, about 130-250 CPU-s;
# time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, shared 2-core machine): the whole R's factors 0.3 ns an
# n**3 (2 sensors of 1,000 readings: 4.1 CPU-s), and the loop over the sensors 2 ms a step plus 0.18 ns a k**3 of
# its k x k batch GLS (500 sensors of one reading: 4.0 CPU-s; 250: 0.68): 0.06 units an n**3, 400 * LOOP_STEP a
# sensor and 0.04 units a k**3.
_SEQ_CUBE, _SEQ_STEP, _SEQ_GLS_CUBE = 0.06, 400 * LOOP_STEP, 0.04


def _sequential_readings(sensors: int | None, m: int) -> None:
    """Refuse ``sensors`` x ``m`` readings beyond :data:`MAX_SEQUENTIAL_READINGS` or the work budget (no check when
    ``sensors`` is None: not yet known)."""
    if sensors is None:
        return
    if sensors * m > MAX_SEQUENTIAL_READINGS:
        raise ValueError(f"sigma and m give {sensors} x {m} = {sensors * m} readings, beyond "
                         f"{MAX_SEQUENTIAL_READINGS} (their covariance is factored)")
    gls = sum((i * m) ** 3 for i in range(1, sensors + 1))
    work((math.ceil(_SEQ_CUBE * (sensors * m) ** 3 + _SEQ_GLS_CUBE * gls) + sensors * _SEQ_STEP,), "sigma and m")


def table_sequential(sigma: tuple[float, ...] = (1.0, 2.0, 3.0), sigma_env: float = 1.5, m: int = 4,
                     seed: int = SEED) -> pd.DataFrame:
    r"""The block structure of :math:`M = L^{-1}` and its sensor-by-sensor use (§2.7), on a small example.

    N sensors (SDs ``sigma``) each read a scalar x = 1 ``m`` times with a common environment
    (:math:`R = \mathrm{diag}(\sigma_i^2) \otimes I_m + \sigma_e^2\mathbf{1}\mathbf{1}^\top`, the lecture's motivation),
    sensor after sensor. From the factors of the *whole* R, sensor i's pseudo-measurements (its rows of M) and the
    fused estimate after it are formed; the estimate is compared with the batch GLS of sensors 1..i alone.

    Parameters
    ----------
    sigma : tuple of float
        Own noise SD of each sensor (> 0).
    sigma_env : float
        SD of the common environment term.
    m : int
        Readings per sensor.
    seed : int
        Seed of the one draw of the readings.

    Returns
    -------
    pandas.DataFrame
        One row per sensor i: ``readings used`` (its pseudo-measurements use readings 1..k), ``largest |M| on later
        readings`` (its rows of M beyond column k: 0 for a lower-triangular M), ``multiplications`` (off-diagonal
        entries of its rows of M: the products that form its pseudo-measurements), ``with a full M`` (the same
        count if M had no zeros), ``estimate after sensor i`` (4 decimals), ``vs batch GLS of sensors 1..i``
        (relative difference, :func:`fusion.book.tables.roundoff`).

    Raises
    ------
    TypeError
        An argument of the wrong type.
    ValueError
        ``sigma`` or ``sigma_env`` not a valid SD, ``m`` not a positive count, too many readings or their work beyond
        the work budget (``fusion._limits.MAX_WORK``: 0.06 units an ``n**3``, 400,000 a sensor and 0.04 a ``k**3``
        of each sensor's batch GLS over the first k readings; about 520 sensors of one reading), counted before
        any entry of ``sigma`` is checked, or ``sigma_env`` so large beside ``sigma`` that R is singular to working
        precision (its factorisation fails).
    """
    seed = check_seed(seed)   # an integer seed (rule 11), named
    m = count(m, "m")
    # the readings counted before sigma's entries are converted and checked one by one (book audit 76: 10**6 sigma
    # were checked first, 3.1 CPU-s, before the refusal of their number)
    _sequential_readings(len(sigma) if isinstance(sigma, (list, tuple)) else None, m)
    sig = as_array(sigma, "sigma", ndim=1)
    _sequential_readings(sig.size, m)
    for i, v in enumerate(sig):
        std_scalar(v, f"sigma[{i}]")
    sigma_env = scalar(sigma_env, "sigma_env", lo=0.0)
    if sigma_env > 0.0:
        std_scalar(sigma_env, "sigma_env")
    n = sig.size * int(m)
    R = np.kron(np.diag(sig ** 2), np.eye(int(m))) + float(sigma_env) ** 2 * np.ones((n, n))
    H = np.ones((n, 1))
    with derived("sigma_env and sigma", "a covariance R singular to working precision"):  # fuzz 19, D3
        z = 1.0 + np.linalg.cholesky(R) @ np.random.default_rng(seed).normal(size=n)
        ldl = co.ldl_unpivoted(R)
        M = co.unit_lower_inverse(ldl.L)
    G, y = M @ H, M @ z
    rows = {}
    for i in range(1, sig.size + 1):
        k, own = i * int(m), slice((i - 1) * int(m), i * int(m))
        w = G[:k] / ldl.d[:k, None]
        x_seq = float(np.linalg.solve(G[:k].T @ w, w.T @ y[:k])[0])
        x_gls = float(co.gls(H[:k], R[:k, :k], z[:k]).x[0])
        rows[f"sensor {i}"] = {"readings used": f"1-{k}", M_LARGEST:
                               float(np.max(np.abs(M[own, k:]), initial=0.0)),
                               "multiplications": int(np.count_nonzero(np.tril(M, -1)[own])),
                               FULL_M: int(m) * (n - 1), "estimate after sensor i": round(x_seq, 4),
                               VS_BATCH: roundoff(abs(x_seq - x_gls) / abs(x_gls))}
    return pd.DataFrame(rows).T


def glue_sequential(tab: pd.DataFrame) -> GlueValues:
    """Glue values of :func:`table_sequential` (keys ``lec_seq_*``).

    Parameters
    ----------
    tab : pandas.DataFrame
        Result of :func:`table_sequential`.

    Returns
    -------
    GlueValues
        ``lec_seq_n`` (sensors), ``lec_seq_zero`` (sensors whose rows of M are exactly 0 on later readings),
        ``lec_seq_same`` (sensors whose running estimate equals the batch GLS of the sensors so far to round-off),
        ``lec_seq_mult`` and ``lec_seq_full`` (multiplications of all pseudo-measurements, with M's zeros and with
        a full M).

    Raises
    ------
    TypeError
        ``tab`` not a DataFrame, or a cell read that is not a number (text in ``vs batch GLS``).
    ValueError
        ``tab`` without the columns of :func:`table_sequential`, empty, holding a sensor's row twice, or a
        non-finite cell read.
    """
    _frame(tab, "tab", (M_LARGEST, VS_BATCH, "multiplications", FULL_M), maker="table_sequential",
           finite=(M_LARGEST, "multiplications", FULL_M), texts=(VS_BATCH,), unique=True)  # a sensor counted once
    return {"lec_seq_n": len(tab), "lec_seq_zero": int((tab[M_LARGEST] == 0.0).sum()),
            "lec_seq_same": int(tab[VS_BATCH].str.startswith("less than").sum()),
            "lec_seq_mult": int(tab["multiplications"].sum()), "lec_seq_full": int(tab[FULL_M].sum())}


#: Units of work (``fusion._limits.work``, about 10 ns) of :func:`table_james_stein`: a normal draw of its d x runs
#: noise, and a term of :func:`james_stein_risk`'s Poisson sum. Measured (CPU time, minimum of 2,
#: OPENBLAS_NUM_THREADS=1, shared machine): 10 ratios over d x runs = 3e6 draws (d = 3 to 10,000) took 0.46-1.04 units
#: an element and ratio, draws included (so 1 unit an element and ratio, 3 a drawn element); the exact risk at
#: ratio 1000 (5.4e5 terms) 32 ms, 6 units a term.
_JS_DRAW_WORK = 3
_JS_TERM_WORK = 6
#: Units of one (d, ratio) cell of :func:`table_james_stein` besides its elements and terms: a
#: ``fusion.readings.biased.james_stein`` call with its checks, :func:`james_stein_risk`'s own checks and scipy's
#: ``poisson.pmf`` call, a row. Measured (fuzz 42b C1: 530,000 cells ran 42.9 CPU-s, counted 1.8e3 units each; CPU time,
#: minimum of 2, OPENBLAS_NUM_THREADS=1, shared machine): 72-88 us a cell at d = 3, 100 runs, ratio 0 (5,000 and 20,000
#: ratios) and 120 us at d = 3 to 52 (50 x 400 cells, 27 us of them its 2,700 elements): 9 ``LOOP_STEP`` (90 us).
_JS_CELL_WORK = 9 * LOOP_STEP


def _js_terms(ratio: float) -> int:
    """Terms of :func:`james_stein_risk`'s Poisson sum at ``ratio`` (``‖x‖/σ``): about ratio² / 2."""
    lam = float(ratio) ** 2 / 2.0
    return int(lam + 40.0 * np.sqrt(lam + 1.0) + 50) + 1


def james_stein_risk(d: int, ratio: float) -> float:
    r"""Exact risk of James-Stein over that of least squares, :math:`y \sim N(x, \sigma^2I_d)`, :math:`\lVert x\rVert/\sigma` = ``ratio``.

    :math:`E\lVert\hat x_{JS} - x\rVert^2/(d\sigma^2) = 1 - \frac{(d-2)^2}{d}\,E\big[1/(d - 2 + 2K)\big]`,
    :math:`K \sim \mathrm{Poisson}(\lVert x\rVert^2/2\sigma^2)` (the noncentral :math:`\chi^2`'s Poisson mixture); least
    squares (:math:`y` itself) has risk :math:`d\sigma^2`. 1 at d = 2 (James-Stein is then least squares).

    Parameters
    ----------
    d : int
        Dimension (>= 2).
    ratio : float
        :math:`\lVert x\rVert/\sigma` (0 to 1000: the Poisson sum has about ratio² / 2 terms).

    Returns
    -------
    float
        1 − (d − 2)²/d · E[1/(d − 2 + 2K)], K Poisson with mean ratio²/2: between 0 and 1 (exactly 1 for d = 2).
    """
    from scipy.stats import poisson

    d = count(d, "d", minimum=2)
    ratio = scalar(ratio, "ratio", lo=0.0, hi=MAX_JS_RATIO)
    kmax = _js_terms(ratio) - 1
    lam = float(ratio) ** 2 / 2.0
    k = np.arange(kmax + 1)
    e = float(np.sum(poisson.pmf(k, lam) / (d - 2 + 2 * k))) if d > 2 else 0.0
    return 1.0 - (d - 2) ** 2 / d * e


def table_james_stein(ds: tuple[int, ...] = (3, 5, 10), ratios: tuple[float, ...] = (0.0, 1.0, 3.0, 10.0),
                      runs: int = 20000, seed: int = SEED) -> pd.DataFrame:
    """James-Stein's risk over least squares' for each dimension and ‖x‖/σ, exact and by Monte Carlo (4 decimals).

    Parameters
    ----------
    ds : tuple of int
        Dimensions (>= 2; the Monte-Carlo column needs >= 3, shown as NaN at 2).
    ratios : tuple of float
        ‖x‖/σ (x along the first axis, σ = 1).
    runs : int
        Monte-Carlo draws (:func:`fusion.readings.biased.james_stein` on y = x + e), the same for every cell; at least
        ``fusion.book.rulebook.MIN_RUNS`` (100, the book's rule R4 for any Monte-Carlo reading). The column checks the
        exact one and is printed to 4 decimals: a handful of draws would print one draw's noise as an estimate
        (``runs=1``, seed 0: 3.1 against the exact 0.76 at d = 3, ‖x‖/σ = 1), so fewer runs are refused. It stays an estimate:
        at d = 3 the loss has no finite variance near x = 0, and the deviation is what ``lec_js_mc_dev`` reports.
    seed : int

    Returns
    -------
    pandas.DataFrame
        Index (d, ‖x‖/σ); ``exact`` (:func:`james_stein_risk`) and ``Monte Carlo``. ``attrs["runs"]`` records
        ``runs``, which :func:`glue_james_stein` glues.

    Raises
    ------
    TypeError
        ``runs``, ``seed`` or an entry of ``ds`` not an integer, an entry of ``ratios`` not a number.
    ValueError
        ``runs`` below ``MIN_RUNS``; ``ds`` or ``ratios`` empty, an entry of ``ds`` below 2, above the ceiling of a
        dimension (``10**4``, as :func:`james_stein_risk`) or repeated, of ``ratios`` outside [0, ``MAX_JS_RATIO``];
        before any draw, the draws and estimates of every cell (``runs`` x the sum of ``ds`` x (3 + the ratios),
        units of about 10 ns), each cell's calls (9,000 units, measured) and the exact risks' Poisson sums beyond
        the work budget (``fusion._limits.MAX_WORK``), naming ``ds``, ``ratios`` and ``runs``; the cells are
        counted before any ratio is checked.
    """
    runs = count(runs, "runs", minimum=MIN_RUNS)  # R4: a Monte-Carlo column of fewer draws is one draw's noise
    seed = check_seed(seed)   # an integer seed (rule 11), named
    # james_stein_risk's ceiling of a dimension on every entry, at entry (fuzz 41b C5: ds = (10000, 10001) was refused
    # by it inside the loop, after the first d's Monte Carlo, naming its own d)
    ds = distinct(counts(ds, "ds", minimum=2, maximum=COUNT_CEILINGS["dimension"]), "ds")
    seed = check_seed(seed, span=max(ds))   # dimension d's draws: seed + d, a seed too (fuzz 55 C1)
    ratios = sequence(ratios, "ratios", minimum=1, what="ratio")
    # the cells, counted before any ratio is checked (fuzz 42b C2: 5e6 ratios were checked one by one for 12 CPU-s
    # before the work check refused them)
    names = (f"ds, ratios and runs ({len(ds):,} dimensions summing to {sum(ds):,} x {len(ratios):,} ratios x "
             f"{runs:,} runs)")
    work((len(ds), len(ratios)), names, weight=_JS_CELL_WORK)
    ratios = [scalar(r, f"ratios[{i}]", lo=0.0, hi=MAX_JS_RATIO) for i, r in enumerate(ratios)]
    for d in ds:
        allocation((d, runs), "ds and runs")
        input_allocation((d, runs), "ds and runs")  # the readings are rg.james_stein's input (fuzz 39a D1, class)
    # rule 17 (fuzz 41b C4: nothing counted the cells; ds = (10000, 9999), 60 ratios, 3,000 runs ran 35 CPU-s): per d,
    # its d x runs draws (_JS_DRAW_WORK units an element) and per ratio a James-Stein estimate over them (1 unit an
    # element) and the exact risk's Poisson sum (_JS_TERM_WORK units a term), and each cell's calls (_JS_CELL_WORK,
    # fuzz 42b C1: counted a loop step, 530,000 cells ran 42.9 CPU-s)
    terms = sum(_js_terms(r) for r in ratios)
    work((runs * sum(ds) * (_JS_DRAW_WORK + len(ratios))
          + len(ds) * (len(ratios) * _JS_CELL_WORK + _JS_TERM_WORK * terms),), names)
    rows = []
    for d in ds:
        e = np.random.default_rng(seed + int(d)).normal(size=(int(d), runs))
        for r in ratios:
            x = np.zeros(int(d))
            x[0] = float(r)
            mc = (float(np.mean(np.sum((rg.james_stein(x[:, None] + e, 1.0) - x[:, None]) ** 2, axis=0))) / d
                  if d > 2 else float("nan"))
            rows.append({"d": int(d), "‖x‖/σ": float(r), "exact": round(james_stein_risk(d, r), 4),
                         MONTE_CARLO: round(mc, 4)})
    tab = pd.DataFrame(rows).set_index(["d", "‖x‖/σ"])
    tab.attrs["runs"] = runs  # the draws behind the Monte-Carlo column, for its glue (fuzz 18, E20)
    return tab


def glue_james_stein(tab: pd.DataFrame, runs: int | None = None) -> GlueValues:
    """Glue values of :func:`table_james_stein` (keys ``lec_js_*``).

    Parameters
    ----------
    tab : pandas.DataFrame
        Result of :func:`table_james_stein`.
    runs : int, optional
        Its Monte-Carlo draws (at least ``MIN_RUNS``, as :func:`table_james_stein`): by default those the table
        records (``tab.attrs["runs"]``); when given, they must be those (a table without the record takes them as
        given).

    Returns
    -------
    GlueValues
        ``lec_js_runs``; ``lec_js_min_<d>`` (the exact ratio at x = 0: 2/d) for each d >= 3; ``lec_js_max`` (the
        largest exact ratio for d >= 3, the one farthest from 0); ``lec_js_mc_dev`` (largest |Monte Carlo − exact|).

    Raises
    ------
    TypeError
        ``tab`` not a DataFrame, ``runs`` or ``tab.attrs["runs"]`` (when there) not an integer.
    ValueError
        ``tab.attrs["runs"]`` below ``MIN_RUNS``;
        ``tab`` without the columns and index of :func:`table_james_stein` or empty, holding a row twice, without
        a dimension d >= 3 or
        the row ‖x‖/σ = 0 of one, a non-finite exact value (or
        Monte-Carlo value at d >= 3); ``runs`` below ``MIN_RUNS``, not the
        draws the table records, or not given for a table that records none.
    """
    _frame(tab, "tab", ("exact", MONTE_CARLO), ("d", "‖x‖/σ"), maker="table_james_stein", finite=("exact",),
           unique=True)  # read by (d, ‖x‖/σ): a repeated row gave pandas' unnamed TypeError (fuzz 33b B3)
    made = tab.attrs.get("runs")
    if made is not None:  # the table's record, named as such (fuzz 33b D1: a bad one was blamed on runs)
        made = count(made, "tab.attrs['runs']", minimum=MIN_RUNS)
    if runs is None:
        if made is None:
            raise ValueError("runs must be given: tab does not record its Monte-Carlo draws (tab.attrs['runs'])")
        runs = made
    runs = count(runs, "runs", minimum=MIN_RUNS)
    if made is not None and runs != made:
        raise ValueError(f"runs = {runs} is not the {made} Monte-Carlo draws that tab was made with")
    three = tab[tab.index.get_level_values("d") >= 3]
    d3 = sorted({int(d) for d in three.index.get_level_values("d")})
    if not d3:
        raise ValueError(f"tab lacks a dimension d >= 3 that glue_james_stein reads (it holds d = "
                         f"{sorted({int(d) for d in tab.index.get_level_values('d')})})")
    _holds(tab.index, [(d, 0.0) for d in d3], "tab", "rows (d, ‖x‖/σ)", "glue_james_stein")
    if not np.all(np.isfinite(three[MONTE_CARLO].to_numpy(dtype=float))):  # NaN only at d = 2 (no estimate there)
        raise ValueError(f"tab[{shown(MONTE_CARLO)}] must hold finite numbers for d >= 3, got a NaN or an infinity")
    out: GlueValues = {"lec_js_runs": runs, "lec_js_max": float(three["exact"].max()),
                           "lec_js_mc_dev": round(float((three[MONTE_CARLO] - three["exact"]).abs().max()), 4)}
    for d in d3:
        out[f"lec_js_min_{d}"] = float(tab.loc[(d, 0.0), "exact"])
    return out


def table_shrunken(v: VectorStudy) -> pd.DataFrame:
    r"""Exact MSEs in the vector case of §2.5: least squares, the best shrunken LS :math:`c\hat x_{LS}` and the best ridge.

    With :math:`A` the total information and :math:`P = A^{-1}`: :math:`\mathrm{MSE}(c) = c^2\,\mathrm{tr}P + (1-c)^2\lVert
    x\rVert^2`, least at :math:`c^* = \lVert x\rVert^2/(\lVert x\rVert^2 + \mathrm{tr}P)`; ridge
    :math:`(A + kI)^{-1}A\hat x_{LS}` has :math:`\mathrm{tr}\big((A+kI)^{-1}A(A+kI)^{-1}\big) + k^2x^\top(A+kI)^{-2}x`,
    minimised numerically over k in [e⁻²⁰, e²⁰] (a grid in log k, then refined). Both with x known (oracle parameters): the best each form can do.

    Parameters
    ----------
    v : VectorStudy
        :func:`fusion.scenarios.ridge_sensors.vector_study` (its ``A`` and true values ``x``).

    Returns
    -------
    pandas.DataFrame
        One row per (direction, ‖x‖): ``LS``, ``best c·LS`` and ``best ridge`` (exact MSE, 4 significant digits),
        ``c*`` and ``k*`` (3 significant digits).
    """
    instance_of(v, VectorStudy, "v")
    from scipy.optimize import minimize_scalar

    A = np.asarray(v.A, dtype=float)
    tr = float(np.trace(np.linalg.inv(A)))
    rows = {}
    for (direction, scale), x in v.x.items():
        x = np.asarray(x, dtype=float)
        nx = float(x @ x)

        def ridge_mse(logk: float) -> float:
            B = np.linalg.inv(A + np.exp(logk) * np.eye(A.shape[0]))
            b = np.exp(logk) * B @ x
            return float(np.trace(B @ A @ B) + b @ b)

        grid = np.linspace(-20.0, 20.0, 401)  # a grid first (the risk in log k need not be unimodal), then refined
        g0 = float(grid[int(np.argmin([ridge_mse(t) for t in grid]))])
        opt = minimize_scalar(ridge_mse, bounds=(g0 - 0.1, g0 + 0.1), method="bounded", options={"xatol": 1e-10})
        best_r = min(float(opt.fun), tr)
        rows[f"{direction}, ‖x‖ = {scale:g}"] = {METHOD_SHORT_LABELS[LS]: float(f"{tr:.4g}"), BEST_SCALED_LS: float(f"{tr * nx / (nx + tr):.4g}"),
                                                 BEST_RIDGE: float(f"{best_r:.4g}"),
                                                 "c*": float(f"{nx / (nx + tr):.3g}"),
                                                 "k*": float(f"{np.exp(opt.x):.3g}")}
    return pd.DataFrame(rows).T


def glue_shrunken(tab: pd.DataFrame) -> GlueValues:
    """Glue values of :func:`table_shrunken` (keys ``lec_sh_*``).

    Parameters
    ----------
    tab : pandas.DataFrame
        Result of :func:`table_shrunken`.

    Returns
    -------
    GlueValues
        ``lec_sh_n`` (cases), ``lec_sh_ridge_wins`` (cases where the best ridge has the lower MSE),
        ``lec_sh_max_gap`` (the largest ratio best c·LS over best ridge) and ``lec_sh_min_ratio`` (the smallest
        best c·LS over LS: the most shrinking helps).

    Raises
    ------
    TypeError
        ``tab`` not a DataFrame, or a cell read that is not a number.
    ValueError
        ``tab`` without the columns of :func:`table_shrunken`, empty, holding a case's row twice, or a non-finite
        cell read.
    """
    _frame(tab, "tab", (BEST_RIDGE, BEST_SCALED_LS, METHOD_SHORT_LABELS[LS]), maker="table_shrunken",
           finite=(BEST_RIDGE, BEST_SCALED_LS, METHOD_SHORT_LABELS[LS]), unique=True)  # a case counted once
    return {"lec_sh_n": len(tab), "lec_sh_ridge_wins": int((tab[BEST_RIDGE] < tab[BEST_SCALED_LS]).sum()),
            "lec_sh_max_gap": round(float((tab[BEST_SCALED_LS] / tab[BEST_RIDGE]).max()), 2),
            "lec_sh_min_ratio": round(float((tab[BEST_SCALED_LS] / tab[METHOD_SHORT_LABELS[LS]]).min()), 3)}
