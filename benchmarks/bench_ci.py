"""Source 000, Fig. 5 and Tables 1-2: what does choosing the CI weight, and fusing, cost?

Side by side in one run, on the same 4-D covariance pair (step 60 of the chapter's asymmetric
two-sensor case, sensor b three times more precise):

* the weight by FOA with the source's settings (30 flies x 200 generations), scoring one fly at
  a time and the whole swarm at once;
* by exhaustive search on 1001 points, one point at a time and vectorised;
* by scipy's bounded scalar minimisation;
* in closed form (`fusion.estimates.ci_weight`: generalised eigenvalues, root of an n-term slope);

and the whole 50-run simulation of the source's case (both local filters for all runs, then the
fusion centre at every step) with CI (closed-form weight), the "improved CI" (split CI, weight
by bounded search), the convex combination, fuzzy clustering and CI with FOA at every step.

Table 1 unconfounded: one identical search routine (`fusion.optimise.bounded_minimum`: scipy's
bounded Brent plus the two ends, the same tolerance) on the CI objective tr P(omega) and on the
split-CI objective, at every step of the source's case (identical sensors) and of an asymmetric
anisotropic pair, the local filters run before the timer starts. Each step's two searches are
timed alternately (best of several repeats each), so that a change of machine load hits both; the
per-step times and the evaluation counts are stored under ``per_step``.

Records everything in `benchmarks/results/ci.json` (read by chapter 05). Timings are the best
of several repeats; ratios are taken between numbers measured in this same run.

Run: `.venv/bin/python benchmarks/bench_ci.py`
"""

from __future__ import annotations

import os
import time

import numpy as np

from fusion import data
from fusion import estimates as es
from fusion.optimise import scalar as opt
from fusion import filtering as tr
from fusion.scenarios import two_sensor
from _results import write_results  # benchmarks/_results.py (scripts run from anywhere)

REPEATS = 5
SEED = 2024


def best_of(fn, repeats: int = REPEATS, inner: int = 1) -> float:
    """Best time of ``repeats`` batches of ``inner`` calls, per call (s)."""
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        times.append((time.perf_counter() - t0) / inner)
    return min(times)


def _searches(a: "tr.LocalTrack", b: "tr.LocalTrack", k: int):
    """The CI and the split-CI weight searches at step ``k``: one routine, one tolerance, plain numpy objectives.

    CI: tr (w P1^-1 + (1 - w) P2^-1)^-1 on [0, 1] (the two inverses taken inside the timed call);
    split CI: tr ((P1d/w + P1i)^-1 + (P2d/(1 - w) + P2i)^-1)^-1 on [1e-6, 1 - 1e-6] (its ends divide by zero).
    """
    P1, P2 = a.gains.P[k], b.gains.P[k]
    P1d, P1i, P2d, P2i = a.Pd[k], a.Pi[k], b.Pd[k], b.Pi[k]
    inv, trace = np.linalg.inv, np.trace

    def ci_search():
        I1, I2 = inv(P1), inv(P2)
        return opt.bounded_minimum(lambda w: float(trace(inv(w * I1 + (1.0 - w) * I2))))

    def split_search():
        return opt.bounded_minimum(lambda w: float(trace(inv(inv(P1d / w + P1i) + inv(P2d / (1.0 - w) + P2i)))),
                                   lo=1e-6, hi=1.0 - 1e-6)

    return ci_search, split_search


def main() -> None:
    sc = data.WANG2024_SCENARIO
    Q = np.diag([sc["delta0"] ** 2] * 4)
    R = np.diag([sc["delta1"] ** 2] * 2)
    pair = two_sensor.two_sensor_scenario(R, R / 9, Q, np.random.default_rng(SEED + 1), runs=sc["runs"])
    P1, P2 = pair.tracks[0].gains.P[60], pair.tracks[1].gains.P[60]
    obj = lambda w: es.ci_objective(w, P1, P2)  # noqa: E731  (scalar or array of weights)
    w_star = es.ci_weight(P1, P2)
    # every method must find the optimum before it is timed
    found = {
        "foa_loop": opt.fruit_fly(obj, np.random.default_rng(SEED)).x,
        "foa_vectorised": opt.fruit_fly(obj, np.random.default_rng(SEED), vectorized=True).x,
        "grid_loop": opt.grid_search(obj, 1001).x,
        "grid_vectorised": opt.grid_search(obj, 1001, vectorized=True).x,
        "bounded": opt.bounded_minimum(obj).x,
    }
    for name, w in found.items():
        assert abs(w - w_star) < 2e-3, (name, w, w_star)

    per_call = {
        "foa_loop": best_of(lambda: opt.fruit_fly(obj, np.random.default_rng(SEED)), repeats=3),
        "foa_vectorised": best_of(lambda: opt.fruit_fly(obj, np.random.default_rng(SEED), vectorized=True)),
        "grid_loop": best_of(lambda: opt.grid_search(obj, 1001), repeats=3),
        "grid_vectorised": best_of(lambda: opt.grid_search(obj, 1001, vectorized=True), inner=20),
        "bounded": best_of(lambda: opt.bounded_minimum(obj), inner=20),
        "closed_form": best_of(lambda: es.ci_weight(P1, P2), inner=500),
        "ci_fusion": best_of(lambda: es.covariance_intersection(np.zeros(4), P1, np.zeros(4), P2), inner=500),
    }
    labels = {
        "foa_loop": "omega by FOA (30 x 200), one fly at a time",
        "foa_vectorised": "omega by FOA (30 x 200), swarm vectorised",
        "grid_loop": "omega by exhaustive grid (1001 points), one point at a time",
        "grid_vectorised": "omega by exhaustive grid (1001 points), vectorised",
        "bounded": "omega by bounded scalar minimisation (scipy)",
        "closed_form": "omega in closed form (ci_weight)",
        "ci_fusion": "CI fusion with the optimal omega (covariance_intersection)",
    }
    measurements = [{"key": k, "what": f"4-D pair: {labels[k]}: seconds per call", "value": v, "unit": "s"}
                    for k, v in per_call.items()]

    # the whole 50-run simulation of the source's case (identical sensors, printed noise)
    def simulate(rule: str, foa: bool = False, bounded: bool = False) -> None:
        s = two_sensor.two_sensor_scenario(R, R, Q, np.random.default_rng(SEED), runs=sc["runs"])
        a, b = s.tracks
        omega = None
        if bounded:   # the same weight search as split CI uses: scipy's bounded minimisation at every step
            omega = [opt.bounded_minimum(lambda w, k=k: es.ci_objective(w, a.gains.P[k], b.gains.P[k])).x
                     for k in range(s.t.size)]
        if foa:
            omega = [opt.fruit_fly(lambda w, k=k: es.ci_objective(w, a.gains.P[k], b.gains.P[k]),
                                   np.random.default_rng(SEED + k), vectorized=True).x for k in range(s.t.size)]
        tr.fuse_tracks(a, b, rule, omega=omega)

    whole = {
        "sim_ci": best_of(lambda: simulate("ci"), repeats=3),
        "sim_improved": best_of(lambda: simulate("split"), repeats=3),
        "sim_convex": best_of(lambda: simulate("convex"), repeats=3),
        "sim_fuzzy": best_of(lambda: simulate("fuzzy"), repeats=3),
        "sim_ci_foa": best_of(lambda: simulate("ci", foa=True), repeats=2),
        "sim_ci_bounded": best_of(lambda: simulate("ci", bounded=True), repeats=3),
    }
    sim_labels = {
        "sim_ci": "CI, closed-form omega",
        "sim_improved": "improved CI (split CI, omega by bounded search)",
        "sim_convex": "convex combination (= multi-Bayesian = maximum likelihood)",
        "sim_fuzzy": "fuzzy clustering",
        "sim_ci_foa": "CI, omega by vectorised FOA at every step",
        "sim_ci_bounded": "CI, omega by bounded search at every step (the search split CI uses)",
    }
    # Table 1 unconfounded: the same search on both objectives, no filtering in the timer
    per_step: dict[str, list[float]] = {}
    pairs = {"printed": (R, R), "anisotropic": (np.diag([150.0**2, 50.0**2]), 80.0**2 * np.eye(2))}
    for pair_name, (Ra, Rb) in pairs.items():
        tracks = two_sensor.two_sensor_scenario(Ra, Rb, Q, np.random.default_rng(SEED), runs=1).tracks
        t_ci, t_split, n_ci, n_split = [], [], [], []
        for k in range(tracks[0].gains.P.shape[0]):
            ci_search, split_search = _searches(tracks[0], tracks[1], k)
            n_ci.append(ci_search().n_evaluations)
            n_split.append(split_search().n_evaluations)
            a_best, b_best = np.inf, np.inf
            for _ in range(REPEATS):   # alternately, so that a change of load hits both
                a_best = min(a_best, best_of(ci_search, repeats=1, inner=3))
                b_best = min(b_best, best_of(split_search, repeats=1, inner=3))
            t_ci.append(a_best)
            t_split.append(b_best)
        per_step[f"search_ci_{pair_name}_s"] = t_ci
        per_step[f"search_split_{pair_name}_s"] = t_split
        per_step[f"search_ci_{pair_name}_evaluations"] = n_ci
        per_step[f"search_split_{pair_name}_evaluations"] = n_split
        label = "source's identical sensors" if pair_name == "printed" else "R1 = diag(150^2, 50^2), R2 = 80^2 I"
        measurements += [
            {"key": f"search_ci_{pair_name}", "what": f"{len(t_ci)} steps ({label}): omega by bounded search on tr P of CI, "
             "no filtering: seconds", "value": float(np.sum(t_ci)), "unit": "s"},
            {"key": f"search_split_{pair_name}", "what": f"{len(t_ci)} steps ({label}): the same search on tr P of split CI, "
             "no filtering: seconds", "value": float(np.sum(t_split)), "unit": "s"},
        ]

    steps = two_sensor.trajectory(1.0).t.size
    measurements += [{"key": k, "what": f"50 runs x {steps} steps: {sim_labels[k]}: seconds", "value": v, "unit": "s"}
                     for k, v in whole.items()]
    pub = data.WANG2024_FOA.columns
    ratios = {
        "ratio_foa": (f"published FOA time ({pub['foa_time_s'][0]:g} s) / our vectorised FOA", float(pub["foa_time_s"][0]) / per_call["foa_vectorised"]),
        "ratio_grid": (f"published exhaustive time ({pub['grid_time_s'][0]:g} s) / our vectorised grid", float(pub["grid_time_s"][0]) / per_call["grid_vectorised"]),
        "ratio_closed": ("published FOA time / our closed-form omega", float(pub["foa_time_s"][0]) / per_call["closed_form"]),
        "ratio_foa_vs_closed": ("our vectorised FOA / our closed-form omega", per_call["foa_vectorised"] / per_call["closed_form"]),
        "ratio_loop_vs_vector": ("our FOA one fly at a time / swarm vectorised", per_call["foa_loop"] / per_call["foa_vectorised"]),
        "ratio_improved_vs_ci": ("our whole simulation: improved CI / CI", whole["sim_improved"] / whole["sim_ci"]),
    }
    measurements += [{"key": k, "what": w, "value": v, "unit": "x"} for k, (w, v) in ratios.items()]
    write_results("ci", measurements, repeats=REPEATS, per_step=per_step)


if __name__ == "__main__":
    main()
