"""Issue 37: the kernels sped up without changing a digit, timed side by side with their reference paths.

Each row times the previous code (``benchmarks/_reference_kernels.py``) and the package's kernel on the same input,
interleaved (``REPEATS`` rounds, process CPU time, median), checks that both give the same numbers bit for bit,
and records the ratio (reference / new: above 1 the new kernel is faster):

* ``equal_kl_g``: chapter 06's equal-KL rule on the first-order mixture g
  (``fusion.scenarios.range_bearing_batch._equal_kl_on_mixture``) on the mixtures of the study's first
  ``FRAMES`` frames of ``RUNS`` runs (one block of the study's worker, ``study_scenario()``): its exponent-free
  terms prepared once, the Jacobian's columns in one evaluation, the line search re-evaluating the halved steps only,
  several halvings per evaluation (chunks of 1, 1, 3, 8 and 17 steps);
* ``huber`` and ``biweight``: chapter 01's robust baselines (``fusion.readings.robust``) on 50,000 epochs of ten
  thermocouple-like readings: rows at an exact fixed point of the iteration set aside;
* ``appendix_logpdf``: chapter 06 appendix's mixture log density (``fusion.book.chapters.chernoff_steps._logpdf``)
  of ``SIGMA_PROBLEMS`` random pairs and their first-order mixture on the sigma-point study's 401 x 401 grid, and
  their sigma-point fusions at 25 exponents: the quadratic forms term by term on contiguous rows instead of a
  three-operand einsum, the components laid out for the log-sum-exp, one call per mixture instead of one per
  component.

The whole study's CPU time is ``bench_study.py``'s. Writes ``benchmarks/results/kernels.json``.

Run: ``.venv/bin/python benchmarks/bench_kernels.py``
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one BLAS thread (before numpy loads its BLAS)

import dataclasses  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _reference_kernels as ref  # noqa: E402
from _results import write_results  # noqa: E402

from fusion.book.chapters.chernoff import study_scenario  # noqa: E402
from fusion.readings import robust  # noqa: E402
from fusion.scenarios import range_bearing as dist  # noqa: E402
from fusion.scenarios import range_bearing_batch as rbb  # noqa: E402

SEED, RUNS, FRAMES, REPEATS = 2017, 17, 6, 5
SIGMA_PROBLEMS = 4


def study_mixtures() -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The nodes' mixtures (log weights, means, covariances) the study hands the equal-KL rule, frame by frame."""
    seen: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    kernel = rbb._equal_kl_on_mixture

    def record(logw, means, covs, *args, **kwargs):
        seen.append((logw.copy(), means.copy(), covs.copy()))
        return kernel(logw, means, covs, *args, **kwargs)
    rbb._equal_kl_on_mixture = record
    try:
        sc = dataclasses.replace(study_scenario(), frames=FRAMES)
        dist.run_tracking_batch(sc, np.random.SeedSequence(SEED).spawn(RUNS))
    finally:
        rbb._equal_kl_on_mixture = kernel
    return seen


def sigma_problems() -> tuple[list, np.ndarray]:
    """Random mixture pairs of the sigma-point study with their first-order mixture at 0.4, and its random grid."""
    from fusion.book.chapters import chernoff_first_order as csf
    from fusion.estimates.chernoff import first_order_fusion
    rng = np.random.default_rng(SEED + 604)
    pairs = [csf.random_two_mixtures(rng) for _ in range(SIGMA_PROBLEMS)]
    axis = np.linspace(-9.0, 9.0, csf.SIGMA_RANDOM_NODES)
    X, Y = np.meshgrid(axis, axis)
    return [(a, b, first_order_fusion([a, b], [0.4, 0.6]).mixture) for a, b in pairs], np.column_stack([X.ravel(), Y.ravel()])


def appendix_logpdf(logpdf, sigma_point, problems, pts) -> list[np.ndarray]:
    """Every mixture's log density on the grid and the sigma-point fusions' normalisers and weights."""
    out = [logpdf(g, pts) for trio in problems for g in trio]
    for a, b, _ in problems:
        for w in np.linspace(0.02, 0.98, 25):
            f = sigma_point(a, b, w)
            out += [np.array([f.log_z_first_order]), f.mixture.weights]
    return out


def readings(rows: int = 50_000, n: int = 10) -> np.ndarray:
    """Ten thermocouples at 900 °C, noise 0.5-2 °C, two sensors biased by 0, 3 or 10 °C per epoch."""
    rng = np.random.default_rng(SEED)
    s = 900.0 + rng.normal(size=(rows, n)) * rng.uniform(0.5, 2.0, size=n)
    s[:, :2] += rng.choice([0.0, 3.0, 10.0], size=(rows, 1))
    return s


def side_by_side(old, new) -> tuple[float, float, bool]:
    """Median CPU seconds of ``old()`` and ``new()``, interleaved, and whether their results are identical."""
    t_old, t_new = [], []
    for _ in range(REPEATS):
        for fn, times in ((old, t_old), (new, t_new)):
            t0 = time.process_time()
            out = fn()
            times.append(time.process_time() - t0)
            if fn is old:
                r_old = out
            else:
                r_new = out
    same = all(np.array_equal(a, b, equal_nan=True) for a, b in zip(r_old, r_new))
    return float(np.median(t_old)), float(np.median(t_new)), same


def main() -> None:
    mixtures = study_mixtures()
    s = readings()
    from fusion.book.chapters import chernoff_first_order as csf
    from fusion.book.chapters import chernoff_steps as cs
    problems, pts = sigma_problems()
    rows = {
        "equal_kl_g": (lambda: [ref.equal_kl_on_mixture(*m) for m in mixtures],
                       lambda: [rbb._equal_kl_on_mixture(*m) for m in mixtures],
                       f"equal-KL rule on g, {FRAMES} frames x {RUNS} runs of the study"),
        "huber": (lambda: [ref.huber(s, 1.345)], lambda: [robust._huber(s, 1.345)],
                  f"Huber location, {s.shape[0]} epochs x {s.shape[1]} readings"),
        "biweight": (lambda: [ref.biweight(s, 4.685)], lambda: [robust._biweight(s, 4.685)],
                     f"biweight location, {s.shape[0]} epochs x {s.shape[1]} readings"),
        "appendix_logpdf": (
            lambda: appendix_logpdf(ref.mixture_logpdf_einsum, lambda a, b, w: ref.sigma_point_first_order([a, b], [w, 1 - w]),
                                    problems, pts),
            lambda: appendix_logpdf(cs._logpdf, lambda a, b, w: csf.sigma_point_first_order([a, b], [w, 1 - w]),
                                    problems, pts),
            f"chapter 06 appendix: mixture log densities of {SIGMA_PROBLEMS} problems on the 401 x 401 grid, "
            "sigma-point fusions at 25 exponents"),
    }
    measurements = []
    for key, (old, new, what) in rows.items():
        t_old, t_new, same = side_by_side(old, new)
        if not same:
            raise SystemExit(f"{key}: the kernel and its reference path disagree")
        measurements += [
            {"what": f"{what}: reference path, CPU seconds", "value": t_old, "unit": "s", "key": f"{key}_reference_s"},
            {"what": f"{what}: package kernel, CPU seconds", "value": t_new, "unit": "s", "key": f"{key}_s"},
            {"what": f"{what}: ratio reference / kernel (bitwise identical)", "value": t_old / t_new, "unit": "",
             "key": f"{key}_ratio"},
        ]
    write_results("kernels", measurements, repeats=REPEATS, load_average=round(os.getloadavg()[0], 2),
                  blas_threads=os.environ.get("OPENBLAS_NUM_THREADS", "default"))


if __name__ == "__main__":
    main()
