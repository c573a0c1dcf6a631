"""Fuzz 37b (chapter layer, issue 35): a damaged study-cache entry (C1, D1), glue_27's self-check at the edge of
correlated_study (C5), huge JSON integers (C4), process-global warning filters (C2) and warnings from valid calls (C3,
D2). Chapter registries are not imported here: each test builds only what it needs."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from fusion.book import study_cache as sc

_CALLS: list = []


@sc.study_cache(maxsize=4)
def _study(seed: int) -> tuple:
    """Module-level: only a function its module holds under its name reaches the disk (fuzz 34a D2)."""
    _CALLS.append(seed)
    return _expected(seed)


def _expected(seed: int) -> tuple:
    return (seed, np.arange(float(seed)), "x" * 300, b"y" * 300)


def _stored_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, seed: int = 5) -> Path:
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    _study.cache_clear()
    _CALLS.clear()
    _study(seed)
    (entry,) = tmp_path.glob("*.pkl")
    _study.cache_clear()
    return entry


def _same(a: tuple, b: tuple) -> bool:
    return pickle.dumps(a) == pickle.dumps(b)


@pytest.mark.parametrize("at", [9, 10])
def test_a_damaged_frame_length_of_a_stored_entry_is_a_miss(at: int, tmp_path: Path,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    """C1: one flipped high bit of a stored entry's frame length (bytes 3-10 after ``0x80 0x05 0x95``) made pickle ask
    for petabytes: a raw MemoryError from every later call. It is a miss: computed again, equal, the entry rewritten."""
    entry = _stored_once(tmp_path, monkeypatch)
    good = entry.read_bytes()
    assert good[sc._DIGEST:sc._DIGEST + 3] == b"\x80\x05\x95"   # the pickle, after its digest (fuzz 40b C3)
    damaged = bytearray(good)
    damaged[sc._DIGEST + at] ^= 0x40
    entry.write_bytes(bytes(damaged))
    value = _study(5)
    assert _CALLS == [5, 5] and _same(value, _expected(5))
    assert entry.read_bytes() == good                   # rewritten
    _study.cache_clear()
    assert _same(_study(5), value) and _CALLS == [5, 5]   # loaded


def test_a_directory_in_place_of_an_entry_or_its_lock_returns_the_result_unstored(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """D1: a directory at ``<key>.pkl`` raised IsADirectoryError after the computation (the result lost), one at
    ``<key>.lock`` before it. Decided: the entry is a miss that cannot be written; the result is returned unstored,
    as without the disk (documented in the module)."""
    entry = _stored_once(tmp_path, monkeypatch)
    entry.unlink()
    entry.mkdir()
    assert _same(_study(5), _expected(5)) and _CALLS == [5, 5]
    assert entry.is_dir() and not list(tmp_path.glob(".*.tmp"))     # no temporary file left behind
    _study.cache_clear()
    entry.rmdir()
    lock = entry.with_suffix(".lock")
    lock.unlink()
    lock.mkdir()
    assert _same(_study(5), _expected(5)) and _CALLS == [5, 5, 5]
    assert not entry.exists()


# --- C5: glue_27's solver self-check on every study correlated_study accepts ------------------------------------------

@settings(max_examples=25, deadline=None)
@example(sigma=[1e-4, 2e-4], sigma_env=1e3)                        # the report's case: cond(R) = 8e13
@example(sigma=[1e-3, 2e-3, 3e-3], sigma_env=1e3)                  # cond(R) ~ 4e12, 3 sensors
@given(sigma=st.lists(st.floats(-6, 1).map(lambda e: 10.0 ** e), min_size=1, max_size=4),
       sigma_env=st.floats(-3, 4).map(lambda e: 10.0 ** e))
def test_glue_27_checks_every_study_correlated_study_accepts(sigma: list[float], sigma_env: float) -> None:
    """C5 (regression of fuzz 36b B4's capped tolerance): cond(R) from ~4e12 up to the positive-definite limit (~3e14)
    raised RuntimeError in glue_27's self-check. Decided: correlated_study refuses cond(R) or sigma_env²/min(sigma²) above MAX_COND = 1e11 naming
    sigma and sigma_env (GLS's own round-off eps cond(R) would reach the 4 digits glued); below it the check holds."""
    from fusion.book.chapters.lecture_correlated import correlated as co
    from fusion.scenarios import lecture_correlated as lsc

    try:
        s = lsc.correlated_study(runs=20, sigma=sigma, sigma_env=sigma_env)
    except ValueError as exc:
        assert "sigma" in str(exc) and ("condition number" in str(exc) or "positive definite" in str(exc))
        return
    assert np.linalg.cond(s.R) <= 1.01 * lsc.MAX_COND
    assert co.glue_27(s)["lec_cor_runs"] == 20


def test_glue_27_names_s_for_an_r_beyond_the_limit_built_otherwise() -> None:
    """A study carrying an R beyond correlated_study's limit (built by hand) is refused naming ``s``, not a RuntimeError
    of the self-check."""
    import dataclasses

    from fusion.book.chapters.lecture_correlated import correlated as co
    from fusion.scenarios import lecture_correlated as lsc

    s = lsc.correlated_study(runs=20, sigma=(1.0, 2.0))
    for sig, env in (((1e-4, 2e-4), 1e3), ((1.0, 1e-6), 1e3)):   # cond(R) 8e13; cond 4e6 but R lost the 1e-12
        sig = np.array(sig)
        R = np.kron(np.diag(sig**2), np.eye(2)) + env**2 * np.kron(np.ones((2, 2)), np.eye(2))
        with pytest.raises(ValueError, match=r"^s must have an R with a condition number"):
            co.glue_27(dataclasses.replace(s, R=R))


# --- C4: integers beyond a float's range in the book's JSON files -------------------------------------------------

def test_benchmark_cost_names_path_for_an_integer_beyond_a_float(tmp_path: Path) -> None:
    """C4: a measurement ``value`` of 10**400 (a JSON integer, 401 digits) raised OverflowError in the check
    ``math.isfinite(v)``. The one JSON reader refuses integers beyond a float's range at decode time, naming the file."""
    import json

    from fusion.book.chapters.chernoff import swarm

    src = json.loads((Path(__file__).resolve().parents[1] / "benchmarks/results/chernoff.json").read_text())
    for m in src["measurements"]:
        if m.get("stage") == "em":
            m["value"] = 10**400
    path = tmp_path / "bench.json"
    path.write_text(json.dumps(src))
    with pytest.raises(ValueError, match=r"bench\.json.*401 digits overflows a float"):
        swarm.benchmark_cost(path)


@pytest.mark.parametrize("sign", ["", "-"])
def test_json_document_keeps_integers_a_float_holds_and_refuses_the_rest(sign: str) -> None:
    import sys

    from fusion._paths import json_document

    top = int(sys.float_info.max)
    assert json_document(f"[{sign}{top + 1}, {sign}{10**308}, {sign}12]", "f") == [int(f"{sign}{v}") for v in
                                                                                  (top + 1, 10**308, 12)]
    for bad in (2 * top, 10**309, 10**4000):
        with pytest.raises(ValueError, match=r"^f: an integer of \d+ digits overflows a float"):
            json_document(f"{{\"a\": [{sign}{bad}]}}", "f")


# --- C2: no process-global warning filter in the package --------------------------------------------------------------

def test_the_package_sets_no_warning_filter() -> None:
    """C2 (fuzz 24a W's rule): ``warnings.catch_warnings`` / ``simplefilter`` / ``filterwarnings`` change process-global
    state; three threads in ``ir_ratio`` left its two "ignore" filters in ``warnings.filters`` for good."""
    import re

    root = Path(__file__).resolve().parents[1] / "fusion"
    call = re.compile(r"^\s*(with\s+)?(warnings|_?w)\.(catch_warnings|simplefilter|filterwarnings|resetwarnings)\(|"
                      r"^\s*from warnings import", re.M)
    found = [str(p.relative_to(root)) for p in sorted(root.rglob("*.py")) if call.search(p.read_text(encoding="utf-8"))]
    assert not found, found


def _rmse(runs: int, seed: int = 0) -> np.ndarray:
    return np.abs(np.random.default_rng(seed).normal(1, 0.3, size=(runs, 4)))


def test_ir_ratio_warns_nothing_and_refuses_every_undefined_interval_by_name() -> None:
    """C2/C3: without its warning filter, ``ir_ratio`` emits no warning under the caller's ``simplefilter("error")``,
    on valid runs or on degenerate ones (refused by name), and leaves ``warnings.filters`` as it found them. Decided:
    a resample holding only zero x errors is refused wherever it is among the 2000 (as documented; before, one outside
    the interval's quantiles passed with an infinite resampled ratio)."""
    import warnings

    from fusion.book.chapters.ci import infrared_readings as ir

    ok = ir.ir_ratio(_rmse(40), 1)
    x_zero = _rmse(6, 3)
    x_zero[:2, 2] = 0                     # 2 of 6 runs without x error: a few of 2000 resamples hold no x error
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        before = list(warnings.filters)
        assert ir.ir_ratio(_rmse(40), 1) == ok
        for bad in (np.ones((10, 4)), _rmse(10) * [1, 1, 1, 0], x_zero):
            with pytest.raises(ValueError, match="run_rmse: the bootstrap interval of the ratio is undefined"):
                ir.ir_ratio(bad, 1)
        assert warnings.filters == before


# --- C3: valid calls emit no third-party warning (a caller's simplefilter("error")) -----------------------------------

def test_valid_calls_emit_no_warning_under_the_callers_error_filter() -> None:
    """C3: ``length_study(64, runs=3)`` (documented ``length >= 16``) raised pywt's UserWarning "Level value of 4 is
    too high"; ``mean_only_status(a, a + 0.5)`` (a constant paired difference) and ``architecture``'s interval of
    differences equal up to round-off raised scipy's "Precision loss" RuntimeWarning."""
    import warnings

    from fusion.book.chapters.ci import architecture
    from fusion.book.chapters.lecture_wavelets import appendix, e26

    a = np.array([1.0, 2.0, 3.0, 4.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert e26.mean_only_status(a, a + 0.5) == "reproduced"
        assert appendix.length_study(64, runs=3).length == 64
        assert architecture._mean_ci(np.array([0.3, 0.1 + 0.2, 0.3, 0.1 + 0.2])) == (np.mean([0.3, 0.1 + 0.2] * 2), 0.0)


@settings(max_examples=40, deadline=None)
@example(base=1.0, n=2, seed=0, spread=1e-14)                        # scipy warns at 10 eps of the mean, any n
@given(base=st.floats(-1e6, 1e6, allow_subnormal=False), n=st.integers(2, 30), seed=st.integers(0, 2**16),
       spread=st.sampled_from([0.0, 1e-18, 1e-16, 1e-15, 3e-15, 1e-14, 1e-3, 1.0]))
def test_t_intervals_warn_nothing_and_equal_scipy_where_scipy_does_not_warn(base: float, n: int, seed: int,
                                                                           spread: float) -> None:
    """The shared rule (``fusion.book._t_interval``): data constant to round-off give the zero-width interval at their
    mean and a test decided by the mean's side, without a warning; all other data scipy's numbers bit for bit."""
    import warnings

    from scipy import stats

    from fusion.book import _t_interval as ti

    x = base + spread * max(abs(base), 1.0) * np.random.default_rng(seed).normal(size=n)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        ref = stats.ttest_1samp(x, 0.0).confidence_interval(0.95)
        p_ref = stats.ttest_1samp(x, base + 1.0, alternative="less").pvalue
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got, p = ti.mean_interval(x, 0.95), ti.t_pvalue(x, base + 1.0, "less")
    if any(issubclass(w.category, RuntimeWarning) for w in seen):
        assert got == (float(x.mean()), float(x.mean())) and p == (0.0 if x.mean() < base + 1.0 else 1.0)
    else:
        assert got == (float(ref.low), float(ref.high)) and p == float(p_ref)


@pytest.mark.parametrize("wavelet", ["db4", "haar", "coif3"])
def test_the_wavelet_transform_equals_pywt_at_every_depth_without_its_warning(wavelet: str) -> None:
    """C3's pywt site, in the main package: ``denoise``'s decimated transform is ``pywt.wavedec``'s bit for bit at any
    depth (beyond ``pywt.dwt_max_level`` too, where pywt warns) and warns nothing."""
    import warnings

    import pywt

    from fusion.readings import wavelet as wv

    x = np.random.default_rng(5).normal(size=(2, 64))
    for level in (1, 4, 6):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ref = pywt.wavedec(x, wavelet, level=level, mode="periodization", axis=-1)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            got = wv._wavedec_periodic(x, wavelet, level)
            wv.denoise(x, wavelet=wavelet, level=level)
        assert len(got) == len(ref) and all(np.array_equal(g, r) for g, r in zip(got, ref))


# --- D2: benchmark_cost's stage times beyond a measured duration's range ---------------------------------------------

@pytest.mark.parametrize("value", [1e300, 1e-320, 2e6])
def test_benchmark_cost_refuses_a_duration_outside_the_plausible_range(value: float, tmp_path: Path) -> None:
    """D2, decided: a measured duration lies in [1e-9, 1e6] s (a timer's nanosecond to 11 days; the stored benchmarks
    measure 4.6e-5 to 218 s); 1e300 s glued a 300-digit number of ms, 1e-320 s "0.0 against 0.0 ms per frame"."""
    import json

    from fusion.book.chapters.chernoff import swarm

    src = json.loads((Path(__file__).resolve().parents[1] / "benchmarks/results/chernoff.json").read_text())
    for m in src["measurements"]:
        if "stage" in m:
            m["value"] = value
    path = tmp_path / "bench.json"
    path.write_text(json.dumps(src))
    with pytest.raises(ValueError, match=r"^path: benchmark result .*bench\.json.*must lie in \[1e-09, 1e\+06\]"):
        swarm.benchmark_cost(path)
    for m in src["measurements"]:
        if "stage" in m:
            m["value"] = 1e-9 if value < 1 else 1e6              # the range's ends are measured durations
    path.write_text(json.dumps(src))
    assert swarm.benchmark_cost(path)[1]["chf_bench_current"] is True
