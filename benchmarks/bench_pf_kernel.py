"""Issue 37, item 4: the particle-filter kernel of chapter 06's study, its GFLOP/s and fraction of peak,
and the speed-ups that were measured but not landed (they change the results for a seed).

The kernel is step B of ``fusion.scenarios.range_bearing._Batch.frame`` (predict every node's particles,
weight them by the range-bearing likelihood, normalise, weighted moments), run here on the study's
arrays: ``RUNS`` runs x 3 nodes x 2000 particles, one generator per node and run, as the study does. It
is timed by parts over ``FRAMES`` frames (best of ``REPEATS``, process CPU time), with one BLAS thread
(``OPENBLAS_NUM_THREADS=1`` unless set otherwise).

Flops per particle and frame, counted by hand (an elementwise +, -, *, / or a sqrt, atan2, exp or
round counts as 1; a random normal counts as 0, it is timed on its own):

* predict ``X F' + W L'``: 2 x (4 x 4 multiply-adds) + 4 additions = 68
* log-likelihood (``fusion.filtering.particles._log_likelihood``): 19
* normalisation (max, subtract, exp, sum, divide): 5
* weighted mean and covariance (``_moments_batch``): 8 + 4 + 4 + 32 = 48

so 140 flops per particle and frame. Peak: a 2000 x 2000 dgemm on one thread on this machine (what numpy's
BLAS reaches), and the processor's nominal peak where ``lscpu`` tells the clock and the vector width.

Landed (the same numbers bit for bit: each generator fills its slot of one array in place, in the same
order, instead of one array per generator then a stacked copy; the predicted particles summed in place):
``landed_speedup`` compares the kernel before and after on the same arrays.

Options measured (not landed, the lead decides; neither keeps the draws or the arithmetic identical):

* ``fused_predict``: one product ``[X W] [F'; L']`` instead of two products and a sum (the same maths,
  another summation order: differences at round-off, so stored outputs could change in their last digit);
* ``bulk_draws``: every frame's normals of a generator drawn in one call; the study's node generators
  also draw the k-means++ starts of the mixture fit and the regularisation between frames, so drawing
  ahead changes which numbers go where (results change for a seed). Timed here as the floor the
  generator calls could reach.

Writes ``benchmarks/results/pf_kernel.json``.

Run: ``.venv/bin/python benchmarks/bench_pf_kernel.py``
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one BLAS thread (before numpy loads its BLAS)

import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_results  # noqa: E402

from fusion.estimates.chernoff.mixture import _moments_batch
from fusion.filtering.particles import _log_likelihood, ncv_model
from fusion.scenarios.range_bearing import RangeBearingScenario, _normals, simulate_target

RUNS, FRAMES, REPEATS = 100, 5, 5
FLOPS_PER_PARTICLE = 68 + 19 + 5 + 48


def best(fn, repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return min(times)


def nominal_peak() -> tuple[float | None, str]:
    """Nominal double-precision GFLOP/s of one core from lscpu (max MHz x flops per cycle), and how."""
    try:
        info = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None, "lscpu not available"
    fields = dict(line.split(":", 1) for line in info.splitlines() if ":" in line)
    fields = {k.strip(): v.strip() for k, v in fields.items()}
    flags = fields.get("Flags", "").split()
    mhz = fields.get("CPU max MHz") or fields.get("CPU MHz")
    model = fields.get("Model name", "?")
    if mhz is None:
        return None, f"{model}: clock not reported"
    per_cycle = 32 if "avx512f" in flags else 16 if ("avx2" in flags and "fma" in flags) else 8 if "avx" in flags else 4
    return float(mhz) / 1e3 * per_cycle, f"{model}, {float(mhz):.0f} MHz x {per_cycle} DP flops/cycle (one core)"


def main() -> None:
    sc = RangeBearingScenario()
    N, n = len(sc.sensors), sc.n_particles
    model = ncv_model(sc.T, sc.q)
    F, LQ = model.F, np.linalg.cholesky(model.Q)
    S = sc.sensor_array
    targets = [simulate_target(sc, np.random.default_rng(r)) for r in range(RUNS)]
    z = np.stack([t.z for t in targets])  # (RUNS, K, N, 2)
    X0 = np.stack([t.m0 for t in targets])[:, None, None, :] + np.random.default_rng(0).normal(size=(RUNS, N, n, 4))
    particles = RUNS * N * n

    def gens():
        return [[np.random.default_rng([r, i]) for i in range(N)] for r in range(RUNS)]

    def step_b(X, rngs, k, parts=None, before=False):
        t = time.process_time
        t0 = t()
        if before:  # the kernel as it was: one array per generator, stacked; the sum in a third array
            draws = np.stack([[rngs[b][i].standard_normal((n, 4)) for i in range(N)] for b in range(RUNS)])
            t1 = t()
            X = np.matmul(X, F.T) + np.matmul(draws, LQ.T)
        else:  # as landed (range_bearing._Batch.frame): the same numbers, filled in place, the sum in place
            draws = _normals([g for row in rngs for g in row], (n, 4)).reshape(RUNS, N, n, 4)
            t1 = t()
            X = np.matmul(X, F.T)
            X += np.matmul(draws, LQ.T)
        t2 = t()
        lw = np.stack([_log_likelihood(X[:, i], z[:, k, i], S[i], sc.sigma_r, sc.sigma_theta) for i in range(N)], axis=1)
        t3 = t()
        w = np.exp(lw - lw.max(axis=-1, keepdims=True))
        w /= w.sum(axis=-1, keepdims=True)
        t4 = t()
        m, c = _moments_batch(X.reshape(-1, n, 4), w.reshape(-1, n))
        t5 = t()
        if parts is not None:
            for key, dt in zip(("draws", "predict", "likelihood", "normalise", "moments"),
                               (t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4)):
                parts[key] = parts.get(key, 0.0) + dt
        return X, m

    if True:  # (one BLAS thread: OPENBLAS_NUM_THREADS set above)
        # the kernel, by parts
        runs = []
        for _ in range(REPEATS):
            parts: dict[str, float] = {}
            X, rngs = X0.copy(), gens()
            for k in range(FRAMES):
                X, _ = step_b(X, rngs, k, parts)
            runs.append(parts)
        fastest = min(runs, key=lambda p: sum(p.values()))  # the repeat with the least total time, by parts
        total, per = sum(fastest.values()), fastest
        # the kernel before and after the landed change (same numbers: checked here on the last frame's moments)
        t_before, t_after, last = [], [], {}
        for r in range(REPEATS):
            for before, store in ((True, t_before), (False, t_after)) if r % 2 == 0 else ((False, t_after), (True, t_before)):
                X, rngs = X0.copy(), gens()
                t0 = time.process_time()
                for k in range(FRAMES):
                    X, m = step_b(X, rngs, k, before=before)
                store.append(time.process_time() - t0)
                if r == 0:
                    last[before] = m
        same = bool(np.array_equal(last[True], last[False]))
        per_frame = total / FRAMES
        gflops = FLOPS_PER_PARTICLE * particles / per_frame / 1e9
        flop_parts = {"predict": 68, "likelihood": 19, "normalise": 5, "moments": 48}
        # peak: a large dgemm on one thread
        A = np.random.default_rng(1).random((2000, 2000))
        t_mm = best(lambda: A @ A, 3)
        dgemm = 2 * 2000**3 / t_mm / 1e9
        nominal, how = nominal_peak()

        # option 1: the predict as one product (not bitwise)
        Xs = X0.copy()
        W = np.random.default_rng(5).standard_normal(Xs.shape)
        FL = np.concatenate([F.T, LQ.T])  # (8, 4)
        XW = np.concatenate([Xs, W], axis=-1)
        t_two = best(lambda: np.matmul(Xs, F.T) + np.matmul(W, LQ.T))
        t_cat = best(lambda: np.matmul(np.concatenate([Xs, W], axis=-1), FL))
        t_one = best(lambda: np.matmul(XW, FL))  # if the draws were written next to the states
        a, b = np.matmul(Xs, F.T) + np.matmul(W, LQ.T), np.matmul(XW, FL)
        fused_diff = float(np.max(np.abs(a - b) / np.maximum(np.abs(a), 1e-300)))
        fused_bitwise = bool(np.array_equal(a, b))
        # option 2: the draws of all frames in one call per generator (changes which numbers go where)
        t_per_frame = best(lambda: [[g.standard_normal((n, 4)) for g in row] for row in gens()
                                    for _ in range(FRAMES)]) / FRAMES
        t_bulk = best(lambda: [[g.standard_normal((FRAMES, n, 4)) for g in row] for row in gens()]) / FRAMES
        t_gens = best(gens) / FRAMES
        one = np.random.default_rng(0)
        t_single = best(lambda: one.standard_normal((FRAMES, RUNS * N * n * 4))) / FRAMES

    blas = f"numpy {np.__version__}, OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}"
    meas = [
        {"key": "pf_kernel_frame_s", "what": f"step B, one frame of {RUNS} runs x {N} nodes x {n} particles",
         "value": per_frame, "unit": "s"},
        {"key": "pf_kernel_gflops", "what": "step B throughput (140 flops per particle and frame)", "value": gflops,
         "unit": "GFLOP/s"},
        {"key": "dgemm_gflops", "what": "peak reference: 2000x2000 dgemm, one thread", "value": dgemm,
         "unit": "GFLOP/s"},
        {"key": "pf_kernel_fraction_of_dgemm", "what": "step B as a fraction of the dgemm peak", "value": gflops / dgemm,
         "unit": ""},
    ]
    if nominal:
        meas += [{"key": "nominal_peak_gflops", "what": f"nominal peak of one core ({how})", "value": nominal,
                  "unit": "GFLOP/s"},
                 {"key": "pf_kernel_fraction_of_nominal", "what": "step B as a fraction of the nominal peak",
                  "value": gflops / nominal, "unit": ""}]
    for key, dt in per.items():
        share = dt / total
        rate = flop_parts.get(key, 0) * particles * FRAMES / dt / 1e9
        meas.append({"key": f"share_{key}", "what": f"share of step B's time: {key}"
                     + (f" ({rate:.2f} GFLOP/s)" if key in flop_parts else " (random normals, no flops counted)"),
                     "value": share, "unit": ""})
    meas += [
        {"key": "landed_speedup", "what": "step B before / after the landed change (normals filled in place, sum in place)",
         "value": min(t_before) / min(t_after), "unit": "x"},
        {"key": "landed_identical", "what": "landed change: the same estimates, bit for bit (1 = yes)",
         "value": float(same), "unit": ""},
        {"key": "option_fused_predict_speedup", "what": "option: predict as one product [X W][F'; L'] (concatenating)",
         "value": t_two / t_cat, "unit": "x"},
        {"key": "option_fused_predict_speedup_no_concat", "what": "option: the same with the draws already beside X",
         "value": t_two / t_one, "unit": "x"},
        {"key": "option_fused_predict_max_rel_diff", "what": "option fused predict: largest relative difference",
         "value": fused_diff, "unit": ""},
        {"key": "option_bulk_draws_speedup", "what": "option: a generator's normals for all frames in one call",
         "value": t_per_frame / t_bulk, "unit": "x"},
        {"key": "draws_floor_one_generator_s", "what": "floor: the same normals from one generator in one call, per frame",
         "value": t_single, "unit": "s"},
        {"key": "draws_generators_setup_s", "what": "creating the 300 generators (per frame of the timing loop)",
         "value": t_gens, "unit": "s"},
    ]
    write_results("pf_kernel", meas, runs=RUNS, frames=FRAMES, repeats=REPEATS, threads=1, blas=blas,
                  load_average_at_end=os.getloadavg(), fused_predict_bitwise=fused_bitwise,
                  flops_per_particle=FLOPS_PER_PARTICLE, landed=False,
                  landed_change="range_bearing._normals and in-place sums (bit for bit the same results)")


if __name__ == "__main__":
    main()
