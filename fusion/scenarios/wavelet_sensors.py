r"""The lecture notes' §2.6 reconstruction under its open choices: signal, threshold rule, wavelet, variance.

Case:
:math:`X_j = g_jS + e_j`, four sensors, gains g = (1, 1.5, 0.8, 2), noise SDs σ = (0.05, 0.1, 0.2, 0.4),
I = 1024 samples. The reconstruction is run for every Monte-Carlo run at once
(:func:`fusion.readings.wavelet.reconstruct` takes leading batch axes).

* :func:`measurand`, :data:`SIGNALS`: the measured signal S is an open choice (the lecture gives
  none; its application is a flowmeter): the chapter's two tones, one slow tone, a constant (a
  steady flow) and a piecewise-smooth Donoho-Johnstone test signal (HeaviSine).
* :func:`signal_study`: each signal × threshold rule × normaliser, with three metrics per run and
  sensor: the MSE against :math:`g_jS` (bias included), the **ensemble error variance** (the MSE
  minus the squared bias, bias = mean error over the runs at each sample) and the **temporal
  variance of the data** (the spread of the signal itself over time, what an experimenter can
  measure without knowing the truth; an error measure only for a constant measurand).
* :func:`mechanism_study`: with one signal, the **bias** of the denoised signals and its share of
  the MSE, the **cross-sensor correlation** of the relative errors :math:`(Y_j - g_jS)/g_j`, the
  energy of the bias curve by period, the two **orders** (denoise-then-fuse, the lecture's, and
  fuse-then-denoise) and the **sensitivity** to the wavelet family, depth, threshold rule and
  transform (:data:`CONFIGS`).
* :func:`variance_study`: the lecture's step 3, the variance "recursively by an MA model", under each
  reading of :data:`fusion.readings.wavelet.VARIANCES`, and oracle weights from the true noise.

References
----------
* Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
  *Biometrika*, 81(3), 425-455 (the HeaviSine test signal).
* Chang, S. G., Yu, B., & Vetterli, M. (2000). Adaptive wavelet thresholding for image
  denoising and compression. *IEEE Transactions on Image Processing*, 9(9), 1532-1546.
* Coifman, R. R., & Donoho, D. L. (1995). Translation-invariant de-noising. In *Wavelets and
  Statistics* (Lecture Notes in Statistics 103), 125-150. Springer.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from functools import partial
from typing import Any

import numpy as np
import pywt

from fusion._frozen import constant
from fusion._results import (NONNEGATIVE, ResultSpec, array, dict_of, instance, integer, number, same_keys, text,
                             tuple_of, validated_post_init)
from fusion._validation import derived_inputs, read_mapping, read_once, record, sequence, shown, within, seed as check_seed
from fusion._validation import MAX_MAGNITUDE, allocation, as_array, check_magnitude, count, derived, one_of
from fusion._validation import LOOP_STEP, count_ceiling, distinct, loop_work, seeds as check_seeds, work
from fusion.readings import wavelet as wv
from fusion.scenarios._wavelet_names import _SIGNAL_STEP, _names, _swt_level
from fusion.scenarios._wavelet_stats import _accumulate_rec, _error_stats  # noqa: F401 (tests read them here)
from fusion.scenarios._wavelet_relations import MECHANISM_ERRORS, cases_relation, configs_relation, seed_cases_relation

__all__ = ["CONFIGS", "Signal", "SIGNALS", "SignalStudy", "SeedStudy", "MechanismStudy", "VarianceStudy", "config_label",
           "measurand", "error_metrics", "signal_study", "seed_study", "mechanism_study", "variance_study"]

#: Wavelet settings of the sensitivity study; the first is the chapter's primary reading (db4, 4
#: levels, universal threshold, hard: the lecture's "remove the coefficients below the threshold").
CONFIGS: tuple[dict[str, Any], ...] = constant((
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard"},
    {"wavelet": "haar", "level": 4, "threshold": "universal", "mode": "hard"},
    {"wavelet": "sym8", "level": 4, "threshold": "universal", "mode": "hard"},
    {"wavelet": "coif3", "level": 4, "threshold": "universal", "mode": "hard"},
    {"wavelet": "db4", "level": 2, "threshold": "universal", "mode": "hard"},
    {"wavelet": "db4", "level": 6, "threshold": "universal", "mode": "hard"},
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "soft"},
    {"wavelet": "db4", "level": 4, "threshold": "bayes", "mode": "soft"},
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "hard", "transform": "swt"},
    {"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "soft", "transform": "swt"},
))

class Signal(StrEnum):
    """Keys of the measured signals of :func:`measurand` (:data:`SIGNALS`; labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    TWO_TONES
        Two tones, periods 256 and 64 samples (the chapter's default).
    SLOW
        The slower tone alone.
    CONSTANT
        A steady measurand.
    HEAVISINE
        Donoho and Johnstone's piecewise-smooth test signal.
    """

    TWO_TONES = "sig_two_tones"
    SLOW = "sig_slow"
    CONSTANT = "sig_constant"
    HEAVISINE = "sig_heavisine"


#: The measured signals S(n) of :func:`measurand` (key → formula); the first is the chapter's default.
SIGNALS: dict[Signal, str] = constant({
    Signal.TWO_TONES: "2 + sin(2πn/256) + 0.5 sin(2πn/64)",
    Signal.SLOW: "2 + sin(2πn/256)",
    Signal.CONSTANT: "2 (a steady flow)",
    Signal.HEAVISINE: "2 + HeaviSine(n/I)/4, HeaviSine(t) = 4 sin 4πt − sgn(t − 0.3) − sgn(0.72 − t)",
})

#: The keys of :data:`SIGNALS` as plain strings (what an error message lists).
_SIGNAL_KEYS: tuple[str, ...] = tuple(str(k) for k in SIGNALS)


def _signal(kind: object, name: str = "kind") -> Signal:
    """``kind`` as a :class:`Signal` (TypeError if not a string, ValueError naming ``name`` if not a key)."""
    return Signal(one_of(kind, _SIGNAL_KEYS, name))  # type: ignore[arg-type]


@dataclass(frozen=True)
class SignalStudy:
    r"""The lecture's reconstruction over signals, threshold rules and normalisers (:func:`signal_study`).

    Attributes
    ----------
    cases : mapping of (Signal, str, str) to mapping
        ``cases[(signal, mode, normaliser)]``: ``"raw"``, ``"denoised"``, ``"reconstructed"`` and (``"max"``)
        ``"fuse-first"``, each a dict of :func:`error_metrics` (arrays (runs, sensors)); ``"gain_err"`` (runs,
        sensors), the relative error of each normaliser against its value for the noise-free :math:`g_jS`;
        ``"weights"`` (runs, sensors); ``"example"``: run 0's ``denoised`` and ``reconstructed`` signals.
    truth, raw0 : mapping of Signal to ndarray, shape (sensors, I)
        Per signal: the noise-free :math:`g_jS` and run 0's raw signals.
    signals : tuple of Signal
        The signals run.
    modes, normalisers : tuple of str
        The options run.
    runs, seed, length : int
    gains, sigma : ndarray, shape (sensors,)
    """

    cases: Mapping[tuple[Signal, str, str], Mapping[str, Any]]
    truth: Mapping[Signal, np.ndarray]
    raw0: Mapping[Signal, np.ndarray]
    signals: tuple[Signal, ...]
    modes: tuple[str, ...]
    normalisers: tuple[str, ...]
    runs: int
    seed: int
    gains: np.ndarray
    sigma: np.ndarray
    length: int

    __result_spec__ = ResultSpec(
        {"cases": dict_of(dict_of(instance(Mapping, np.ndarray)), key=tuple),
         "truth": dict_of(array("sensors", "I")), "raw0": dict_of(array("sensors", "I")),
         "signals": tuple_of(instance(Signal)), "modes": tuple_of(text()), "normalisers": tuple_of(text()),
         "runs": integer(1, dim="runs"), "seed": integer(0), "gains": array("sensors", bounds=NONNEGATIVE),
         "sigma": array("sensors", bounds=NONNEGATIVE), "length": integer(1, dim="I")},
        relations=(same_keys("signals", "truth", "raw0"), cases_relation))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class SeedStudy:
    r"""One case of :func:`signal_study` under several seeds (:func:`seed_study`).

    Attributes
    ----------
    cases : mapping of int to mapping
        ``cases[seed]``: the case of :attr:`SignalStudy.cases` (``"raw"``, ``"denoised"``, ``"reconstructed"``, ...).
    seeds : tuple of int
    runs : int
    kind : Signal
    mode, normaliser : str
    """

    cases: Mapping[int, Mapping[str, Any]]
    seeds: tuple[int, ...]
    runs: int
    kind: Signal
    mode: str
    normaliser: str

    __result_spec__ = ResultSpec(
        {"cases": dict_of(dict_of(instance(Mapping, np.ndarray)), key=int), "seeds": tuple_of(integer(0)),
         "runs": integer(2), "kind": instance(Signal), "mode": text("hard", "soft"),
         "normaliser": text(*wv.NORMALISERS)},
        relations=(same_keys("seeds", "cases"), seed_cases_relation))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class MechanismStudy:
    r"""Bias, correlation, wavelet settings and the order of the steps (:func:`mechanism_study`).

    Attributes
    ----------
    labels : tuple of str
        One per config (:func:`config_label`).
    err, evar : mapping of str to mapping of str to ndarray, shape (runs, sensors)
        Per config label: per-run MSE against :math:`g_jS` and the ensemble error variance
        (:func:`error_metrics`) of ``raw``, ``denoised``, ``denoise-first`` and ``fuse-first``.
    stats : mapping of str to mapping
        Per config label: the bias and correlation measurements below under that config.
    bias_share, bias_share_rec : ndarray, shape (sensors,)
        Squared bias over MSE of each sensor's denoised signal and of its reconstruction (first config).
    corr, corr_random : ndarray, shape (sensors, sensors)
        Correlation of the denoised signals' relative errors pooled over runs and samples, and the same
        after removing each sensor's bias (first config).
    mean_offdiag_corr, mean_offdiag_corr_random : float
    bias_curve : ndarray, shape (sensors, length)
        The relative bias of each denoised signal (first config).
    rms_bias : ndarray, shape (sensors,)
        Its RMS along the signal.
    bias_spectrum : tuple of (float, float)
        (period in samples, share of the energy) of the three largest frequency bins of sensor 1's bias curve.
    bias_share_period : mapping of int to float
        Period → share at the periods 256 (when the length is a multiple of it) and 64 (always held).
    tone_bands : mapping of int to ndarray
        Period (256 and 64) → energy shares of a unit sine of that period in the bands (a_L, d_L, …, d_1) of the first
        config's transform.
    runs, seed : int
    gains, sigma : ndarray, shape (sensors,)
    configs : tuple of mapping
    kind : Signal
    """

    labels: tuple[str, ...]
    err: Mapping[str, Mapping[str, np.ndarray]]
    evar: Mapping[str, Mapping[str, np.ndarray]]
    stats: Mapping[str, Mapping[str, np.ndarray | float]]
    bias_share: np.ndarray
    bias_share_rec: np.ndarray
    corr: np.ndarray
    corr_random: np.ndarray
    mean_offdiag_corr: float
    mean_offdiag_corr_random: float
    bias_curve: np.ndarray
    rms_bias: np.ndarray
    bias_spectrum: tuple[tuple[float, float], ...]
    bias_share_period: Mapping[int, float]
    tone_bands: Mapping[int, np.ndarray]
    runs: int
    seed: int
    gains: np.ndarray
    sigma: np.ndarray
    configs: tuple[Mapping[str, Any], ...]
    kind: Signal

    __result_spec__ = ResultSpec(
        {"labels": tuple_of(text()),
         "err": dict_of(dict_of(array("runs", "sensors", bounds=NONNEGATIVE), required=MECHANISM_ERRORS)),
         "evar": dict_of(dict_of(array("runs", "sensors", bounds=NONNEGATIVE), required=MECHANISM_ERRORS[:3])),
         "stats": dict_of(dict_of(instance(np.ndarray, float, np.floating))),
         "bias_share": array("sensors", bounds=NONNEGATIVE), "bias_share_rec": array("sensors", bounds=NONNEGATIVE),
         "corr": array("sensors", "sensors"), "corr_random": array("sensors", "sensors"),
         "mean_offdiag_corr": number(nonnegative=False), "mean_offdiag_corr_random": number(nonnegative=False),
         "bias_curve": array("sensors", "I"), "rms_bias": array("sensors", bounds=NONNEGATIVE),
         "bias_spectrum": tuple_of(tuple_of(number(positive=True), number(bounds=(0.0, 1.0)))),
         "bias_share_period": dict_of(number(bounds=(0.0, 1.0)), key=int, required=(64,)),  # read by the glue
         "tone_bands": dict_of(array("bands", bounds=(0.0, 1.0)), key=int, required=(64, 256)),  # (fuzz 34b B5)
         "runs": integer(1, dim="runs"), "seed": integer(0), "gains": array("sensors", bounds=NONNEGATIVE),
         "sigma": array("sensors", bounds=NONNEGATIVE), "configs": tuple_of(instance(Mapping)),
         "kind": instance(Signal)},
        relations=(same_keys("labels", "err", "evar", "stats"), configs_relation))
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class VarianceStudy:
    r"""The lecture's step 3 under each reading of the variance of the weights (:func:`variance_study`).

    Attributes
    ----------
    readings : tuple of str
        The readings run, then ``"oracle"``.
    err, evar : mapping of str to ndarray, shape (runs, sensors)
        Per reading: per-run MSE of each sensor's reconstruction against :math:`g_jS`, and its ensemble
        error variance (:func:`error_metrics`).
    fused_mse : mapping of str to ndarray, shape (runs,)
        Per reading: per-run MSE of the fused normalised signal :math:`\hat Y` against :math:`S/\max S`.
    raw, raw_evar, denoised, denoised_evar : ndarray, shape (runs, sensors)
        The same metrics of the raw and the own denoised signals (every reading's).
    w_final : mapping of str to ndarray, shape (sensors,)
        Mean over runs of the weights at the last sample.
    w_spread : mapping of str to float
        Mean over runs of the SD along the signal of sensor 1's weight.
    w_true : ndarray, shape (sensors,)
        Inverse-variance weights of the true noise of the normalised noise-free signals,
        :math:`\propto (g_j/\sigma_j)^2`.
    window, runs, seed : int
    gains, sigma : ndarray, shape (sensors,)
    mode, normaliser : str
    """

    readings: tuple[str, ...]
    err: Mapping[str, np.ndarray]
    evar: Mapping[str, np.ndarray]
    fused_mse: Mapping[str, np.ndarray]
    raw: np.ndarray
    raw_evar: np.ndarray
    denoised: np.ndarray
    denoised_evar: np.ndarray
    w_final: Mapping[str, np.ndarray]
    w_spread: Mapping[str, float]
    w_true: np.ndarray
    window: int
    runs: int
    seed: int
    gains: np.ndarray
    sigma: np.ndarray
    mode: str
    normaliser: str

    __result_spec__ = ResultSpec(
        {"readings": tuple_of(text()), "err": dict_of(array("runs", "sensors", bounds=NONNEGATIVE)),
         "evar": dict_of(array("runs", "sensors", bounds=NONNEGATIVE)),
         "fused_mse": dict_of(array("runs", bounds=NONNEGATIVE)),
         "raw": array("runs", "sensors", bounds=NONNEGATIVE), "raw_evar": array("runs", "sensors", bounds=NONNEGATIVE),
         "denoised": array("runs", "sensors", bounds=NONNEGATIVE),
         "denoised_evar": array("runs", "sensors", bounds=NONNEGATIVE),
         "w_final": dict_of(array("sensors", bounds=(0.0, 1.0))), "w_spread": dict_of(number()),
         "w_true": array("sensors", bounds=(0.0, 1.0)), "window": integer(1), "runs": integer(1, dim="runs"),
         "seed": integer(0), "gains": array("sensors", bounds=NONNEGATIVE),
         "sigma": array("sensors", bounds=NONNEGATIVE),
         "mode": text(), "normaliser": text()},
        relations=(same_keys("readings", "err", "evar", "fused_mse", "w_final", "w_spread"),))
    __post_init__ = validated_post_init


def config_label(cfg: dict[str, Any]) -> str:
    """``"db4, 4 levels, universal hard"`` for a configuration of :data:`CONFIGS`.

    A configuration with ``"transform": "swt"`` is labelled ``"…, translation-invariant"``.

    Parameters
    ----------
    cfg : dict
        Keys ``wavelet``, ``level``, ``threshold``, ``mode`` and optionally ``transform``.

    Returns
    -------
    str
        ``"<wavelet>, <level> levels, <threshold> <mode>"``, with ``", translation-invariant"`` for the stationary
        transform.

    Raises
    ------
    TypeError
        ``cfg`` is not a mapping, or a value of the wrong type.
    ValueError
        A key is missing or unknown, ``level`` is not a positive integer, or an option is not one of ``denoise``'s
        (:func:`fusion.readings.wavelet.denoise`).
    """
    cfg = record(read_mapping(cfg, "cfg"), "cfg", ("wavelet", "level", "threshold", "mode"), ("transform",))
    for key in ("wavelet", "threshold", "mode", "transform"):
        if key in cfg and not isinstance(cfg[key], str):
            raise TypeError(f"cfg[{shown(key)}] must be a name (str), got {shown(cfg[key])}")
    kw = _kw(cfg)  # the plain texts (rule 19): a (str, Enum) member is labelled by its text, not its name
    level = count(cfg["level"], "cfg['level']")
    ti = ", translation-invariant" if kw["transform"] == "swt" else ""
    return f"{kw['wavelet']}, {level} levels, {kw['threshold']} {kw['mode']}{ti}"


def _kw(cfg: dict[str, Any]) -> dict[str, str | int]:
    """``denoise``'s keywords of a configuration: plain texts (rule 19), options checked here (fuzz 32a C5)."""
    wavelets = tuple(pywt.wavelist(kind="discrete"))
    return {"wavelet": one_of(cfg["wavelet"], wavelets, "cfg['wavelet']"), "level": cfg["level"],
            "threshold": one_of(cfg["threshold"], ("universal", "bayes"), "cfg['threshold']"),
            "mode": one_of(cfg["mode"], ("soft", "hard"), "cfg['mode']"),
            "transform": one_of(cfg.get("transform", "dwt"), ("dwt", "swt"), "cfg['transform']")}


def measurand(kind: Signal | str = Signal.TWO_TONES, length: int = 1024) -> np.ndarray:
    r"""A measured signal S(n), n = 0..length-1, of :data:`SIGNALS` (all positive, so that every normaliser exists).

    * :attr:`Signal.TWO_TONES`: :math:`2 + \sin(2\pi n/256) + 0.5\sin(2\pi n/64)`, exactly periodic over 1024
      samples (so periodisation adds no boundary error);
    * :attr:`Signal.SLOW`: :math:`2 + \sin(2\pi n/256)`, all its energy in the coarsest band of a 4-level db4
      transform;
    * :attr:`Signal.CONSTANT`: 2, a steady measurand (the lecture's application is a flowmeter);
    * :attr:`Signal.HEAVISINE`: :math:`2 + \mathrm{HeaviSine}(n/I)/4` with the test signal
      :math:`4\sin 4\pi t - \mathrm{sgn}(t - 0.3) - \mathrm{sgn}(0.72 - t)` of Donoho & Johnstone (1994),
      piecewise smooth with two jumps (values 0.5 to 3).

    Parameters
    ----------
    kind : Signal or str
        A key of :data:`SIGNALS` (a :class:`Signal`, or its value).
    length : int
        Number of samples I (>= 16).

    Returns
    -------
    ndarray, shape (length,)
        S(0), ..., S(length − 1) of the signal ``kind``, all positive.

    Raises
    ------
    ValueError
        Unknown ``kind`` or ``length`` below 16.

    References
    ----------
    * Donoho, D. L., & Johnstone, I. M. (1994). Ideal spatial adaptation by wavelet shrinkage.
      *Biometrika*, 81(3), 425-455.
    """
    kind = _signal(kind)
    n = np.arange(count(length, "length", minimum=16))
    if kind is Signal.TWO_TONES:
        return 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64)
    if kind is Signal.SLOW:
        return 2 + np.sin(2 * np.pi * n / 256)
    if kind is Signal.CONSTANT:
        return np.full(n.size, 2.0)
    t = n / n.size
    return 2 + (4 * np.sin(4 * np.pi * t) - np.sign(t - 0.3) - np.sign(0.72 - t)) / 4


def error_metrics(est: np.ndarray, truth: np.ndarray) -> dict[str, np.ndarray]:
    r"""Per-run, per-sensor error metrics of signals against the truth, along the last axis.

    With the error :math:`e_{rj}(n) = \hat Y_{rj}(n) - g_jS(n)` of run r and sensor j, and its mean over
    the runs :math:`b_j(n)` (the bias at sample n):

    * ``"mse"``: :math:`\overline{e_{rj}^2}` over the samples (bias included);
    * ``"evar"``: :math:`\overline{(e_{rj} - b_j)^2}`, the ensemble error variance (bias excluded; its
      mean over runs is the MSE minus the mean squared bias);
    * ``"tvar"``: the temporal variance :math:`\overline{\hat Y_{rj}^2} - \bar{\hat Y}_{rj}^2` of the data
      themselves (what can be measured without the truth; an error measure only when S is constant).

    Parameters
    ----------
    est : ndarray, shape (runs, n, I)
        Estimated (or raw) signals; at least two runs.
    truth : ndarray, shape (n, I)
        True signals :math:`g_jS`.

    Returns
    -------
    dict of str to ndarray, each shape (runs, n)
        ``"mse"``, ``"evar"`` and ``"tvar"`` → entry (r, j): that metric of run r's signal of sensor j.

    Raises
    ------
    ValueError
        Shapes that do not match, fewer than two runs or non-finite values.
    """
    E = as_array(est, "est", ndim=3)
    T = as_array(truth, "truth", ndim=2)
    if E.shape[1:] != T.shape or E.shape[0] < 2:
        raise ValueError(f"est must be (runs >= 2, {T.shape[0]}, {T.shape[1]}) to match truth, got {E.shape}")
    return _stream_metrics(partial(_stored, "est", E), T, _blocks(E.shape[0], T.size))["est"]


def _stream_metrics(produce: Any, truth: np.ndarray, blocks: list[slice], each: Any = None,
                    evar: tuple[str, ...] | bool = True, tvar: bool = True) -> dict[str, dict[str, np.ndarray]]:
    """:func:`error_metrics` of estimates produced block by block (the ensemble variance in a second pass).

    ``produce(sl, keys)`` returns a dict name → estimates of the runs ``sl`` (shape (runs in sl, n, I)),
    every estimate it makes when ``keys`` is None, else those named; nothing of size (runs, n, I) is kept.
    The ensemble error variance needs the bias, the mean error over *every* run, so the estimates named in
    ``evar`` (all of them for ``True``, none for ``False``) are kept from the first pass when they fit in
    :data:`_KEEP_BYTES`, else produced a second time; the others have no
    ``"evar"``, and without ``tvar`` none has ``"tvar"``. ``each(sl, estimates)``, if given, is called once
    per block in the first pass.
    """
    runs, size = blocks[-1].stop, truth.shape[-1]
    sums: dict[str, np.ndarray] = {}
    out: dict[str, dict[str, np.ndarray]] = {}
    want: set[str] | None = None if evar is True else set(evar or ())
    kept: dict[str, np.ndarray] = {}     # the first pass's estimates for the second, when they fit in _KEEP_BYTES
    for sl in blocks:
        est = produce(sl, None)
        if each is not None:
            each(sl, est)
        for k, E in est.items():
            if (want is None or k in want) and runs * E[0].nbytes * max(1, len(want or est)) <= _KEEP_BYTES:
                if k not in kept:
                    kept[k] = np.empty((runs, *E.shape[1:]))
                kept[k][sl] = E
        for k, E in est.items():
            if k not in out:
                if want is None:
                    want_k = True
                else:
                    want_k = k in want
                out[k] = {"mse": np.empty((runs, truth.shape[0]))}
                if want_k:
                    out[k]["evar"] = np.empty((runs, truth.shape[0]))
                    sums[k] = np.zeros(truth.shape)
                if tvar:
                    out[k]["tvar"] = np.empty((runs, truth.shape[0]))
            e = E - truth
            if k in sums:
                sums[k] += e.sum(axis=0)
            out[k]["mse"][sl] = np.einsum("rjn,rjn->rj", e, e) / size
            if tvar:
                out[k]["tvar"][sl] = E.var(axis=-1)
    if sums:
        bias = {k: v / runs for k, v in sums.items()}
        for sl in blocks:
            again = tuple(k for k in sums if k not in kept)
            est = {k: kept[k][sl] for k in sums if k in kept}
            if again:
                est |= produce(sl, again)
            for k, E in est.items():
                e = E - truth - bias[k]
                out[k]["evar"][sl] = np.einsum("rjn,rjn->rj", e, e) / size
    return out


def _case_arrays(length: int, runs: int, gains: Sequence[float], sigma: Sequence[float], seed: int,
                 kind: Signal | str = Signal.TWO_TONES, weight: int = 0, configs: list[dict[str, Any]] | tuple = (),
                 readings: int = 0) -> tuple[np.ndarray, ...]:
    runs = count(runs, "runs", minimum=2)
    g = as_array(gains, "gains", ndim=1)
    sig = as_array(sigma, "sigma", ndim=1)
    if g.size < 2 or np.any(g <= 0):
        raise ValueError(f"gains must hold >= 2 positive gains, got {g}")
    if g.size > count_ceiling("sensors"):  # rule 9: one gain per sensor, a count of sensors is a dimension
        raise ValueError(f"gains holds {g.size} sensors, beyond the ceiling of a count of dimension "
                         f"({count_ceiling('sensors'):,}; fusion._validation.COUNT_CEILINGS)")
    if sig.shape != g.shape or np.any(sig <= 0):
        raise ValueError(f"sigma must hold {g.size} positive SDs (one per entry of gains), got {sig}")
    seed = check_seed(seed)
    S = measurand(kind, length)
    allocation((runs, g.size, S.size), "runs, gains and length")  # the memory budget, before the noise is drawn
    if weight:  # rule 17: the caller's work at ``weight`` units a sample (variance_study: 690,000 runs, ~31 CPU-s, ran)
        if readings:  # and each of its readings' passes, summed (variance_study, fuzz 42a C14)
            N = runs * g.size * S.size
            work((weight * N + readings * (_READING_STEP + _READING_SAMPLE * N),), "readings, runs, gains and length")
        else:
            work((runs, g.size, S.size), "runs, gains and length", weight=weight)
    if configs:  # rule 17 (fuzz 35a D3): mechanism_study's loop over its settings, at their measured cost
        units = loop_work((len(configs),), _MECH_SAMPLE * runs * g.size * S.size, "configs, runs, gains and length",
                          step=_MECH_STEP)
        for i, c in enumerate(configs):  # each config read, then each stationary one's transforms counted, all blocks
            with within(f"configs[{i}]"):  # and both orders (fuzz 61b C2), before the draw
                config_label(c)
                # the level read once, counted and run (fuzz 62b C6: int() gave 1 to the budget, __index__ 8 to the
                # run): the caller's list holds the copy with the int read
                configs[i] = {**c, "level": count(c["level"], "cfg['level']")}
            _swt_level(configs[i], S.size, f"configs[{i}]")  # its 2**level divides length (fix71a)
        calls, nm = 2 * len(_blocks(runs, g.size * S.size)), "configs (levels, wavelets), runs, gains and length"
        swt = [(c["level"], _kw(c)["wavelet"]) for c in configs if _kw(c)["transform"] == "swt"]
        work((units + sum(wv._swt_work(runs * (g.size + 1), S.size, lv, w, nm, calls) for lv, w in swt),), nm)
    noise = np.random.default_rng(seed).normal(size=(runs, g.size, S.size))
    noise *= sig[:, None]                                   # in place: the same numbers, one array fewer
    truth = g[:, None] * S
    with derived("gains and sigma", "sensor signals g*S + noise"):  # each factor valid, the product may not be
        check_magnitude(truth, "g*S")
        check_magnitude(noise, "the noise")
        if float(np.abs(truth).max()) + float(np.abs(noise).max()) > MAX_MAGNITUDE:
            raise ValueError(f"g*S + noise may exceed {MAX_MAGNITUDE:g} in magnitude")
    return g, sig, S, truth, noise


#: Units of one setting of :func:`mechanism_study` (its loop step: the denoising, both orders' metrics and the error
#: statistics, ~0.57 ms measured at length 64) and of one sample of a setting (~0.06-0.1 us measured at length 1024,
#: 100-2,000 runs): 60,000 runs (~250 CPU-s) and 10**6 settings (~12 min) were accepted (fuzz 35a D3).
_MECH_STEP, _MECH_SAMPLE = 60 * LOOP_STEP, 10
#: Units of :func:`variance_study`: 10 a sample for its denoising and reference metrics, and per reading (the oracle
#: too) a step and 4 units a sample (fuzz 42a C14: the readings were not counted; 450,000 of 2 runs x 64 samples were
#: accepted and ran 46.2 CPU-s). Measured (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two calls,
#: machine shared): 93 us a reading of 2 runs x 2 sensors x 64 samples (2,000 readings); at 100 runs x 4 x 1,024 a
#: reading 1.0 ("equal"), 3.1, 5.6, 7.6 and 9.8 ("window") units a sample, at 1,000 runs 1.2 ("batch"); the whole
#: default call (5 readings, 300 and 1,000 runs) 19.7 and 14.4 units a sample, counted 34.
_READING_STEP, _READING_SAMPLE = 10 * LOOP_STEP, 4


def _blocks(runs: int, per_run: int) -> list[slice]:
    """Slices of runs whose arrays stay small (about 2 MB): the studies run block by block into reused buffers."""
    step = max(1, _BLOCK_SAMPLES // per_run)
    return [slice(i, min(i + step, runs)) for i in range(0, runs, step)]


#: Largest size (bytes) of the estimates :func:`_stream_metrics` keeps from its first pass for the ensemble variance,
#: instead of producing them a second time (the same numbers either way).
_KEEP_BYTES = 64 << 20

#: Samples per block of :func:`_blocks` (the same numbers as one run at a time, without the page faults of
#: fresh 30-MB arrays at every step).
_BLOCK_SAMPLES = 1 << 18


def _fuse_first(X: np.ndarray, rec: wv.Reconstruction, kw: dict[str, Any]) -> np.ndarray:
    """The fuse-first reconstruction from a denoise-first one (same constant weights and normalisers).

    Equals ``wv.reconstruct(X, order="fuse-first", **kw).reconstructed`` for constant weights (the
    batch variance) without denoising every sensor a second time.
    """
    dkw = {k: kw[k] for k in ("wavelet", "level", "mode", "threshold", "transform") if k in kw}
    fused = wv.denoise(np.einsum("...j,...jn->...n", rec.weights, X / rec.norms[..., None]), **dkw)
    return fused[..., None, :] * rec.norms[..., None]


def _norm_ref(normaliser: str, truth: np.ndarray, g: np.ndarray) -> np.ndarray:
    """The normaliser of the noise-free signals g_jS (what each normaliser estimates)."""
    if normaliser in ("max", "max-raw"):
        return truth.max(axis=-1)
    if normaliser == "median":
        return np.median(truth, axis=-1)
    return g / g[0]


@derived_inputs()
def signal_study(
    signals: Sequence[Signal | str] = tuple(SIGNALS),
    modes: Sequence[str] = ("hard", "soft"),
    normalisers: Sequence[str] = ("max", "median"),
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
    wavelet: str = "db4",
    level: int = 4,
    threshold: str = "universal",
) -> SignalStudy:
    r"""The §2.6 reconstruction for each signal, threshold rule and normaliser, with three error metrics.

    The same noise for every case (one seed; more runs extend the same stream, so the first 100 runs
    of 1000 are those of 100). For each case: the raw signals, every sensor's own denoised signal, the
    lecture's reconstruction and (for the lecture's formula, ``"max"``) the reconstruction in the other
    order (fuse the normalised raw signals, then denoise), each measured by
    :func:`error_metrics` (MSE, ensemble error variance, temporal variance of the data). Every sensor is
    denoised once per signal and rule, and the normalisers fuse the same denoised signals.

    Parameters
    ----------
    signals : sequence of Signal or str
        Keys of :data:`SIGNALS` (:class:`Signal` members or their values).
    modes : sequence of {"hard", "soft"}
        Threshold rules.
    normalisers : sequence of {"max", "max-raw", "median", "lsq"}
        Normalisers of :func:`fusion.readings.wavelet.reconstruct` (``"max"``: the maximum of the denoised
        signal, ``"max-raw"``: of the raw measurements; ``"max"`` gets the fuse-first order too).
    length, runs : int
        Samples per signal I (>= 16) and Monte-Carlo runs (>= 2).
    gains, sigma : sequence of float
        Sensor gains and noise SDs (> 0, same length).
    seed : int
        Seed of the noise.
    wavelet, level, threshold
        Wavelet setting (:func:`fusion.readings.wavelet.denoise`).

    Returns
    -------
    SignalStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Bad lengths, values or option names, or empty option lists; a study beyond the work budget
        (``fusion._validation.MAX_WORK``: signals x modes x (normalisers + 1) steps of 60,000 units and 20 a run,
        sensor and sample); a repeated signal, mode or normaliser (the cases are keyed by them).
    """
    gains = read_once(gains, "gains")  # a Sequence class read once (fuzz 31a C4)
    # the lists read are what is counted and run (fuzz 42a C14), counted by their lengths before any name is read
    # (fuzz 62b C5: 10**7 modes were each checked first, refused after 10.3 CPU-s)
    signals, modes, normalisers = (sequence(v, k) for v, k in ((signals, "signals"), (modes, "modes"),
                                                               (normalisers, "normalisers")))
    # rule 17, before any draw: runs x sensors x samples a case, ~20 vectorised operations each, in _SIGNAL_STEP steps
    n_gains = len(sequence(gains, "gains"))
    runs_, length_ = count(runs, "runs", minimum=2), count(length, "length")
    runs, length = runs_, length_  # the ints read, never the caller's objects (fuzz 29a C2)
    level = count(level, "level")  # its ceiling before the work budget: a bad level is named whatever the counts
    loop_work((len(signals), len(modes), len(normalisers) + 1), 20 * runs_ * max(n_gains, 1) * length_,
              "signals, modes, normalisers, runs, gains and length", step=_SIGNAL_STEP)
    signals = _names(signals, "signals", _SIGNAL_KEYS)
    modes, normalisers = _names(modes, "modes", ("hard", "soft")), _names(normalisers, "normalisers", wv.NORMALISERS)
    distinct(signals, "signals"), distinct(modes, "modes"), distinct(normalisers, "normalisers")  # keys (64b C8)
    # every wavelet option (level against length included) checked on one noise-free signal, before the noise
    signals = [Signal(v) for v in signals]          # the cases are keyed by the signals' keys
    wv.denoise(measurand(signals[0], length_)[None], wavelet=wavelet, level=level, threshold=threshold, mode=modes[0])
    g, sig, _, _, noise = _case_arrays(length, runs, gains, sigma, seed)
    R_, n, size = noise.shape
    blocks = _blocks(R_, n * size)
    den = np.empty_like(noise)                      # every sensor denoised once per signal and rule
    cases: dict[tuple[Signal, str, str], dict[str, Any]] = {}
    truths, raw0 = {}, {}
    for kind in signals:
        truth = g[:, None] * measurand(kind, length)
        truths[kind], raw0[kind] = truth, truth + noise[0]
        flat = bool(np.all(np.ptp(truth, axis=-1) == 0.0))   # the spread over time measures error only for a constant
        raw = _stream_metrics(partial(_raw, truth=truth, noise=noise), truth, blocks, tvar=flat)["raw"]
        for mode in modes:
            dkw = {"wavelet": wavelet, "level": level, "threshold": threshold, "mode": mode}
            for sl in blocks:
                den[sl] = wv.denoise(truth + noise[sl], **dkw)
            den_m = _stream_metrics(partial(_stored, "denoised", den), truth, blocks, tvar=flat)["denoised"]
            for nm in normalisers:
                keep = {"norms": np.empty((R_, n)), "weights": np.empty((R_, n))}
                lecture = nm in ("max", "max-raw")          # the lecture's normalisers: every metric
                met = _stream_metrics(partial(_fused, truth=truth, noise=noise, den=den, normaliser=nm, dkw=dkw,
                                              fuse_first=nm == "max", keep=keep), truth, blocks,
                                      evar=("reconstructed",) if lecture else False, tvar=flat)
                case = {"raw": raw, "denoised": den_m, **met,
                        "gain_err": keep["norms"] / _norm_ref(nm, truth, g) - 1, "weights": keep["weights"],
                        "example": {"denoised": den[0].copy(), "reconstructed": keep["rec0"]}}
                cases[kind, mode, nm] = case
    return SignalStudy(cases=cases, truth=truths, raw0=raw0, signals=list(signals), modes=list(modes),
                       normalisers=list(normalisers), runs=int(runs), seed=int(seed), gains=g, sigma=sig,
                       length=int(length))


def _raw(sl: slice, keys: tuple[str, ...] | None, truth: np.ndarray, noise: np.ndarray) -> dict[str, np.ndarray]:
    return {"raw": truth + noise[sl]}


def _stored(name: str, arr: np.ndarray, sl: slice, keys: tuple[str, ...] | None = None) -> dict[str, np.ndarray]:
    return {name: arr[sl]}


def _fused(sl: slice, keys: tuple[str, ...] | None, truth: np.ndarray, noise: np.ndarray, den: np.ndarray,
           normaliser: str, dkw: dict[str, Any], fuse_first: bool,
           keep: dict[str, np.ndarray] | None) -> dict[str, np.ndarray]:
    """The lecture's reconstruction (and, with ``fuse_first``, the fuse-first one) of the runs ``sl``.

    From the stored denoised signals (validated inputs: the private kernel of
    :func:`fusion.readings.wavelet.fuse_denoised`); ``keep`` (if given) receives the normalisers, the weights
    and run 0's reconstruction; ``keys`` (if given) names the estimates wanted.
    """
    X = truth + noise[sl]
    part = wv._fuse(X, den[sl], normaliser, "batch", 64)
    if keep is not None and keys is None:
        keep["norms"][sl], keep["weights"][sl] = part.norms, part.weights
        if sl.start == 0:
            keep["rec0"] = part.reconstructed[0].copy()
    out = {}
    if keys is None or "reconstructed" in keys:
        out["reconstructed"] = part.reconstructed
    if fuse_first and (keys is None or "fuse-first" in keys):
        out["fuse-first"] = _fuse_first(X, part, dkw)
    return out


def seed_study(
    seeds: Sequence[int] = (2602, 2603, 2604, 2605),
    runs: int = 1000,
    kind: Signal | str = Signal.TWO_TONES,
    mode: str = "hard",
    normaliser: str = "max",
    **kwargs: Any,
) -> SeedStudy:
    r"""One case of :func:`signal_study` under several seeds: does its verdict depend on the noise drawn?

    Parameters
    ----------
    seeds : sequence of int
        Seeds of the noise (>= 0, at least one, no two equal: the cases are keyed by seed).
    runs : int
        Runs per seed (>= 2).
    kind : Signal or str
        The signal, a key of :data:`SIGNALS`.
    mode, normaliser : str
        The case's threshold rule and normaliser.
    **kwargs
        Other arguments of :func:`signal_study` (gains, sigma, length, wavelet, level, threshold).

    Returns
    -------
    SeedStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        An empty ``seeds``, a negative or repeated seed, more seeds x runs x length x gains than the work
        budget (``fusion._validation.MAX_WORK``), or bad arguments of :func:`signal_study`.
    """
    sv = check_seeds(seeds, "seeds")  # a non-empty list, tuple or 1-D array of seeds
    runs_ = count(runs, "runs", minimum=2)
    n_gains = len(sequence(kwargs.get("gains", (1,) * 4), "gains"))
    # rule 17: a signal_study a seed, 40 units a sample (1 was: 127-186 ns measured at 100 runs x 1,024 x 4 gains, 1,409
    # seeds accepted, ~75 CPU-s) and 300 LOOP_STEP (2.2-2.7 ms at 2 x 64 x 2; process_time, least of 2, shared machine)
    per_seed = 40 * runs_ * count(kwargs.get("length", 1024), "length") * n_gains
    loop_work((len(sv),), per_seed, "seeds, runs, length and gains", step=300 * LOOP_STEP)
    distinct(sv, "seeds")  # the cases are keyed by seed: a repeated seed would collapse two of them (after the budget)
    kind = _signal(kind)
    mode = one_of(mode, ("hard", "soft"), "mode")
    normaliser = one_of(normaliser, wv.NORMALISERS, "normaliser")
    cases = {v: signal_study(signals=(kind,), modes=(mode,), normalisers=(normaliser,), runs=runs, seed=v,
                             **kwargs).cases[kind, mode, normaliser] for v in sv}
    return SeedStudy(cases=cases, seeds=tuple(sv), runs=int(runs), kind=kind, mode=mode, normaliser=normaliser)


def _weighted(sl: slice, keys: tuple[str, ...] | None, truth: np.ndarray, noise: np.ndarray, den: np.ndarray,
              reading: str, window: int, sigma: np.ndarray, ref: np.ndarray,
              keep: dict[str, np.ndarray], normaliser: str = "max") -> dict[str, np.ndarray]:
    """The lecture's reconstruction of the runs ``sl`` with the weights of one reading of step 3 (or the oracle).

    The oracle uses the normalisers that an earlier reading stored in ``keep["norms"]`` (every reading
    normalises by the same maxima).
    """
    if reading == "oracle":
        nrm = keep["norms"][sl]
        w = (nrm / sigma) ** 2
        w = w / w.sum(axis=-1, keepdims=True)
        fused = np.einsum("rj,rjn->rn", w, den[sl] / nrm[..., None])
        rec = fused[:, None, :] * nrm[..., None]
        keep["weights"][sl], keep["spread"][sl] = w, 0.0
    else:
        part = wv._fuse(truth + noise[sl], den[sl], normaliser, reading, window)
        fused, rec = part.fused, part.reconstructed
        keep["norms"][sl], keep["weights"][sl] = part.norms, part.weights
        w1 = part.weight_path[:, 0, :]
        keep["spread"][sl] = np.std(w1 - w1[:, -1:], axis=-1)              # exactly 0 for constant weights
    keep["fused_mse"][sl] = np.mean((fused - ref) ** 2, axis=-1)
    return {"rec": rec}


def _orders(sl: slice, keys: tuple[str, ...] | None, truth: np.ndarray, noise: np.ndarray, den: np.ndarray,
            kw: dict[str, Any]) -> dict[str, np.ndarray]:
    """Both orders' reconstructions (maximum normaliser) of the runs ``sl`` from the stored denoised signals."""
    X = truth + noise[sl]
    part = wv._fuse(X, den[sl], "max", "batch", 64)
    out = {}
    if keys is None or "denoise-first" in keys:
        out["denoise-first"] = part.reconstructed
    if keys is None or "fuse-first" in keys:
        out["fuse-first"] = _fuse_first(X, part, kw)
    return out


def _band_shares(x: np.ndarray, wavelet: str, level: int) -> np.ndarray:
    """Share of the energy of ``x`` in each band of its decimated transform, (a_L, d_L, ..., d_1)."""
    from fusion.readings.wavelet import _wavedec_periodic   # pywt.wavedec's values without its depth warning

    c = _wavedec_periodic(np.asarray(x, dtype=float), wavelet, int(level))
    e = np.array([np.sum(v**2) for v in c])
    return e / e.sum()


def mechanism_study(
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
    configs: Sequence[dict[str, Any]] = CONFIGS,
    kind: Signal | str = Signal.TWO_TONES,
) -> MechanismStudy:
    r"""Bias, cross-sensor error correlation, order and wavelet choices of the §2.6 reconstruction.

    Parameters
    ----------
    length : int
        Samples per signal I: a multiple of 64 (>= 64), since the bias's share at the tone's period 64
        (``bias_share_period``) is read over whole periods; other lengths are refused naming ``length``.
    runs : int
        Monte-Carlo runs (>= 2).
    gains : sequence of float
        Sensor gains :math:`g_j` (> 0).
    sigma : sequence of float
        Noise SD of each sensor (> 0), same length as ``gains``.
    seed : int
        Seed of the noise (as :func:`signal_study`).
    configs : sequence of dict
        Wavelet settings (keys ``wavelet``, ``level``, ``threshold``, ``mode``, optionally
        ``transform``); the first is the reference of the bias and correlation measurements.
    kind : Signal or str
        The signal, a key of :data:`SIGNALS`.

    Returns
    -------
    MechanismStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Bad lengths or values (``length`` not a multiple of 64), an empty ``configs``, a config with unknown options
        or an unknown ``kind``; ``configs``, ``runs``, ``gains`` and ``length`` asking for more work than the budget
        (``fusion._validation.MAX_WORK``, about 10 CPU-s).
    """
    kind = _signal(kind)
    if count(length, "length", minimum=64) % 64:  # fuzz 35a D1: bias_share_period[64] needs whole periods of 64
        raise ValueError("length must be a multiple of 64 (the bias's share at the tone's period 64, "
                         f"MechanismStudy.bias_share_period, needs whole periods), got {int(length)}")
    # the list sequence() reads is what is counted and iterated, each config read once (fuzz 42a C12: a len() true on
    # its first call and 1 after counted 600 configs as 1, 35.2 CPU-s)
    # its length counted first, a setting's step (fuzz 62b: 10**7 configs were each read first)
    items = sequence(configs, "configs")
    loop_work((len(items),), 0, "configs, runs, gains and length", step=_MECH_STEP)
    configs = [read_mapping(c, f"configs[{i}]") for i, c in enumerate(items)]
    if not configs:
        raise ValueError("configs must be a non-empty sequence of dicts")
    g, sig, S, truth, noise = _case_arrays(length, runs, gains, sigma, seed, kind, configs=configs)
    R_, n, size = noise.shape
    blocks = _blocks(R_, n * size)
    raw = _stream_metrics(partial(_raw, truth=truth, noise=noise), truth, blocks, tvar=False)["raw"]
    den = np.empty_like(noise)                                         # reused by every setting
    labels, err, evar, stats = [], {}, {}, {}
    for cfg in configs:
        kw = _kw(cfg)
        lab = config_label(cfg)
        labels.append(lab)
        for sl in blocks:
            den[sl] = wv.denoise(truth + noise[sl], **kw)
        acc = {"sum": np.zeros(truth.shape), "sq": np.zeros(n)}
        met = {"raw": raw, **_stream_metrics(partial(_stored, "denoised", den), truth, blocks, tvar=False),
               **_stream_metrics(partial(_orders, truth=truth, noise=noise, den=den, kw=kw), truth, blocks,
                                 each=partial(_accumulate_rec, truth=truth, g=g, acc=acc), evar=("denoise-first",),
                                 tvar=False)}
        err[lab] = {k: v["mse"] for k, v in met.items()}
        evar[lab] = {k: v["evar"] for k, v in met.items() if "evar" in v}
        stats[lab] = _error_stats(den, acc, truth, g, blocks)
    first = stats[labels[0]]
    F = np.abs(np.fft.rfft(first["bias_curve"][0])) ** 2
    F = F / F.sum() if F.sum() > 0 else F
    top = np.argsort(F[1:])[::-1][:3] + 1
    n = np.arange(S.size)
    cfg0 = configs[0]
    return MechanismStudy(
        labels=labels, err=err, evar=evar, stats=stats, **{k: first[k] for k in (
            "bias_share", "bias_share_rec", "corr", "corr_random", "mean_offdiag_corr",
            "mean_offdiag_corr_random", "bias_curve", "rms_bias")},
        bias_spectrum=[(S.size / int(k), float(F[k])) for k in top],
        bias_share_period={p: float(F[S.size // p]) for p in (256, 64) if S.size % p == 0 and S.size // p < F.size},
        tone_bands={p: _band_shares(np.sin(2 * np.pi * n / p), cfg0["wavelet"], cfg0["level"]) for p in (256, 64)},
        runs=int(runs), seed=int(seed), gains=g, sigma=sig, kind=kind,
        configs=[{k: v if k == "level" else _kw(c)[k] for k, v in c.items()} for c in configs])  # plain texts


def variance_study(
    length: int = 1024,
    runs: int = 100,
    gains: Sequence[float] = (1.0, 1.5, 0.8, 2.0),
    sigma: Sequence[float] = (0.05, 0.1, 0.2, 0.4),
    seed: int = 2601,
    window: int = 64,
    readings: Sequence[str] = wv.VARIANCES,
    mode: str = "hard",
    normaliser: str = "max",
) -> VarianceStudy:
    r"""The §2.6 reconstruction under each reading of its step 3 (the variance behind the weights).

    The lecture estimates each sensor's variance "recursively by an MA model"; the readings are
    those of :func:`fusion.readings.wavelet.variance_estimates` (db4, 4 levels, universal threshold,
    rule ``mode``; maximum normaliser; the lecture's order). A last reading, ``"oracle"``, weights
    the normalised denoised signals by the true noise, :math:`W_j \propto (\mathrm{norm}_j/\sigma_j)^2`
    (not available in practice: it shows what a perfect variance estimate would give). Same case and
    noise as :func:`mechanism_study` (same seed).

    Parameters
    ----------
    length, runs : int
        Samples per signal I (>= 16) and Monte-Carlo runs (>= 2).
    gains, sigma : sequence of float
        Sensor gains and noise SDs (> 0, same length).
    seed : int
        Seed of the noise.
    window : int
        Window of the moving-average reading (>= 2 samples).
    readings : sequence of str
        Readings of :data:`fusion.readings.wavelet.VARIANCES`, the first the reference.
    mode : {"hard", "soft"}
        Threshold rule.
    normaliser : {"max", "max-raw"}
        The maximum of each sensor's denoised signal (the default) or of its raw measurements.

    Returns
    -------
    VarianceStudy
        See the class's attributes.

    Raises
    ------
    ValueError
        Bad lengths or values, an empty or unknown ``readings``, an unknown ``mode``; the draws and every reading's
        pass beyond the work budget (10 units a sample, and 4 a sample and 10,000 a reading, the oracle too:
        measured), naming readings, runs, gains and length, before any draw.
    """
    readings = sequence(readings, "readings")  # read once; its length bounded by a reading's step before its names
    loop_work((len(readings),), 0, "readings", step=_READING_STEP)
    readings = _names(readings, "readings", wv.VARIANCES)  # counted below, each reading and the oracle
    g, sig, S, truth, noise = _case_arrays(length, runs, gains, sigma, seed, weight=10, readings=len(readings) + 1)
    window = count(window, "window", minimum=2)
    mode, normaliser = one_of(mode, ("hard", "soft"), "mode"), one_of(normaliser, ("max", "max-raw"), "normaliser")
    R_, n, size = noise.shape
    blocks = _blocks(R_, n * size)
    den = np.empty_like(noise)
    for sl in blocks:                                   # every reading fuses the same denoised signals
        den[sl] = wv.denoise(truth + noise[sl], level=4, mode=mode)
    ref = S / S.max()                                   # what the fused normalised signal estimates (max normaliser)
    err: dict[str, np.ndarray] = {}
    evar: dict[str, np.ndarray] = {}
    fused_mse: dict[str, np.ndarray] = {}
    w_final: dict[str, np.ndarray] = {}
    w_spread: dict[str, float] = {}
    norms = np.empty((R_, n))
    for r in list(readings) + ["oracle"]:
        keep = {"weights": np.empty((R_, n)), "spread": np.empty(R_), "fused_mse": np.empty(R_), "norms": norms}
        met = _stream_metrics(partial(_weighted, truth=truth, noise=noise, den=den, reading=r, window=window,
                                      sigma=sig, ref=ref, keep=keep, normaliser=normaliser), truth, blocks,
                              tvar=False)["rec"]
        err[r], evar[r], fused_mse[r] = met["mse"], met["evar"], keep["fused_mse"]
        w_final[r], w_spread[r] = keep["weights"].mean(axis=0), float(np.mean(keep["spread"]))
    w_true = (g / sig) ** 2 / np.sum((g / sig) ** 2)
    den_m = _stream_metrics(partial(_stored, "den", den), truth, blocks, tvar=False)["den"]
    raw = _stream_metrics(partial(_raw, truth=truth, noise=noise), truth, blocks, tvar=False)["raw"]
    return VarianceStudy(readings=list(readings) + ["oracle"], err=err, evar=evar, fused_mse=fused_mse, raw=raw["mse"],
                         raw_evar=raw["evar"], denoised=den_m["mse"], denoised_evar=den_m["evar"],
                         w_final=w_final, w_spread=w_spread, w_true=w_true, window=int(window), runs=int(runs),
                         seed=int(seed), gains=g, sigma=sig, mode=mode, normaliser=normaliser)
