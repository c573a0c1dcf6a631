"""Source 003 sec. 2.6: wavelet denoising and normalised fusion reconstruction."""

from __future__ import annotations

import numpy as np
import pytest

from fusion.readings import wavelet as wv
from fusion.readings.wavelet import denoise, reconstruct


def _signals(seed: int = 0):
    n = np.arange(1024)
    S = 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64)
    g = np.array([1.0, 1.5, 0.8, 2.0])
    sig = np.array([0.05, 0.1, 0.2, 0.4])
    rng = np.random.default_rng(seed)
    return S, g, g[:, None] * S + sig[:, None] * rng.normal(size=(4, 1024))


def test_denoising_reduces_error() -> None:
    S, g, X = _signals()
    Y = denoise(X)
    assert np.all(np.mean((Y - g[:, None] * S) ** 2, axis=1) < np.mean((X - g[:, None] * S) ** 2, axis=1))


def test_reconstruction_identities() -> None:
    S, g, X = _signals()
    rec = reconstruct(X)
    assert rec.weights.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(rec.reconstructed / rec.norms[:, None], np.tile(rec.fused, (4, 1)))
    assert rec.weights.argmax() == 0  # least noisy sensor


def test_noise_free_equal_gain_signals_are_reproduced() -> None:
    S, _, _ = _signals()
    X = np.tile(S, (3, 1)) + 1e-3 * np.random.default_rng(1).normal(size=(3, 1024))
    rec = reconstruct(X)
    assert np.max(np.abs(rec.reconstructed - S)) < 0.05


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="shape"):
        reconstruct(np.ones(10))
    with pytest.raises(ValueError, match="normaliser"):
        reconstruct(-np.abs(_signals()[2]))
    with pytest.raises(ValueError, match="level"):
        denoise(np.ones(64), level=0)


# --------------------------------------------------------------------------- issue 18: options, batches, order
def _case(seed: int = 3, runs: int = 3):
    from fusion.scenarios import wavelet_sensors as ws

    S = ws.measurand(ws.Signal.TWO_TONES, 256)
    g = np.array([1.0, 1.5, 0.8])
    sig = np.array([0.05, 0.1, 0.2])
    X = g[:, None] * S + np.random.default_rng(seed).normal(size=(runs, 3, 256)) * sig[:, None]
    return X, g[:, None] * S


def test_reconstruct_batches_equal_single_runs() -> None:
    X, _ = _case()
    for order in ("denoise-first", "fuse-first"):
        for nm in ("max", "median", "lsq"):
            batch = wv.reconstruct(X, level=3, normaliser=nm, order=order)
            for r in range(X.shape[0]):
                one = wv.reconstruct(X[r], level=3, normaliser=nm, order=order)
                np.testing.assert_allclose(batch.reconstructed[r], one.reconstructed, rtol=1e-12, atol=1e-12)
                np.testing.assert_allclose(batch.weights[r], one.weights, rtol=1e-12)


def test_bayes_threshold_and_hard_mode_denoise() -> None:
    X, truth = _case(runs=1)
    for thr in ("universal", "bayes"):
        for mode in ("soft", "hard"):
            Y = wv.denoise(X[0], level=4, mode=mode, threshold=thr)
            assert np.mean((Y - truth) ** 2) < np.mean((X[0] - truth) ** 2)
    # a pure-noise level is zeroed by BayesShrink; a noise-free signal is returned unchanged
    flat = np.full(256, 3.0)
    np.testing.assert_allclose(wv.denoise(flat, level=3, threshold="bayes"), flat, atol=1e-9)
    with pytest.raises(ValueError, match="threshold"):
        wv.denoise(X[0], threshold="sure")
    with pytest.raises(ValueError, match="order"):
        wv.reconstruct(X[0], order="both")


def test_fuse_first_of_identical_sensors_is_denoising_the_mean() -> None:
    X, _ = _case(runs=1)
    same = np.repeat(X[0, :1], 3, axis=0)
    rec = wv.reconstruct(same, level=3, order="fuse-first")
    np.testing.assert_allclose(rec.fused, wv.denoise(same[0], level=3) / rec.norms[0], rtol=1e-10)


def test_mechanism_study_shapes_and_the_bias_is_shared() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    cfgs = ws.CONFIGS[:2]
    s = ws.mechanism_study(length=256, runs=20, configs=cfgs)
    assert s.labels == tuple(ws.config_label(c) for c in cfgs)
    e = s.err[s.labels[0]]
    assert e["raw"].shape == (20, 4) and set(e) == {"raw", "denoised", "denoise-first", "fuse-first"}
    assert np.all((s.bias_share >= 0) & (s.bias_share <= 1))
    # what is left after removing the per-sample bias is (nearly) uncorrelated between sensors
    assert abs(s.mean_offdiag_corr_random) < 0.1 < s.mean_offdiag_corr
    np.testing.assert_allclose(np.diag(s.corr), 1.0)


# --------------------------------------------------------------------------- issue 18: step 3, the "recursive MA" variance
def test_running_variance_ends_at_the_batch_variance_and_window_is_the_recursion() -> None:
    X, _ = _case(runs=2)
    Y = wv.denoise(X, level=3)
    norms = Y.max(axis=-1)
    batch = wv.variance_estimates(X, Y, norms, "batch")
    run = wv.variance_estimates(X, Y, norms, "running")
    np.testing.assert_allclose(run[..., -1], batch[..., -1], rtol=1e-9)
    np.testing.assert_allclose(run[..., 0], 0.0, atol=1e-15)          # one sample has no spread
    # the moving average as the lecture's recursion, sample by sample: z̄(n) = z̄(n-1) + (z(n) - z(n-L))/L
    L = 16
    r = ((X - Y) / norms[..., None])[0, 1]
    m1 = m2 = 0.0
    ref = []
    for n in range(r.size):
        w = min(n + 1, L)
        if n < L:   # the window still grows: a running mean of what there is
            m1 += (r[n] - m1) / w
            m2 += (r[n] ** 2 - m2) / w
        else:
            m1 += (r[n] - r[n - L]) / L
            m2 += (r[n] ** 2 - r[n - L] ** 2) / L
        ref.append(m2 - m1 * m1)
    got = wv.variance_estimates(X, Y, norms, "window", window=L)[0, 1]
    np.testing.assert_allclose(got, np.maximum(ref, 0.0), rtol=1e-8, atol=1e-14)


def test_variance_readings_in_reconstruct() -> None:
    X, truth = _case(runs=2)
    batch = wv.reconstruct(X, level=3)
    run = wv.reconstruct(X, level=3, variance="running")
    # the last sample of the running reading uses the batch weights; the first gets equal weights
    np.testing.assert_allclose(run.weights, batch.weights, rtol=1e-9)
    np.testing.assert_allclose(run.weight_path[..., 0], 1.0 / 3)
    np.testing.assert_allclose(run.weight_path.sum(axis=-2), 1.0)
    np.testing.assert_allclose(batch.weight_path, np.broadcast_to(batch.weights[..., None], batch.weight_path.shape))
    eq = wv.reconstruct(X, level=3, variance="equal")
    np.testing.assert_allclose(eq.fused, np.mean(eq.denoised / eq.norms[..., None], axis=-2), rtol=1e-12)
    # the measurement's own variance contains the signal: far flatter weights than the residual's
    meas = wv.reconstruct(X, level=3, variance="measurement")
    assert np.all(np.ptp(meas.weights, axis=-1) < 0.5 * np.ptp(batch.weights, axis=-1))
    with pytest.raises(ValueError, match="variance"):
        wv.reconstruct(X, variance="ma")
    with pytest.raises(ValueError, match="window"):
        wv.reconstruct(X, variance="window", window=1)
    with pytest.raises(ValueError, match="Y"):
        wv.variance_estimates(X, X[..., :-1], batch.norms)
    with pytest.raises(ValueError, match="norms"):
        wv.variance_estimates(X, X, -batch.norms)


def test_variance_study_batch_reading_is_the_mechanism_studys_default() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    v = ws.variance_study(length=256, runs=10, readings=("batch", "window"), window=32)
    m = ws.mechanism_study(length=256, runs=10, configs=ws.CONFIGS[:1])
    e = m.err[m.labels[0]]
    np.testing.assert_allclose(v.err["batch"], e["denoise-first"], rtol=1e-12)
    np.testing.assert_allclose(v.denoised, e["denoised"], rtol=1e-12)
    assert v.w_spread["batch"] == 0.0 < v.w_spread["window"]
    np.testing.assert_allclose(v.w_true.sum(), 1.0)
    with pytest.raises(ValueError, match="readings"):
        ws.variance_study(length=64, runs=2, readings=("batch", "ma"))


# --------------------------------------------------------------------------- review of chapter 03: signals, metrics, transform
def test_translation_invariant_denoiser_keeps_noise_levels_and_is_shift_equivariant() -> None:
    X, truth = _case(runs=1)
    Y = wv.denoise(X[0], level=3, mode="hard", transform="swt")
    assert np.mean((Y - truth) ** 2) < np.mean((X[0] - truth) ** 2)
    # the stationary transform commutes with circular shifts (the decimated one does not)
    for shift in (1, 5):
        a = wv.denoise(np.roll(X[0], shift, axis=-1), level=3, transform="swt")
        np.testing.assert_allclose(a, np.roll(wv.denoise(X[0], level=3, transform="swt"), shift, axis=-1), atol=1e-10)
    d = wv.denoise(np.roll(X[0], 1, axis=-1), level=3)
    assert np.max(np.abs(d - np.roll(wv.denoise(X[0], level=3), 1, axis=-1))) > 1e-6
    # a noise-free constant is returned unchanged; a length not divisible by 2**level is refused
    np.testing.assert_allclose(wv.denoise(np.full(64, 2.0), level=3, transform="swt"), 2.0, atol=1e-12)
    with pytest.raises(ValueError, match="2\\*\\*level"):
        wv.denoise(np.ones(60), level=3, transform="swt")
    with pytest.raises(ValueError, match="transform"):
        wv.denoise(np.ones(64), transform="cwt")


def test_measurands_and_error_metrics() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    for kind in ws.SIGNALS:
        S = ws.measurand(kind, 256)
        assert S.shape == (256,) and S.min() > 0
    n = np.arange(64)
    np.testing.assert_allclose(ws.measurand(ws.Signal.TWO_TONES, 64), 2 + np.sin(2 * np.pi * n / 256) + 0.5 * np.sin(2 * np.pi * n / 64))
    assert np.ptp(ws.measurand(ws.Signal.CONSTANT, 64)) == 0.0
    h = ws.measurand(ws.Signal.HEAVISINE, 1000)
    np.testing.assert_array_equal(ws.measurand("sig_slow", 64), ws.measurand(ws.Signal.SLOW, 64))  # a key's value
    with pytest.raises(ValueError, match="kind"):
        ws.measurand("two tones", 64)                    # a label (issue 36: labels are in the style registry only)
    assert h[500] - h[250] < -0.4 and np.isclose(h.max(), 3.0, atol=0.01)   # the jump at t = 0.3
    rng = np.random.default_rng(2)
    truth = np.tile(ws.measurand(ws.Signal.TWO_TONES, 128), (2, 1))
    bias = 0.1 * np.sin(np.arange(128))
    est = truth + bias + 0.01 * rng.normal(size=(50, 2, 128))
    m = ws.error_metrics(est, truth)
    # MSE = ensemble variance + squared bias of the runs' mean error, exactly
    e = est - truth
    np.testing.assert_allclose(m["mse"].mean(0), m["evar"].mean(0) + np.mean(e.mean(0) ** 2, axis=-1), rtol=1e-12)
    assert np.all(m["evar"].mean(0) < 2e-4) and np.all(m["mse"].mean(0) > 4e-3)
    np.testing.assert_allclose(m["tvar"], est.var(axis=-1))
    with pytest.raises(ValueError, match="est"):
        ws.error_metrics(est[:1], truth)


def test_signal_study_and_the_fuse_first_shortcut() -> None:
    from fusion.readings import wavelet as wv_
    from fusion.scenarios import wavelet_sensors as ws

    s = ws.signal_study(signals=(ws.Signal.CONSTANT, ws.Signal.TWO_TONES), modes=("hard",), normalisers=("max", "median"), length=128,
                        runs=12, level=3)
    c = s.cases[ws.Signal.CONSTANT, "hard", "max"]
    assert set(c) >= {"raw", "denoised", "reconstructed", "fuse-first", "gain_err", "weights"}
    assert "fuse-first" not in s.cases[ws.Signal.CONSTANT, "hard", "median"]
    # the same noise for every case; the raw MSE is the noise power
    np.testing.assert_allclose(c["raw"]["mse"], s.cases[ws.Signal.TWO_TONES, "hard", "max"]["raw"]["mse"])
    # with a flat signal the maximum of the residual noise sets the normaliser: it overshoots
    assert np.all(c["gain_err"] > 0) and np.all(np.abs(s.cases[ws.Signal.CONSTANT, "hard", "median"]["gain_err"])
                                                  < np.abs(c["gain_err"]))
    # the fuse-first shortcut equals reconstruct(order="fuse-first")
    X = s.truth[ws.Signal.TWO_TONES] + (s.raw0[ws.Signal.TWO_TONES] - s.truth[ws.Signal.TWO_TONES])[None]
    X = np.concatenate([X, X[:, ::-1]], axis=0)
    for cfg in ws.CONFIGS[:1] + ws.CONFIGS[-1:]:
        kw = dict(ws._kw(cfg), level=3)
        ref = wv_.reconstruct(X, order="fuse-first", **kw).reconstructed
        np.testing.assert_allclose(ws._fuse_first(X, wv_.reconstruct(X, **kw), kw), ref, rtol=1e-12, atol=1e-12)


def test_variance_study_oracle_uses_the_true_noise() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    v = ws.variance_study(length=256, runs=8, readings=("batch",))
    assert v.readings == ("batch", "oracle")
    np.testing.assert_allclose(v.w_final["oracle"].sum(), 1.0)
    assert v.w_final["oracle"].argmax() == 0 and v.err["oracle"].shape == (8, 4)


# --------------------------------------------------------------------------- second review: normalisers, blocks, streaming
def test_fuse_denoised_is_reconstruct_after_denoise_and_max_raw_uses_the_raw_maximum() -> None:
    X, truth = _case(runs=3)
    Y = wv.denoise(X, level=3, mode="hard")
    for nm in wv.NORMALISERS:
        a = wv.reconstruct(X, level=3, mode="hard", normaliser=nm)
        b = wv.fuse_denoised(X, Y, normaliser=nm)
        np.testing.assert_allclose(a.reconstructed, b.reconstructed, rtol=1e-12)
    np.testing.assert_allclose(wv.fuse_denoised(X, Y, normaliser="max-raw").norms, X.max(axis=-1))
    np.testing.assert_allclose(wv.fuse_denoised(X, Y, normaliser="max").norms, Y.max(axis=-1))
    with pytest.raises(ValueError, match="Y"):
        wv.fuse_denoised(X, Y[..., :-1])


def test_reconstruct_in_blocks_equals_one_run_at_a_time() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    S = ws.measurand(ws.Signal.TWO_TONES, 1024)
    X = 2 * S + 0.1 * np.random.default_rng(1).normal(size=(70, 4, 1024))     # two blocks of runs
    for variance in ("batch", "running"):
        rec = wv.reconstruct(X, mode="hard", variance=variance)
        for r in (0, 63, 64, 69):
            one = wv.reconstruct(X[r], mode="hard", variance=variance)
            np.testing.assert_allclose(rec.reconstructed[r], one.reconstructed, rtol=1e-12)
            np.testing.assert_allclose(rec.weight_path[r], one.weight_path, rtol=1e-12)


def test_streamed_metrics_and_error_statistics_match_the_direct_formulas() -> None:
    from functools import partial

    from fusion.scenarios import wavelet_sensors as ws

    rng = np.random.default_rng(3)
    truth = np.tile(ws.measurand(ws.Signal.TWO_TONES, 128), (3, 1)) * np.array([[1.0], [1.5], [0.8]])
    est = truth + 0.05 * np.sin(np.arange(128)) + 0.02 * rng.normal(size=(150, 3, 128))
    blocks = [slice(0, 40), slice(40, 100), slice(100, 150)]
    out = ws._stream_metrics(partial(ws._stored, "e", est), truth, blocks)["e"]
    e = est - truth
    np.testing.assert_allclose(out["mse"], np.mean(e**2, axis=-1), rtol=1e-12)
    np.testing.assert_allclose(out["evar"], np.mean((e - e.mean(0)) ** 2, axis=-1), rtol=1e-10)
    np.testing.assert_allclose(out["tvar"], est.var(axis=-1), rtol=1e-12)
    only = ws._stream_metrics(partial(ws._stored, "e", est), truth, blocks, evar=False, tvar=False)["e"]
    assert set(only) == {"mse"}
    g = np.array([1.0, 1.5, 0.8])
    acc = {"sum": np.zeros(truth.shape), "sq": np.zeros(3)}
    for sl in blocks:
        ws._accumulate_rec(sl, {"denoise-first": est[sl]}, truth, g, acc)
    st = ws._error_stats(est, acc, truth, g, blocks)
    rel = e / g[:, None]
    np.testing.assert_allclose(st["corr"], np.corrcoef(np.moveaxis(rel, 1, 0).reshape(3, -1)), atol=1e-10)
    np.testing.assert_allclose(st["corr_random"], np.corrcoef(np.moveaxis(rel - rel.mean(0), 1, 0).reshape(3, -1)),
                               atol=1e-10)
    np.testing.assert_allclose(st["rms_bias"], np.sqrt(np.mean(rel.mean(0) ** 2, axis=-1)), rtol=1e-10)


def test_seed_study_is_signal_study_under_each_seed() -> None:
    from fusion.scenarios import wavelet_sensors as ws

    s = ws.seed_study(seeds=(5, 6), runs=4, length=128, level=3)
    for v in (5, 6):
        ref = ws.signal_study(signals=(ws.Signal.TWO_TONES,), modes=("hard",), normalisers=("max",), runs=4, seed=v,
                              length=128, level=3).cases[ws.Signal.TWO_TONES, "hard", "max"]
        np.testing.assert_allclose(s.cases[v]["reconstructed"]["mse"], ref["reconstructed"]["mse"])
    with pytest.raises(ValueError, match="kind"):
        ws.seed_study(seeds=(1,), runs=2, kind="sine")
    assert ws.seed_study(seeds=(5,), runs=4, length=128, level=3, kind="sig_slow").kind is ws.Signal.SLOW
