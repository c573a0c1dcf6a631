"""Simulated thermocouple bank of Yang, Feng & Fan (2012, Figs. 1-4) and its Monte-Carlo study.

The source simulates ten thermocouples measuring a furnace at 900 °C, 100 samples each,
"with ten groups of normal random numbers", and a failure in which sensors 4 and 10 get
biases of 4 and 8 °C on samples 50-80. It does not give the noise levels; they are a
parameter here and the chapter states and varies its choice.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray

from fusion._frozen import constant
from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, integer, number, same_keys, text, tuple_of,
                             validated_post_init)
from fusion._validation import read_mapping, read_once
from fusion._validation import derived_inputs
from fusion._validation import LOOP_STEP, distinct, loop_work, one_of, work
from fusion._validation import allocation, record, seed as check_seed
from fusion._validation import (FloatArray, as_array, as_reading_rows, as_rng, check_magnitude, count, instance_of,
                                scalar, sequence, window as check_window)
from fusion.readings.fusion_set import METHODS as _METHODS, _check_options, fuse_epochs
from fusion.readings._row_blocks import epochs_limit
from fusion._validation import within
from fusion._options import text_key
from fusion._shown import shown
from fusion._nesting import ndim_of

__all__ = [
    "DEFAULT_SIGMAS",
    "simulate",
    "inject_failure",
    "FAILURE_MODES",
    "random_failure",
    "absolute_errors",
    "monte_carlo",
    "best_linear_abs_error",
    "PairedStudy",
    "paired_study",
    "scale_sweep",
]

#: Noise standard deviations (°C) of the ten simulated thermocouples used by default:
#: evenly spaced from 0.5 to 2.0 °C (our choice; the source gives none).
DEFAULT_SIGMAS: FloatArray = constant(np.linspace(0.5, 2.0, 10))


def _sigmas(sigma: ArrayLike, n_sensors: int) -> FloatArray:
    s = np.broadcast_to(np.asarray(sigma, dtype=float), (n_sensors,)).copy()
    if not np.all(np.isfinite(s)) or np.any(s <= 0):
        raise ValueError("sigma must be finite and positive for every sensor")
    return s


def simulate(
    rng: np.random.Generator,
    n_samples: int = 100,
    sigma: ArrayLike = DEFAULT_SIGMAS,
    truth: float = 900.0,
    n_runs: int | None = None,
    n_sensors: int = 10,
) -> FloatArray:
    """Draw thermocouple readings :math:`s_i(t) = X + v_i(t)`, :math:`v_i \\sim N(0, \\sigma_i^2)`.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of randomness (pass a seeded generator for reproducibility).
    n_samples : int
        Number of sampling instants (epochs).
    sigma : array_like, shape (n_sensors,) or scalar
        Noise standard deviation of each sensor, °C (a scalar applies to all).
    truth : float
        True temperature :math:`X`, °C.
    n_runs : int, optional
        If given, draw that many independent runs at once.
    n_sensors : int
        Number of sensors (10 in the source); must match ``sigma`` if it is an array.

    Returns
    -------
    ndarray, shape (n_samples, n_sensors) or (n_runs, n_samples, n_sensors)
        Readings in °C.
    """
    as_rng(rng)
    n_sensors = count(n_sensors, "n_sensors")
    n_samples = count(n_samples, "n_samples")
    truth = scalar(truth, "truth")
    sig_in = as_array(sigma, "sigma")
    if sig_in.ndim > 1 or (sig_in.ndim == 1 and sig_in.size != n_sensors):
        raise ValueError(f"sigma must be a scalar or have n_sensors = {n_sensors} entries, got shape {sig_in.shape}")
    sig = _sigmas(sig_in, n_sensors)
    if n_samples < 1:
        raise ValueError(f"n_samples must be at least 1, got {n_samples}")
    shape: tuple[int, ...] = (n_samples, sig.size)
    if n_runs is not None:
        n_runs = count(n_runs, "n_runs")
        shape = (n_runs, *shape)
    allocation(shape, "n_runs, n_samples and n_sensors")  # the memory budget, before anything is drawn
    return truth + rng.standard_normal(shape) * sig


def inject_failure(
    z: ArrayLike,
    sensors: Sequence[int] = (4, 10),
    samples: tuple[int, int] = (50, 80),
    biases: Sequence[float] = (4.0, 8.0),
) -> FloatArray:
    """Add a constant bias to some sensors on a window of samples (Yang, Feng & Fan (2012), Fig. 3).

    Parameters
    ----------
    z : array_like, shape (..., n_samples, n_sensors)
        Readings (a copy is returned; ``z`` is not modified).
    sensors : sequence of int
        **1-based** sensor numbers, as in the source, no two equal (each receives one bias).
    samples : (int, int)
        First and last **1-based** sample numbers, inclusive (50-80 is 31 samples).
    biases : sequence of float
        Bias added to each sensor in ``sensors``, °C.

    Returns
    -------
    ndarray
        Same shape as ``z``.
    """
    samples = read_once(samples, "samples")  # a Sequence class read once (fuzz 31a C4)
    out = np.array(as_array(z, "z"), dtype=float, copy=True)
    if out.ndim < 2:
        raise ValueError(f"z must have shape (..., n_samples, n_sensors), got {out.shape}")
    n_samples, n_sensors = out.shape[-2:]
    sensors, biases = sequence(sensors, "sensors"), sequence(biases, "biases")  # their items (any 1-D array-like)
    if len(sensors) != len(biases):
        raise ValueError("sensors and biases must have the same length")
    if isinstance(samples, (str, bytes)) or ndim_of(samples, "samples") != 1 or len(samples) != 2:
        raise TypeError(f"samples must be a pair (first, last) of sample numbers, got {shown(samples)}")
    first, last = count(samples[0], "samples[0]"), count(samples[1], "samples[1]")
    for nm, seq in (("sensors", sensors), ("biases", biases)):
        if isinstance(seq, (str, bytes)) or any(e is None or isinstance(e, (str, bytes, dict, list, tuple, np.ndarray))
                                                for e in sequence(seq, nm)):
            raise TypeError(f"{nm} must be a flat sequence of numbers, got {shown(seq)}")
    check_window((first, last), "samples", n_samples, one_based=True)
    bias_values = as_array(biases, "biases", ndim=1, nonempty=False)
    numbers = []
    for i, sensor in enumerate(sensors):
        sensor = count(sensor, f"sensors[{i}]", maximum=None)
        if not (1 <= sensor <= n_sensors):
            raise ValueError(f"sensor {sensor} outside 1..{n_sensors} (sensors[{i}])")
        numbers.append(sensor)
    distinct(numbers, "sensors")  # one bias per sensor: a repeated sensor would receive the sum of two
    for sensor, bias in zip(numbers, bias_values):
        out[..., first - 1 : last, sensor - 1] += bias
    return out


#: Readings of the source's "随机地" ("randomly") in its failure experiment (section 2, Fig. 3):
#: ``"fixed"``: the stated biases on every sample of the window (the book's primary reading);
#: ``"random size"``: each biased sample gets a bias drawn uniformly between 0 and the stated bias;
#: ``"random samples"``: the stated bias on each sample of the window with probability 1/2.
FAILURE_MODES: tuple[str, ...] = ("fixed", "random size", "random samples", "opposite signs")


def random_failure(
    z: ArrayLike,
    rng: np.random.Generator,
    mode: str = "fixed",
    sensors: Sequence[int] = (4, 10),
    samples: tuple[int, int] = (50, 80),
    biases: Sequence[float] = (4.0, 8.0),
) -> FloatArray:
    """The failure of :func:`inject_failure` under one reading of "randomly" (:data:`FAILURE_MODES`).

    Parameters
    ----------
    z : array_like, shape (..., n_samples, n_sensors)
        Readings (a copy is returned).
    rng : numpy.random.Generator
        Draws the random bias sizes or the biased samples (unused for ``"fixed"``).
    mode : {"fixed", "random size", "random samples", "opposite signs"}
        ``"fixed"``: the biases on every sample of the window; ``"random size"``: at each sample
        and failing sensor a bias drawn from U(0, bias); ``"random samples"``: the full bias at
        each sample and failing sensor independently with probability 1/2; ``"opposite signs"``:
        as ``"fixed"`` with the sign of every second failing sensor's bias reversed (the source
        gives the biases' sizes only).
    sensors, samples, biases
        As in :func:`inject_failure` (1-based sensors and samples).

    Returns
    -------
    ndarray
        Same shape as ``z``.

    References
    ----------
    Yang G. N., Feng X. F., Fan L. J. (2012), section 2, Fig. 3.
    """
    samples = read_once(samples, "samples")  # a Sequence class read once (fuzz 31a C4)
    rng = as_rng(rng)
    mode = one_of(mode, FAILURE_MODES, "mode")   # TypeError for a non-str (issue 35)
    base = as_array(z, "z")
    sensors, biases = sequence(sensors, "sensors"), sequence(biases, "biases")  # their items (any 1-D array-like)
    if mode == "opposite signs":
        return inject_failure(base, sensors, samples, [-float(b) if k % 2 else float(b) for k, b in enumerate(biases)])
    out = inject_failure(base, sensors, samples, biases)
    if mode == "fixed":
        return out
    first, last = int(samples[0]), int(samples[1])
    cols = np.asarray(sensors, dtype=int) - 1
    shape = (*base.shape[:-2], last - first + 1, cols.size)
    if mode == "random size":
        factor = rng.uniform(0.0, 1.0, size=shape)
    else:
        factor = (rng.random(shape) < 0.5).astype(float)
    out = np.array(base, dtype=float, copy=True)
    out[..., first - 1:last, cols] += factor * np.asarray(biases, dtype=float)
    return out


def _check_methods(methods: object, first: Callable[[int], object] | None = None) -> dict[str, dict[str, object]]:
    """``methods``: a dict label -> options dict with a string ``"method"`` key (issue 35, class 6), returned with
    its labels and method names as plain texts (rule 19) and each entry's options checked under its place in the
    argument (``methods['mean']: ...``, fuzz 32a C5). ``first(len(methods))``, when given, is called before any
    entry is read: the caller's budget by the number of methods (fuzz 62b C4: 10**6 specs were each read and
    checked first, refused after 8.1-8.3 CPU-s)."""
    if not isinstance(methods, Mapping):
        raise TypeError(f"methods must be a dict label -> options, got {type(methods).__name__}")
    if first is not None:
        first(len(methods))
    out: dict[str, dict[str, object]] = {}
    for label, spec in methods.items():
        key = text_key(label, "methods")   # a text label (fuzz 33a C5), refused by the caller's argument
        if not isinstance(spec, Mapping):
            raise TypeError(f"methods[{shown(label)}] must be a dict of options, got {type(spec).__name__}")
        if not isinstance(spec.get("method"), str):
            raise ValueError(f"methods[{shown(label)}] must name its method as a string under the key 'method', got {shown(spec)}")
        with within(f"methods[{shown(label)}]"):
            options = dict(spec)
            name = one_of(options.pop("method"), tuple(_METHODS), "method")
            out[key] = {"method": name, **_check_options(name, options)}
    return out


#: Units of one ``fuse_epochs`` call of a method of :func:`absolute_errors` and :func:`paired_study` beyond its epochs'
#: own work: 50 us a call measured (2,000 methods of "mean" on 2 runs: monte_carlo 0.1 CPU-s, paired_study 0.2 with
#: its two calls a method; time.process_time, machine shared), weighed 8 LOOP_STEP.
_METHOD_CALL = 8 * LOOP_STEP
#: Units (about 10 ns each) of one epoch of ``n`` readings fused by each method of ``fuse_epochs``, as (a reading,
#: a pair of readings): measured on this shared machine (OPENBLAS_NUM_THREADS=1, time.process_time, minimum of 2;
#: n = 3, 10, 30, 100, 300 and 900 readings, 2e6 to 1 epochs) and rounded up to the largest per reading at small n
#: and per pair at large n. The optimal fusion set (re-measured, fuzz 42b C6: its 20 units a reading and 1 a pair
#: counted its epochs 1.6-2.1x, so the reseeding sweep's 10x reading of yang-weights-reasonable, 9 scales x 500,000
#: epochs of 10, was refused though it runs 6.7 CPU-s): 42, 164, 789, 5,439, 45,434 and 385,151 units an epoch at
#: n = 3, 10, 30, 100, 300 and 900 (1e6 to 60 epochs), so 14 a reading and 1/2 a pair (47, 190, 870, 6,400, 49,200
#: and 417,600: 8-18 % above); the fusion-set weights 90-112 ns a
#: reading, 3.4-3.8 ns a pair; the support degree 35-50 ns a reading, 1.8-2.2 ns a pair; the belief degree (its
#: eigendecomposition included) 480-820 ns a reading at n <= 10, 70-160 ns a pair up to n = 900; the mean 2-6 ns a
#: reading. ``fuse_epochs``' own budget (``PAIR_WORK``, 20 units a pair) stays each method's limit (``epochs_limit``):
#: the sum of the methods counts what they cost (fix46: at ``PAIR_WORK`` the book's stability reading of chapter 01,
#: 6 methods of 5,000 runs, counted 6e9 units and ran 3.0 CPU-s).
_EPOCH_UNITS: Mapping[str, tuple[Fraction, Fraction]] = constant({
    "mean": (Fraction(1), Fraction(0)),
    "optimal_fusion_set": (Fraction(14), Fraction(1, 2)),
    "fusion_set_weights": (Fraction(12), Fraction(1, 2)),
    "support_degree": (Fraction(5), Fraction(1, 4)),
    "belief_degree": (Fraction(30), Fraction(16)),
})
#: Units of each reading :func:`paired_study` draws, fails and compares besides its fusions (``simulate``,
#: ``random_failure``, the changed epochs and the errors): 30-40 ns a reading measured (5,000 runs of 10 sensors,
#: 50,000 of 3, 500 of 100), weighed 5.
_PAIRED_READING = 5


def _methods_work(rows: int, n: int, methods: Mapping[str, Mapping[str, object]] | Sequence[Mapping[str, object]],
                  names: str, fusions: int = 1, per_reading: int = 0) -> int:
    """Rule 17 on every method's ``fuse_epochs`` of ``rows`` epochs of ``n`` readings, ``fusions`` times each, naming
    ``names``: first each method's own limits (``epochs_limit``, what ``fuse_epochs`` would refuse), then their sum
    at their measured cost (``_EPOCH_UNITS`` an epoch plus ``_METHOD_CALL`` a call; the methods were not counted:
    200,000 of 2 runs ran over 60 CPU-s, each within ``fuse_epochs``' budget; fuzz 40a, the class), plus
    ``per_reading`` units of each of the ``rows * n`` readings for the caller's own work. ``methods``: a dict of
    specs, or their list."""
    used = Counter(str(spec["method"]) for spec in (methods.values() if isinstance(methods, Mapping) else methods))
    for name in used:   # the limits depend on the method's name only: once a name (200,000 methods, a few ms)
        epochs_limit(rows, n, name, names)
    total = Fraction(per_reading * rows * n)
    for name, k in used.items():
        reading, pair = _EPOCH_UNITS[name]
        total += k * fusions * (_METHOD_CALL + rows * (reading * n + pair * n * n))
    return work((math.ceil(total),), names)


def _methods_floor(rows: int, n: int, k: int, names: str, fusions: int = 1, per_reading: int = 0) -> int:
    """:func:`_methods_work`'s total for ``k`` methods at the cheapest method's cost (the mean's, ``_EPOCH_UNITS``),
    before any method's spec is read: a lower bound of what the methods ask for, refused under the same names."""
    reading, pair = min(u[0] for u in _EPOCH_UNITS.values()), min(u[1] for u in _EPOCH_UNITS.values())
    total = per_reading * rows * n + k * fusions * (_METHOD_CALL + rows * (reading * n + pair * n * n))
    return work((math.ceil(total),), names)


def absolute_errors(
    z: ArrayLike, methods: dict[str, dict[str, object]], truth: float = 900.0
) -> dict[str, FloatArray]:
    """Absolute error :math:`|\\hat x(t) - X|` of each fusion method at every epoch.

    Parameters
    ----------
    z : array_like, shape (..., n_sensors)
        Readings; all leading axes are epochs.
    methods : dict
        Text label -> ``{"method": name, **options}`` for :func:`fusion.readings.fusion_set.fuse_epochs`.
    truth : float
        True value, °C.

    Returns
    -------
    dict of str to ndarray
        Label -> errors with the leading shape of ``z``.
    """
    arr = as_array(z, "z")
    if arr.ndim < 1:
        raise ValueError(f"z must have a sensor axis, got shape {arr.shape}")
    truth = scalar(truth, "truth")
    methods = _check_methods(methods, lambda k: _methods_floor(arr.size // max(arr.shape[-1], 1), arr.shape[-1], k,
                                                               "z and methods"))
    flat = as_reading_rows(arr.reshape(-1, arr.shape[-1]), "z")
    _methods_work(flat.shape[0], flat.shape[1], methods, "z and methods")
    out: dict[str, FloatArray] = {}
    for label, spec in methods.items():
        spec = dict(spec)
        name = spec.pop("method")
        values = fuse_epochs(flat, name, **spec).values
        out[label] = np.abs(values - truth).reshape(arr.shape[:-1])
    return out


@derived_inputs()
def monte_carlo(
    seed: int,
    n_runs: int,
    methods: dict[str, dict[str, object]],
    sigma: ArrayLike = DEFAULT_SIGMAS,
    n_samples: int = 100,
    failure: dict[str, object] | None = None,
    truth: float = 900.0,
    n_sensors: int = 10,
) -> dict[str, FloatArray]:
    """Repeat the source's experiment over ``n_runs`` independent draws.

    Parameters
    ----------
    seed : int
        Seed of the :class:`numpy.random.Generator` (PCG64).
    n_runs : int
        Number of independent runs.
    methods : dict
        As in :func:`absolute_errors`.
    sigma, n_samples, truth
        As in :func:`simulate`.
    failure : mapping, optional
        Keyword arguments of :func:`inject_failure` (``{}`` for the source's failure).
    n_sensors : int
        Number of thermocouples (10 in Yang, Feng & Fan (2012), Figs. 1-4).

    Returns
    -------
    dict of str to ndarray, each of shape (n_runs, n_samples)
        Absolute errors, °C.
    """
    z = _draws(seed, n_runs, methods, sigma, n_samples, failure, truth, n_sensors)
    return absolute_errors(z, methods, truth=truth)


def _draws(seed: int, n_runs: int, methods: dict[str, dict[str, object]], sigma: ArrayLike, n_samples: int,
           failure: dict[str, object] | None, truth: float, n_sensors: int) -> FloatArray:
    """The readings :func:`monte_carlo` fuses (its checks, in its order): shape (n_runs, n_samples, n_sensors)."""
    n_runs = count(n_runs, "n_runs")
    seed = check_seed(seed)
    checked = _check_methods(methods, lambda k: _methods_floor(
        n_runs * count(n_samples, "n_samples"), count(n_sensors, "n_sensors"), k,
        "n_runs, n_samples, n_sensors and methods"))
    # fuse_epochs's input and kernel limits on the n_runs * n_samples epochs, checked before the draws by the
    # same rule, naming these arguments (fuzz 39a D1: refused inside fuse_epochs, naming every argument)
    rows, n = count(n_runs, "n_runs") * count(n_samples, "n_samples"), count(n_sensors, "n_sensors")
    allocation((rows, n), "n_runs, n_samples and n_sensors")  # simulate's own memory rule first, as before
    # each method's own limits, then their sum (fuzz 40a, the class)
    _methods_work(rows, n, checked, "n_runs, n_samples, n_sensors and methods")
    rng = np.random.default_rng(seed)
    z = simulate(rng, n_samples=n_samples, sigma=sigma, truth=truth, n_runs=n_runs, n_sensors=n_sensors)
    if failure is not None:
        if not isinstance(failure, Mapping):
            raise TypeError(f"failure must be a dict of inject_failure's arguments, got {type(failure).__name__}")
        bad = sorted(set(failure) - {"sensors", "samples", "biases"})
        if bad:
            raise ValueError(f"failure has keys {bad} that inject_failure does not take (sensors, samples, biases)")
        z = inject_failure(z, **failure)  # type: ignore[arg-type]
    return z


def best_linear_abs_error(sigma: ArrayLike, n_sensors: int = 10) -> float:
    r"""Expected absolute error of the best unbiased fusion of independent Gaussian readings.

    With known variances the inverse-variance weighted mean is the minimum-variance
    unbiased estimator (it attains the Cramér-Rao bound),
    :math:`\sigma_\star^2 = (\sum_i \sigma_i^{-2})^{-1}`, and its error is
    :math:`N(0, \sigma_\star^2)`, so :math:`E|\hat x - X| = \sigma_\star\sqrt{2/\pi}`.
    No unbiased method that fuses one epoch at a time can do better on average, in
    mean-square terms, without a failure.

    Parameters
    ----------
    sigma : array_like, shape (n_sensors,) or scalar
        Noise standard deviations, °C.
    n_sensors : int
        Number of sensors when ``sigma`` is a scalar.

    Returns
    -------
    float
        Expected absolute error, °C.
    """
    n_sensors = count(n_sensors, "n_sensors")
    sig_in = as_array(sigma, "sigma", ndim=(0, 1))
    sig = _sigmas(sig_in, sig_in.size if sig_in.ndim == 1 else n_sensors)
    sigma_star = 1.0 / np.sqrt(np.sum(sig**-2.0))
    return float(sigma_star * np.sqrt(2.0 / np.pi))


@dataclass(frozen=True)
class PairedStudy:
    """Absolute errors of several methods on the same Monte-Carlo draws, with and without failure.

    Every method sees the same readings, and the failure case is the same draws plus the
    failure biases, so any two per-run metrics can be compared pairwise.

    Attributes
    ----------
    clean, failed : dict of str to ndarray, shape (n_runs, n_samples)
        Absolute errors (°C) of each method without and with the failure.
    set_size : ndarray, shape (n_runs,)
        Mean number of members of the optimal fusion set per epoch, without failure.
    window : (int, int)
        First and last 1-based sample of the failure window.
    seed : int
    failed_member_share : tuple of float
        For each failing sensor, the share of the window's epochs (all runs) at which it is a
        member of the optimal fusion set under the failure (empty when the optimal set is not
        among the methods).
    failure_mode : str
        The reading of the failure (:data:`FAILURE_MODES`).
    sigma : ndarray, shape (n_sensors,), or None
        Each sensor's noise standard deviation (°C) in the draws, which tells studies of other noise levels
        apart (:func:`paired_study` records it; ``None``: not recorded).
    """

    clean: Mapping[str, FloatArray]
    failed: Mapping[str, FloatArray]
    set_size: FloatArray
    window: tuple[int, int]
    seed: int
    failed_member_share: tuple[float, ...] = ()
    failure_mode: str = "fixed"
    sigma: FloatArray | None = None

    __result_spec__ = ResultSpec(
        {"clean": dict_of(array("runs", "samples", bounds=NONNEGATIVE)),
         "failed": dict_of(array("runs", "samples", bounds=NONNEGATIVE)),
         "set_size": array("runs", nan=True, bounds=NONNEGATIVE), "window": tuple_of(integer(1), integer(1)),
         "seed": integer(0), "failed_member_share": tuple_of(number(bounds=(0.0, 1.0))),
         "failure_mode": text(*FAILURE_MODES), "sigma": array("sensors", optional=True, bounds=NONNEGATIVE)},
        relations=(same_keys("clean", "failed"), lambda v, cls: _window_relation(v, cls)))
    __post_init__ = validated_post_init

    @property
    def n_runs(self) -> int:
        """Number of paired runs."""
        return int(next(iter(self.clean.values())).shape[0])

    def _part(self, failure: bool, window: bool | None) -> slice:
        use_window = failure if window is None else window
        return slice(self.window[0] - 1, self.window[1]) if use_window else slice(None)

    def errors(self, method: str, failure: bool, window: bool | None = None) -> FloatArray:
        """Absolute errors of one method, shape (n_runs, epochs).

        ``window=None`` takes the failure window for the failure case and all samples
        otherwise (the source's Figs. 2 and 4); ``True``/``False`` forces either.
        """
        e = (self.failed if failure else self.clean)[method]
        return e[:, self._part(failure, window)]

    def mae(self, method: str, failure: bool, window: bool | None = None) -> FloatArray:
        """Per-run mean absolute error (°C), shape (n_runs,); ``window`` as in :meth:`errors`."""
        return self.errors(method, failure, window).mean(axis=1)

    def fluctuation(self, method: str, failure: bool, window: bool | None = None) -> FloatArray:
        """Per-run standard deviation of the absolute error over epochs (°C), shape (n_runs,)."""
        return self.errors(method, failure, window).std(axis=1)

    def best_share(self, method: str, failure: bool) -> float:
        """Share of all epochs (all runs) at which ``method`` has the smallest error of all methods."""
        names = list(self.clean)
        stacked = np.stack([self.errors(m, failure) for m in names])
        return float(np.mean(np.argmin(stacked, axis=0) == names.index(method)))


def _paired_errors(z: FloatArray, z_fail: FloatArray, methods: dict[str, dict[str, object]], truth: float
                   ) -> tuple[dict[str, FloatArray], dict[str, FloatArray], NDArray[np.bool_] | None,
                              NDArray[np.bool_] | None]:
    """:func:`absolute_errors` of ``z`` and of ``z_fail`` (the same draws with a failure on some epochs), and the
    optimal set's members of both (``None`` without ``{"method": "optimal_fusion_set"}`` among the methods).

    Every method fuses each epoch on its own (:func:`fusion.readings.fusion_set.fuse_epochs`), so the epochs the
    failure leaves unchanged have the clean epochs' results: only the changed epochs are fused again, and the
    results are :func:`absolute_errors`'s bit for bit (``tests/test_thermocouples.py``).
    """
    flat, flat_fail = z.reshape(-1, z.shape[-1]), z_fail.reshape(-1, z.shape[-1])
    changed = np.flatnonzero(np.any(flat_fail != flat, axis=1))
    clean: dict[str, FloatArray] = {}
    failed: dict[str, FloatArray] = {}
    members = members_fail = None
    for label, spec in methods.items():
        options = dict(spec)
        name = options.pop("method")
        c = fuse_epochs(flat, name, **options)
        f = fuse_epochs(flat_fail[changed], name, **options) if changed.size else c   # (no epoch changed: c's)
        values = c.values.copy()
        values[changed] = f.values[:changed.size]
        clean[label] = np.abs(c.values - truth).reshape(z.shape[:-1])
        failed[label] = np.abs(values - truth).reshape(z.shape[:-1])
        if name == "optimal_fusion_set" and not options and members is None:
            members, members_fail = c.members, c.members.copy()
            members_fail[changed] = f.members[:changed.size]
    return clean, failed, members, members_fail


@derived_inputs()
def paired_study(
    seed: int,
    n_runs: int,
    methods: dict[str, dict[str, object]],
    sigma: ArrayLike = DEFAULT_SIGMAS,
    n_samples: int = 100,
    failure: dict[str, object] | None = None,
    truth: float = 900.0,
    n_sensors: int = 10,
    failure_mode: str = "fixed",
) -> PairedStudy:
    """The source's Figs. 2 and 4 repeated over ``n_runs`` draws, all comparisons paired.

    Draws ``n_runs`` runs once (as :func:`monte_carlo` with the same seed), fuses them with
    every method, then adds the failure of :func:`inject_failure` to the *same* draws and
    fuses again (Yang, Feng & Fan 2012, section 2, Figs. 1-4).

    Parameters
    ----------
    seed : int
        Seed of the :class:`numpy.random.Generator` (PCG64).
    n_runs : int
        Number of independent runs (>= 1).
    methods : dict
        Text label -> ``{"method": name, **options}``; must contain ``"optimal_fusion_set"``
        only if :attr:`PairedStudy.set_size` is to be meaningful (else it is NaN).
    sigma, n_samples, truth, n_sensors
        As in :func:`simulate`.
    failure : mapping, optional
        Keyword arguments of :func:`inject_failure`; default the source's failure
        (sensors 4 and 10, samples 50-80, biases 4 and 8 °C).
    failure_mode : {"fixed", "random size", "random samples", "opposite signs"}
        Reading of the source's "randomly" (:func:`random_failure`); the random part is drawn
        from the same generator after the readings, so the readings are the same for every mode.

    Returns
    -------
    PairedStudy
        Each method's per-run absolute errors without (``clean``) and with the failure (``failed``), the set's size and
        the failure window.
    """
    sigma = read_once(sigma, "sigma")  # a Sequence class read once (fuzz 31a C4)
    n_runs = count(n_runs, "n_runs")
    seed = check_seed(seed)
    methods = _check_methods(methods, lambda k: _methods_floor(
        n_runs * count(n_samples, "n_samples"), count(n_sensors, "n_sensors"), k,
        "n_runs, n_samples, n_sensors and methods", fusions=2, per_reading=_PAIRED_READING))
    failure = read_mapping(failure, "failure")
    instance_of(failure, (Mapping, type(None)), "failure")
    if failure is not None:  # keyword arguments of inject_failure: a misspelt key is refused by name
        record(failure, "failure", (), ("sensors", "samples", "biases"))
    failure_mode = one_of(failure_mode, FAILURE_MODES, "failure_mode")   # TypeError for a non-str (issue 35)
    # each entry read once, the same items injected and recorded (fuzz 42a C11: a Sequence giving (50, 80) and then
    # (1, 100) was injected on samples 50-80 and recorded as the window (1, 100), its member shares of other samples)
    fail = {k: read_once(v, k) for k, v in (failure or {}).items()}  # a list, tuple or array: fixed values
    # every method fuses the clean epochs, then the failed ones (those the failure changed: at most every epoch, 31 of
    # 100 samples by default), so two fusions a method; an optimal set with options only runs the default set for its
    # members (_paired_errors). Counted before the draws by monte_carlo's rules: simulate's memory, each method's
    # fuse_epochs limits (fix46: paired_study lacked them), their sum at their measured cost (fuzz 40a, the class).
    # The book's largest call, chapter 01's alpha study at the stability sweep's 10x runs (6 methods of 5,000 runs),
    # counts 7.0e8 units and ran 3.0 CPU-s; its 3 methods of 5,000 runs count 4.1e8 and ran 2.2 CPU-s.
    rows, n = n_runs * count(n_samples, "n_samples"), count(n_sensors, "n_sensors")
    allocation((rows, n), "n_runs, n_samples and n_sensors")
    fused = list(methods.values())
    if any(s["method"] == "optimal_fusion_set" for s in fused) and not any(
            s == {"method": "optimal_fusion_set"} for s in fused):
        fused.append({"method": "optimal_fusion_set"})
    _methods_work(rows, n, fused, "n_runs, n_samples, n_sensors and methods", fusions=2, per_reading=_PAIRED_READING)
    rng = np.random.default_rng(seed)
    z = simulate(rng, n_samples=n_samples, sigma=sigma, truth=truth, n_runs=n_runs, n_sensors=n_sensors)
    z_fail = random_failure(z, rng, failure_mode, **fail)  # type: ignore[arg-type]
    samples = tuple(fail.get("samples", (50, 80)))  # type: ignore[arg-type]
    sensors = tuple(fail.get("sensors", (4, 10)))  # type: ignore[arg-type]
    size = np.full(n_runs, np.nan)
    share: tuple[float, ...] = ()
    truth = scalar(truth, "truth")
    clean, failed, members, members_fail = _paired_errors(z, z_fail, methods, truth)
    if any(spec.get("method") == "optimal_fusion_set" for spec in methods.values()):
        if members is None:   # no optimal set with its default options among the methods: run it for its members
            members, members_fail = _paired_errors(z, z_fail, {"set": {"method": "optimal_fusion_set"}}, truth)[2:]
        size = members.sum(axis=1).reshape(n_runs, n_samples).mean(axis=1)
        fm = members_fail.reshape(z.shape)[:, int(samples[0]) - 1:int(samples[1])].reshape(-1, z.shape[-1])
        share = tuple(float(fm[:, int(k) - 1].mean()) for k in sensors)
    return PairedStudy(
        clean=clean,
        failed=failed,
        set_size=size,
        window=(int(samples[0]), int(samples[1])),
        seed=seed,
        failed_member_share=share,
        failure_mode=failure_mode,
        sigma=np.broadcast_to(np.asarray(sigma, dtype=float), z.shape[-1:]).copy(),   # as simulate read it
    )


def _window_relation(values: Mapping[str, object], cls: str) -> None:
    """The failure window (1-based, inclusive) lies within the samples of the errors."""
    first, last = values["window"]  # type: ignore[misc]
    samples = next(iter(values["clean"].values())).shape[1]  # type: ignore[attr-defined]
    if not first <= last <= samples:
        raise ValueError(f"{cls}.window must be (first, last) with 1 <= first <= last <= {samples} (the samples of "
                         f"{cls}.clean), got {shown((first, last))}")


def _scale_sweep_work(n_scales: int, n_runs: int, names: str) -> int:
    """Rule 17 of :func:`scale_sweep`: a fusion-set pass per scale, ``n_runs x 100 x 10 x 10`` units a scale (a loop
    step each), naming ``names``; its units (a chapter study that runs sweeps sums them, fuzz 54a C2)."""
    return loop_work((n_scales,), n_runs * 100 * 10 * 10, names)


@derived_inputs()
def scale_sweep(
    seed: int,
    n_runs: int,
    scales: ArrayLike,
    failure: dict[str, object] | None = None,
    sigma: ArrayLike = DEFAULT_SIGMAS,
    window: tuple[int, int] | None = None,
) -> FloatArray:
    r"""Per-run mean absolute error of the optimal fusion set for each scale of eq. 6.

    The same draws (one seed) serve every scale, so differences between scales are paired.

    Parameters
    ----------
    seed : int
    n_runs : int
    scales : array_like, shape (k,)
        Length scale of the fusion-degree function :math:`\exp(-|s_i - s_j|/\text{scale})`, °C
        (the source's factor 1/2 is scale 2).
    failure : mapping, optional
        Keyword arguments of :func:`inject_failure`, or None for no failure.
    sigma : array_like
        As in :func:`simulate`.
    window : (int, int), optional
        First and last 1-based sample averaged (e.g. the failure window 50-80); default all.

    Returns
    -------
    ndarray, shape (k, n_runs)
        Mean absolute error over the samples (all, or ``window``) of each run, °C.
    """
    scales = read_once(scales, "scales")  # converted once, then checked and used (fuzz 29a C5)
    as_array(scales, "scales", finite=False, nonempty=False)  # a TypeError naming scales for non-numbers
    instance_of(failure, (Mapping, type(None)), "failure")
    if failure is not None:  # keyword arguments of inject_failure: a misspelt key is refused by name
        record(failure, "failure", (), ("sensors", "samples", "biases"))
    grid = np.asarray(scales, dtype=float).ravel()
    if grid.size == 0 or np.any(~np.isfinite(grid)) or np.any(grid <= 0):
        raise ValueError("scales must be a non-empty array of positive numbers")
    check_magnitude(grid, "scales")
    n_runs_ = count(n_runs, "n_runs")
    _scale_sweep_work(grid.size, n_runs_, "scales and n_runs")
    methods = {f"s{k}": {"method": "optimal_fusion_set", "scale": float(s)} for k, s in enumerate(grid)}
    if window is None:
        e = monte_carlo(seed, n_runs, methods, sigma=sigma, failure=failure)
        return np.stack([e[f"s{k}"].mean(axis=1) for k in range(grid.size)])
    # only the window's epochs are fused: each epoch is fused on its own, so these are monte_carlo's errors on them
    z = _draws(seed, n_runs, methods, sigma, 100, failure, 900.0, 10)
    first, last = check_window(window, "window", z.shape[1], one_based=True)  # 1-based, inclusive (issue 35, class 4)
    e = absolute_errors(z[:, first - 1:last], methods)
    return np.stack([e[f"s{k}"].mean(axis=1) for k in range(grid.size)])
