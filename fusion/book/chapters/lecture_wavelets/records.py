r"""Chapter 03's studies (cached) and the evidence functions of its records of ``book/claims/lecture003.yaml``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, TypeAlias

import numpy as np

from fusion._frozen import constant
from fusion.book.study_cache import study_cache
from fusion._validation import count, instance_of, mapping_of, one_of, read_mapping
from fusion.book import rulebook as R
from fusion.book.chapters.lecture import evidence_at, reading_function, reading_key
from fusion.book._few_runs import runs_first, runs_named
from fusion.book.ledger import Comparison, Conjunction, Evidence
from fusion.book.chapters.lecture_wavelets.verdicts import PRIMARY, _q
from fusion.book.chapters.lecture_wavelets.variance import _vconj, _weighting
from fusion.book.chapters.lecture_wavelets.mechanism import _wconj
from fusion.scenarios.wavelet_sensors import MechanismStudy, Signal, SignalStudy, VarianceStudy
from fusion.book.glue import GlueValues
from fusion._counts import seed as check_seed
from fusion._shown import shown

__all__ = [
    "CONFIG_KEYS", "SIGNAL_KEYS", "VARIANCE_READINGS", "STUDIES", "SEED", "RUNS", "N_RUNS", "study",
    "COMMON_READINGS", "ev_wavelet_better", "ev_wavelet_accurate", "ev_wavelet_fusion_helps",
    "ev_wavelet_weighting", "EVIDENCE", "evidence", "ledger_values",
]


#: Reading key of each wavelet setting of the mechanism study that the signal table does not already run.
CONFIG_KEYS: dict[str, str] = constant({
    "haar, 4 levels, universal hard": "cfg-haar", "sym8, 4 levels, universal hard": "cfg-sym8",
    "coif3, 4 levels, universal hard": "cfg-coif3", "db4, 2 levels, universal hard": "cfg-level-2",
    "db4, 6 levels, universal hard": "cfg-level-6", "db4, 4 levels, bayes soft": "cfg-bayes-soft",
    "db4, 4 levels, universal hard, translation-invariant": "cfg-ti-hard",
    "db4, 4 levels, universal soft, translation-invariant": "cfg-ti-soft",
})


#: Reading keys of the signal × rule cells (the primary cell excluded): ``sig_two_tones`` and ``soft`` give
#: ``sig-two-tones-soft`` (the claim file's keys, from the signals' keys, not their labels).
SIGNAL_KEYS: dict[tuple[Signal, str], str] = constant({(k, m): f"{k.value.replace('_', '-')}-{m}" for k in Signal
                                              for m in ("hard", "soft") if (k, m) != PRIMARY[:2]})


#: Readings of step 3 (the variance of the weights) run as readings.
VARIANCE_READINGS: tuple[str, ...] = ("running", "window", "measurement")


#: The studies the evidence functions take: ``sg`` (signal table, every reading's run count), ``m26``, ``v26``,
#: ``g1`` (equal gains), ``v1`` and ``v1r`` (the variance study on equal gains, the denoised and the raw maximum) with
#: the same runs; ``e26`` (E2.6, more runs of the same noise stream).
STUDIES: tuple[str, ...] = ("sg", "m26", "v26", "g1", "e26", "v1", "v1r")

#: One of the chapter's studies (:func:`study`).
ChapterStudy: TypeAlias = "SignalStudy | MechanismStudy | VarianceStudy"


#: The type of each study of :data:`STUDIES` (what :func:`study` returns for the key).
_STUDY_TYPES: dict[str, type] = {"sg": SignalStudy, "m26": MechanismStudy, "v26": VarianceStudy, "g1": SignalStudy,
                                 "e26": SignalStudy, "v1": VarianceStudy, "v1r": VarianceStudy}


#: The setup each key's study records that tells it from the same-type studies of the other keys (:func:`study`'s
#: recipe): equal gains (``g1``, ``v1``, ``v1r``) or the scenario's unequal ones, and a variance study's normaliser
#: (``v1`` and ``v1r`` differ there only). A signal study's normalisers are not compared: a reader takes one with
#: those it reads (E2.6 with the maximum only).
_SETUPS: dict[str, tuple[bool, str | None]] = {
    "sg": (False, None), "g1": (True, None), "e26": (False, None), "v26": (False, "max"), "v1": (True, "max"),
    "v1r": (True, "max-raw")}


def _setup(s: ChapterStudy, normaliser: str | None) -> tuple[bool, str | None]:
    """The setup ``s`` records, as :data:`_SETUPS` states it (its normaliser only where the key's is stated)."""
    equal = bool(np.all(np.asarray(s.gains) == np.asarray(s.gains)[0]))
    return equal, (None if normaliser is None else str(s.normaliser))


def _need(st: Mapping[str, ChapterStudy]) -> int:
    """The common run count of the readings (that of the signal table); ValueError if a study is missing or has fewer,
    TypeError (the shared rule ``mapping_of``) if ``st`` is not a mapping or a study not of its key's type;
    ValueError naming ``st[key]`` for a study whose recorded setup is not its key's (:data:`_SETUPS`; fuzz 33b D5:
    the equal-gains study under ``v26`` changed four records)."""
    if not isinstance(st, Mapping) or st:  # an empty mapping is reported below by the studies it lacks
        mapping_of(st, "st", "study", maker="study")
    missing = [k for k in STUDIES if st.get(k) is None]
    if missing:
        raise ValueError(f"st must hold the studies {missing}")
    for k in STUDIES:  # each key's study of its own type (another study's runs would be read silently)
        instance_of(st[k], _STUDY_TYPES[k], f"st[{k!r}]")
    for k, want in _SETUPS.items():  # the swaps rule (decisions of the swaps work): the key's recorded setup
        got = _setup(st[k], want[1])
        if got != want:
            def said(v: tuple[bool, str | None]) -> str:
                return f"{'equal' if v[0] else 'unequal'} gains" + ("" if v[1] is None else f", normaliser {shown(v[1])}")
            raise ValueError(f"st[{shown(k)}] must be study({shown(k)}) ({said(want)}), got a study of {said(got)}")
    runs = int(st["sg"].runs)
    short = [k for k in ("m26", "v26", "g1", "v1", "v1r") if int(st[k].runs) < runs]
    if short:
        raise ValueError(f"st: the studies {short} have fewer runs than the signal table's {runs}")
    return runs


#: Seed of every study of chapter 03 (the scenarios' default).
SEED = 2601


#: Run count of each study of the chapter (:func:`study`): every reading's 300, E2.6's 2000 (the ``more-runs``
#: reading, whose claim-file entry states its runs).
RUNS: dict[str, int] = constant({"sg": 300, "m26": 300, "v26": 300, "g1": 300, "e26": 2000, "v1": 300, "v1r": 300})


#: The records' run count (the ledger's ``runs``): the default of the evidence functions.
N_RUNS = 300


def study(key: str, seed: int = SEED, runs: int | None = None) -> ChapterStudy:
    """One study of the chapter (a key of :data:`STUDIES`) at ``seed`` and ``runs``, cached.

    ``sg``: the signal table (every signal and rule; normalisers max, max-raw, median); ``m26``: the mechanism
    study; ``v26``: the variance study (window 64); ``g1``: equal gains (normalisers max and max-raw); ``v1``, ``v1r``:
    the variance study on equal gains with the maximum of the denoised (``v1``) and of the raw signal (``v1r``);
    ``e26``: E2.6 (normalisers max, median, lsq). At :data:`SEED` and the runs of :data:`RUNS` they are the chapter's own.

    Parameters
    ----------
    key : str
        A key of :data:`STUDIES`.
    seed : int
    runs : int, optional
        Default: the chapter's (:data:`RUNS`).

    Returns
    -------
    SignalStudy or MechanismStudy or VarianceStudy
        The output of :mod:`fusion.scenarios.wavelet_sensors`'s study function (the same object on every call
        with the same arguments: do not modify it).
    """
    seed = check_seed(seed)
    key = one_of(key, tuple(RUNS), "key")
    return _study(key, seed, int(RUNS[key] if runs is None else count(runs, "runs")))


@study_cache(maxsize=12)
def _study(key: str, seed: int, runs: int) -> ChapterStudy:
    from fusion.scenarios import wavelet_sensors as ws

    one = {"signals": (PRIMARY[0],), "modes": (PRIMARY[1],), "runs": runs, "seed": seed}
    if key == "sg":
        return ws.signal_study(normalisers=("max", "max-raw", "median"), runs=runs, seed=seed)
    if key == "m26":
        return ws.mechanism_study(runs=runs, seed=seed)
    if key == "v26":
        return ws.variance_study(window=64, runs=runs, seed=seed)
    if key == "g1":
        return ws.signal_study(normalisers=("max", "max-raw"), gains=(1, 1, 1, 1), **one)
    if key in ("v1", "v1r"):
        return ws.variance_study(window=64, runs=runs, seed=seed, gains=(1, 1, 1, 1),
                                 normaliser="max" if key == "v1" else "max-raw")
    return ws.signal_study(normalisers=("max", "median", "lsq"), **one)


_SIGNAL_CELLS = {v: k for k, v in SIGNAL_KEYS.items()}


_CONFIG_LABELS = {v: k for k, v in CONFIG_KEYS.items()}


#: Reading keys common to the three accuracy records (signals × rules, the raw maximum, equal gains, the wavelet
#: settings, step 3's variances, E2.6's extra runs), in the claim file's order.
COMMON_READINGS: tuple[str, ...] = (("book-model",) + tuple(SIGNAL_KEYS.values()) + ("raw-max", "lecture-raw-max")
                                    + tuple(CONFIG_KEYS.values())
                                    + tuple(f"var-{r}" for r in VARIANCE_READINGS) + ("more-runs",))


#: The accuracy records: record id → (a, b, metric) of their comparison, and their own extra reading.
_ACCURACY: dict[str, tuple[tuple[str, str, str], tuple[str, str, tuple[str, str, str]] | None]] = {
    "lec-wavelet-better": (("reconstructed", "raw", "evar"), ("temporal-variance", "tvar", (Signal.CONSTANT, "hard", "max"))),
    "lec-wavelet-accurate": (("reconstructed", "raw", "mse"), None),
    "lec-wavelet-fusion-helps": (("reconstructed", "denoised", "mse"), ("metric-evar", "evar", PRIMARY)),
}


_Get = Callable[[str], Any]


def _accuracy_reading(rid: str, key: str, get: _Get) -> Conjunction:
    """One reading of an accuracy record; ``get`` gives a study by its key (of :data:`STUDIES`)."""
    (a, b, metric), extra = _ACCURACY[rid]
    if extra is not None and key == extra[0]:
        return _q(get("sg"), extra[2], a, b, extra[1])
    if key == "primary":  # the lecture's model Xⱼ = S + eⱼ and its formula: this set's (the denoised Yⱼ's) maximum
        return _q(get("g1"), PRIMARY, a, b, metric)
    if key == "book-model":  # the book's gains (1, 1.5, 0.8, 2) and the denoised maximum (the former primary)
        return _q(get("sg"), PRIMARY, a, b, metric)
    if key in _SIGNAL_CELLS:
        return _q(get("sg"), (*_SIGNAL_CELLS[key], "max"), a, b, metric)
    if key == "raw-max":
        return _q(get("sg"), (PRIMARY[0], PRIMARY[1], "max-raw"), a, b, metric)
    if key == "lecture-raw-max":  # the lecture's model with the maximum of the raw measurements
        return _q(get("g1"), (PRIMARY[0], PRIMARY[1], "max-raw"), a, b, metric)
    if key in _CONFIG_LABELS:
        return _wconj(get("m26"), _CONFIG_LABELS[key], "denoise-first" if a == "reconstructed" else a, b, metric)
    if key.startswith("var-") and key[4:] in VARIANCE_READINGS:
        return _vconj(get("v26"), key[4:], b, metric)
    if key == "more-runs":
        return _q(get("e26"), PRIMARY, a, b, metric)
    raise ValueError(f"settings: record {rid} has no reading {shown(key)}")


def _weighting_reading(key: str, get: _Get) -> Comparison | Conjunction:
    """One reading of ``lec-wavelet-weighting``: the fused Ŷ with inverse-variance weights against equal weights.

    The primary and ``every-sensor`` run the lecture's model (equal gains, the denoised maximum: ``v1``);
    ``book-model`` the book's gains (``v26``), ``lecture-raw-max`` equal gains with the raw maximum (``v1r``); the
    step-3 variance readings vary the book model, like those of the accuracy records.
    """
    if key == "primary":
        return _weighting(get("v1"))
    if key == "every-sensor":
        return _vconj(get("v1"), "batch", "equal-weights")
    if key == "book-model":
        return _weighting(get("v26"))
    if key == "lecture-raw-max":
        return _weighting(get("v1r"))
    if key.startswith("var-") and key[4:] in VARIANCE_READINGS:
        return _weighting(get("v26"), key[4:])
    raise ValueError(f"settings: record lec-wavelet-weighting has no reading {shown(key)}")


def _reading(rid: str, key: str, get: _Get) -> Comparison | Conjunction:
    return _weighting_reading(key, get) if rid == "lec-wavelet-weighting" else _accuracy_reading(rid, key, get)


def _keys(rid: str) -> tuple[str, ...]:
    """Every reading key of a record, ``"primary"`` first (the claim file's)."""
    if rid == "lec-wavelet-weighting":
        return ("primary", "every-sensor", "book-model", "lecture-raw-max") + tuple(f"var-{r}" for r in VARIANCE_READINGS)
    extra = _ACCURACY[rid][1]
    return ("primary",) + COMMON_READINGS + ((extra[0],) if extra else ())


def _at(rid: str, settings: Mapping[str, Any], seed: int, runs: int) -> Comparison | Conjunction:
    """Reading ``settings["reading"]`` of ``rid`` on the studies at ``seed`` and ``runs`` (:func:`study`)."""
    key = reading_key(settings)
    if key in _keys(rid):  # every reading compares ``runs`` paired runs without a reason: rule R4's refusal before the
        runs = runs_first(runs)  # studies, after the reading is named (fuzz 57c; reading_function's runs_named names it)
    return _reading(rid, key, lambda k: study(k, seed, runs))


def _reader(rid: str, summary: str, seed_runs: str = "The studies' seed and run count (:func:`study`).",
            returns: str = "Conjunction") -> Callable[..., Comparison | Conjunction]:
    """The evidence function of record ``rid``, ``fn(settings, *, seed=SEED, runs=N_RUNS)``: reading
    ``settings["reading"]`` of the record on the studies at ``seed`` and ``runs`` (:func:`_at`;
    :func:`fusion.book.chapters.lecture.reading_function`)."""
    return reading_function(__name__, rid, _at, SEED, N_RUNS, summary, seed_runs, returns)


ev_wavelet_better = _reader(
    "lec-wavelet-better", "every reconstruction's error variance below its raw data's.",
    "The studies' seed and run count (:func:`study`; the ``more-runs`` reading is E2.6 at ``runs``).")
ev_wavelet_accurate = _reader("lec-wavelet-accurate", "every reconstruction's MSE below its raw data's.")
ev_wavelet_fusion_helps = _reader(
    "lec-wavelet-fusion-helps", "every reconstruction's MSE below the sensor's own denoised signal's.")
ev_wavelet_weighting = _reader(
    "lec-wavelet-weighting", "the fused Ŷ with inverse-variance weights against equal weights.",
    "The variance study's seed and run count (:func:`study`).", "Comparison or Conjunction")


#: Record id → evidence function of chapter 03 (the ``evidence`` field of each record names the same function).
EVIDENCE = constant({"lec-wavelet-better": ev_wavelet_better, "lec-wavelet-accurate": ev_wavelet_accurate,
            "lec-wavelet-fusion-helps": ev_wavelet_fusion_helps, "lec-wavelet-weighting": ev_wavelet_weighting})


def evidence(st: Mapping[str, ChapterStudy] | None = None, seed: int | None = None) -> dict[str, dict[str, Evidence]]:
    """Every record's evidence of chapter 03, by record id (for :func:`fusion.book.claims.build_ledger`).

    With ``seed``, every reading through its record's evidence function (:func:`fusion.book.chapters.lecture.evidence_at`:
    the functions the reseeding sweep calls) at that seed and the chapter's runs; the chapter passes :data:`SEED`,
    so the studies are those it computed with :func:`study` (cached). Without it, from the studies ``st``.

    Parameters
    ----------
    st : mapping of str to study, optional
        The studies, keys :data:`STUDIES` (any run counts; those of ``m26``, ``v26`` and ``g1`` at least
        ``sg``'s). Required without ``seed``. They need not share a seed (fuzz 26d DB4, documented): every reading
        pairs the runs of one study, none pairs runs across studies, so each reading's evidence is that of its own
        study, at its seed (the chapter's are all :data:`SEED`).
    seed : int, optional

    Returns
    -------
    dict
        Record id → {reading key → evidence}.

    Raises
    ------
    TypeError
        ``st`` not a mapping of studies, ``seed`` not an integer.
    ValueError
        ``st`` lacking a study, or one of fewer runs than rule R4's 100 (its paired comparisons), naming ``st``.
    """
    seed = None if seed is None else check_seed(seed)
    if seed is not None:
        return evidence_at({rid: N_RUNS for rid in EVIDENCE}, seed)
    _need(st or {})
    assert st is not None
    with runs_named("st", "study(key, seed, runs) at more runs"):   # fuzz 29b B6: named "a and b" and "reason"
        return {rid: {k: _reading(rid, k, st.__getitem__) for k in _keys(rid)} for rid in EVIDENCE}


def ledger_values(st: Mapping[str, ChapterStudy]) -> GlueValues:
    """The computed numbers the claim texts of chapter 03 quote (keys ``lec_wled_*``), also glued.

    Parameters
    ----------
    st : mapping of str to study
        The chapter's studies, keys :data:`STUDIES`; of any seeds, as in :func:`evidence` (each value is read from
        its own study).

    Returns
    -------
    GlueValues
        See the summary line.

    Raises
    ------
    TypeError
        ``st`` not a mapping, or a study not of its key's type (``sg``, ``g1`` and ``e26`` SignalStudy, ``m26``
        MechanismStudy, ``v26``, ``v1`` and ``v1r`` VarianceStudy).
    ValueError
        ``st`` without one of :data:`STUDIES`, or a study with fewer runs than ``sg``.
    """
    st = read_mapping(st, "st")   # read once: the studies checked are the ones read (decision 31a C2)
    runs = _need(st)
    n = int(np.asarray(st["sg"].gains).size)
    # a claim about every sensor is contradicted if one sensor's interval lies wholly above 0: with no difference at
    # all, each does so with probability (1 − level)/2, so the group with probability 1 − (1 − (1 − level)/2)^n
    fwer = 1.0 - (1.0 - (1.0 - R.CONFIDENCE_LEVEL) / 2.0) ** n
    # the weights' exponent (illegible): the fused noise variance Σ Wⱼ²σⱼ² under Wⱼ ∝ σⱼ^(−p), p = 2 (the minimum,
    # what the lecture's 'least mean square' fusion asks for) and p = 1
    sig = np.asarray(st["sg"].sigma, dtype=float)
    fused = {p: float(np.sum((sig ** -p / np.sum(sig ** -p)) ** 2 * sig ** 2)) for p in (1, 2)}
    return {"lec_wled_runs": runs, "lec_wled_e26_runs": int(st["e26"].runs), "lec_wled_fwer": round(fwer, 3),
            "lec_wled_sensors": n, "lec_wled_fvar_p2": round(1e4 * fused[2], 2), "lec_wled_fvar_p1": round(1e4 * fused[1], 2),
            "lec_wled_fvar_ratio": round(fused[1] / fused[2], 3)}
