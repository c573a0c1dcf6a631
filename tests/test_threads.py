"""Stored outputs do not depend on the BLAS thread count or kernel.

The computations whose decisions once hung on round-off (chapter 05: the fruit fly and the
exhaustive search over a flat covariance-intersection objective, and the rules with and without
feedback, whose per-run RMSE is rounded to mm; chapter 06: the particle swarm
and the SLSQP reference on the importance-sampling objective) run in subprocesses under
``OPENBLAS_NUM_THREADS`` = 1 and 4 and, on x86-64, under other OpenBLAS kernels
(``OPENBLAS_CORETYPE``). Everything the optimisers decide (weights, iteration and evaluation
counts) must be bitwise identical; values computed through BLAS are compared at 10⁻⁷ relative, far
coarser than round-off (and than SLSQP's kernel-dependent last digits, 2 × 10⁻⁹) and far finer than
the chapters' rounding (at most 4 significant digits; the ledger rounds every comparison to 4 digits
of its means, :meth:`fusion.book.ledger.Comparison.resolution`).
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fusion.optimise._ties import TIE_RTOL, first_minimum, improves

ROOT = Path(__file__).resolve().parents[1]

SCRIPT = r"""
import dataclasses, json
import numpy as np
from fusion import estimates as es
from fusion import filtering as tr
from fusion.optimise import scalar as opt
from fusion.scenarios import range_bearing, two_sensor

out = {}
# chapter 05: equal sensors make P1 = P2 at every step, so tr P(omega) is flat
q, r = np.diag([0.5**2] * 4), np.diag([10.0**2] * 2)
sc = two_sensor.two_sensor_scenario(r, r, q, np.random.default_rng(2024), runs=5, T=1.0)
a, b = sc.tracks
steps = range(20, 30)  # ten steps: the flat objective is the same at every step
out["foa_flat"] = [opt.fruit_fly(lambda w, k=k: es.ci_objective(w, a.gains.P[k], b.gains.P[k]),
                                 np.random.default_rng(k), vectorized=True).x for k in steps]
out["grid_flat"] = [opt.grid_search(lambda w, k=k: es.ci_objective(w, a.gains.P[k], b.gains.P[k]), 1001,
                                    vectorized=True).x for k in steps]
sa = two_sensor.two_sensor_scenario(r, r / 9, q, np.random.default_rng(2025), runs=5, T=1.0)
PA, PB = sa.tracks[0].gains.P[60], sa.tracks[1].gains.P[60]
foa = opt.fruit_fly(lambda w: es.ci_objective(w, PA, PB), np.random.default_rng(1), vectorized=True)
out["foa_asym"] = [foa.x, foa.n_evaluations]
out["foa_asym_value"] = foa.fun
# chapter 05: every rule with and without the Fig. 2 feedback (split-CI weights by bounded search,
# Bar-Shalom-Campo through a pseudo-inverse of a singular matrix on identical sensors)
for name, r2 in (("equal", r * 225), ("unequal", r * 25)):
    # few runs: the rules' weights depend on the covariances only, the same in every run; a 4 s period: half the
    # steps of 2 s (the study's cost is per step: the rules' weight searches), every rule and both sensor pairs
    arch = two_sensor.architecture_study(np.random.default_rng(7), r * 225, r2, q * 400, runs=8, nees_runs=4, T=4.0)
    out["arch_rmse_" + name] = {" | ".join(k): v.tolist() for k, v in arch.run_rmse.items()}
    out["arch_nees_" + name] = [arch.nees[k] for k in sorted(arch.nees)]
# chapter 06: a short run of the patented pipeline with PSO and the SLSQP reference
small = dataclasses.replace(range_bearing.RangeBearingScenario(), frames=3, n_particles=400,
                            n_samples=400, n_central=800)
run = range_bearing.run_tracking(small, np.random.SeedSequence(2017))
out["pso_eps"] = run.eps["pso"].tolist()
out["pso_evaluations"] = run.evaluations["pso"].tolist()
out["slsqp_evaluations"] = run.evaluations["slsqp"].tolist()
out["slsqp_eps"] = run.eps["slsqp"].tolist()
out["objective"] = [run.objective[k].tolist() for k in ("pso", "slsqp")]
out["estimates"] = [run.estimates[k].tolist() for k in sorted(run.estimates)]
print(json.dumps(out))
"""


def _default_kernel() -> str:
    """The OpenBLAS kernel numpy's bundled library picks on this CPU ("" if it cannot be asked)."""
    import ctypes
    import glob

    try:
        lib = ctypes.CDLL(glob.glob(str(Path(np.__file__).parent) + ".libs/libscipy_openblas*")[0])
        name = lib.scipy_openblas_get_corename64_
    except (IndexError, OSError, AttributeError):
        return ""
    name.restype = ctypes.c_char_p
    return name().decode()


# one thread and four (the first setting lets OpenBLAS pick the kernel for this CPU, which is therefore
# not run again under its name)
SETTINGS = [{"OPENBLAS_NUM_THREADS": n} for n in ("1", "4")]
if platform.machine() in ("x86_64", "AMD64"):
    # another kernel family: Sandybridge (no FMA) runs on every x86-64 CPU of the last decade
    SETTINGS += [{"OPENBLAS_NUM_THREADS": "1", "OPENBLAS_CORETYPE": "Sandybridge"}]
    # and the AVX2 and AVX-512 kernels where the CPU has them: the committed outputs were once made under
    # Haswell and failed on a machine whose OpenBLAS picks SkylakeX (round-off printed into the ledger)
    _FLAGS = set(Path("/proc/cpuinfo").read_text().split()) if Path("/proc/cpuinfo").is_file() else set()
    SETTINGS += [{"OPENBLAS_NUM_THREADS": "1", "OPENBLAS_CORETYPE": c}
                 for c, flag in (("Haswell", "avx2"), ("SkylakeX", "avx512f"))
                 if flag in _FLAGS and c != _default_kernel()]


def _run(setting: dict[str, str]) -> dict[str, object]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OPENBLAS_", "OMP_", "MKL_"))}
    env.update({k: v for k, v in setting.items() if v})
    proc = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=600)
    assert proc.returncode == 0, f"{setting}: {proc.stderr[-3000:]}"
    return json.loads(proc.stdout)


@pytest.fixture(scope="module")
def results() -> list[dict[str, object]]:
    with ThreadPoolExecutor(max_workers=2) as pool:
        return list(pool.map(_run, SETTINGS))


@pytest.mark.parametrize("key", ["foa_flat", "grid_flat", "foa_asym", "pso_eps", "pso_evaluations",
                                 "slsqp_evaluations", "arch_rmse_equal", "arch_rmse_unequal"])
def test_same_decisions_with_any_thread_count_and_kernel(results: list[dict[str, object]], key: str) -> None:
    first = results[0][key]
    for setting, result in zip(SETTINGS[1:], results[1:]):
        assert result[key] == first, f"{key} differs under {setting} from {SETTINGS[0]}"


@pytest.mark.parametrize("key", ["foa_asym_value", "slsqp_eps", "objective", "estimates", "arch_nees_equal",
                                 "arch_nees_unequal"])
def test_same_values_with_any_thread_count_and_kernel(results: list[dict[str, object]], key: str) -> None:
    first = np.asarray(results[0][key], dtype=float)
    # SLSQP's exponents: its stopping rule (ftol 1e-10 on a flat minimum) fixes them only to ~1e-5, and the
    # quadratic-feature densities reach them through dgemm, whose FMA and non-FMA kernels round differently
    # (up to ~4e-11 here); the chapter shows them to 3 decimals
    atol = 1e-9 if key == "slsqp_eps" else 1e-12
    for setting, result in zip(SETTINGS[1:], results[1:]):
        # 10⁻⁷ relative: SLSQP's answer (same iterations) moves by up to 2 × 10⁻⁹ between the Haswell and
        # SkylakeX kernels, and the fused estimates with it; the chapters show at most 4 significant digits
        np.testing.assert_allclose(np.asarray(result[key], dtype=float), first, rtol=1e-7, atol=atol,
                                   err_msg=f"{key} differs under {setting} from {SETTINGS[0]}")


def test_flat_objective_gives_the_first_candidate(results: list[dict[str, object]]) -> None:
    """Not a vacuous comparison: on the flat objective the searches keep their first point."""
    assert set(results[0]["grid_flat"]) == {0.0}
    assert len(set(results[0]["foa_flat"])) > 1  # one first-generation candidate per seed


# --------------------------------------------------------------------------- the tie rule itself

@given(st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=30))
def test_first_minimum_is_the_first_value_within_the_tolerance(values: list[float]) -> None:
    v = np.array(values)
    k = first_minimum(v)
    margin = TIE_RTOL * max(abs(v.min()), 1.0)
    assert v[k] <= v.min() + margin
    assert np.all(v[:k] > v.min() + margin)


@given(st.floats(1.0, 1e6), st.integers(0, 29))
def test_round_off_never_decides(level: float, noisy: int) -> None:
    """A flat objective seen through round-off: the first point wins, whichever value is lowest."""
    v = np.full(30, level)
    v[noisy] = np.nextafter(level, -np.inf)
    assert first_minimum(v) == 0
    assert not improves(float(v[noisy]), level)


def test_improves_needs_more_than_the_tolerance() -> None:
    assert improves(1.0, np.inf)
    assert not improves(np.inf, np.inf)
    assert improves(100.0 - 1e-5, 100.0)
    assert not improves(100.0 - 1e-8, 100.0)  # within 1e-9 * 100
    assert not improves(101.0, 100.0)
