"""Fuzz 49b C6, C7, D1 (fix56d): ``stability.summarise`` grouped its results by a scan per seed (quadratic, no budget,
C6); the Gaussian-mixture kernel of ``fusion.estimates.mixtures`` stacked components x points unchecked (C7);
``time_registration.expected`` refused a zero-process-noise smoother by internal names (D1)."""

from __future__ import annotations

import random
import time
from dataclasses import asdict

import pytest

from fusion._limits import MAX_WORK


def _refused_fast(f, match, limit=1.0):
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        f()
    assert time.process_time() - t0 < limit


# --- C6 -------------------------------------------------------------------------------------------------------------

def _summarise_reference(results, seed_list, committed):
    """The grouping of ``summarise`` before fuzz 49b C6 (a scan of the record's results per seed), for comparison."""
    from fusion.book import rulebook as R
    from fusion.book.stability import _same
    by = {}
    for r in results:
        by.setdefault(r.task.record, []).append(r)
    out = {}
    for rid, rs in sorted(by.items()):
        failed = [asdict(r.task) | {"error": r.error} for r in rs if r.status is None]
        statuses = []
        for s in seed_list:
            mine = [r for r in rs if r.task.seed == s and not r.task.scaled]
            prim = next((r for r in mine if r.task.reading == "primary"), None)
            if prim is None or prim.status is None or any(r.status is None for r in mine):
                statuses.append(None)
                continue
            readings = [(r.task.kind, r.status, r.task.runs) for r in mine if r.task.reading != "primary"]
            statuses.append(R.record_status(prim.status, readings, prim.task.runs, False)[0])
        scaled = next((r.status for r in rs if r.task.scaled), None)
        want = committed.get(rid)
        k = sum(s is not None and _same(s, want) for s in statuses)
        out[rid] = {"committed": want, "reseeds": statuses, "scaled": scaled, "k": k, "K": len(seed_list),
                    "flag": k < len(seed_list) or (scaled is not None and not _same(scaled, want)),
                    "failed": failed}
    return out


def test_c6_summarise_linear_grouping_is_the_old_one_on_random_sweeps():
    from fusion.book import rulebook as R
    from fusion.book.stability import Task, TaskResult, summarise
    rng = random.Random(4956)
    kinds = [k for k in R.READING_KINDS if k != "primary"]
    for trial in range(60):
        seed_list = rng.sample(range(1, 10**6), rng.randint(1, 7))
        results, committed = [], {}
        for rec in range(rng.randint(1, 6)):
            rid = f"r{rec}"
            committed[rid] = rng.choice([None, *R.STATUSES])
            names = ["primary"] + [f"x{j}" for j in range(rng.randint(0, 4))]
            kind = {n: "primary" if n == "primary" else rng.choice(kinds) for n in names}
            for s in seed_list:
                for n in names:
                    if rng.random() < 0.85:
                        st = rng.choice([None, *R.STATUSES[:4]]) if rng.random() < 0.9 else None
                        results.append(TaskResult(Task("src", rid, n, kind[n], s, rng.choice([10, 100]), False), st,
                                                  0.1, "" if st else "boom"))
            if rng.random() < 0.7:
                s = rng.choice(seed_list)
                st = rng.choice([None, *R.STATUSES[:4]])
                results.append(TaskResult(Task("src", rid, "primary", "primary", s, 1000, True), st, 0.1,
                                          "" if st else "boom"))
        rng.shuffle(results)
        assert summarise(results, seed_list, committed) == _summarise_reference(results, seed_list, committed)


def test_c6_summarise_is_linear_in_seeds():
    # 20,000 seeds of one result each ran 6.0 CPU-s before (quadratic; 60,000: 99 CPU-s); now about 0.15 s
    from fusion.book.stability import Task, TaskResult, summarise
    seed_list = list(range(1, 20_001))
    res = [TaskResult(Task("s", "r", "primary", "primary", s, 100, False), "reproduced", 0.1) for s in seed_list]
    t0 = time.process_time()
    out = summarise(res, seed_list, {"r": "reproduced"})
    assert time.process_time() - t0 < 2.0
    assert out["r"]["k"] == 20_000


def test_c6_summarise_budget_edges():
    from fusion.book import stability as S
    # just inside: 10**6 results; 5e7 record x seed cells (with their 10**4 results), accepted by the budget alone
    assert S._summary_work(10**6 - 10**4, 1, 10**4) <= MAX_WORK
    assert S._summary_work(10**4, 10**4, 4_900) <= MAX_WORK
    with pytest.raises(ValueError, match="results and seed_list"):
        S._summary_work(10**6 + 1, 1, 1)
    with pytest.raises(ValueError, match="results and seed_list"):
        S._summary_work(10**4, 10**4, 5_000)


def test_c6_summarise_refuses_beyond_the_budget_before_the_work():
    from fusion.book.stability import Task, TaskResult, summarise
    # more results than the budget: refused before any is grouped (the repeated task is never reached)
    r = TaskResult(Task("s", "r", "primary", "primary", 1, 100, False), "reproduced", 0.1)
    _refused_fast(lambda: summarise([r] * (10**6 + 1), [1], {}), "results and seed_list .*work budget")
    # 10,000 records x 5,000 seeds: refused once grouped, before any status is judged
    seed_list = list(range(1, 5_001))
    res = [TaskResult(Task("s", f"r{i}", "primary", "primary", 1, 100, False), "reproduced", 0.1)
           for i in range(10_000)]
    _refused_fast(lambda: summarise(res, seed_list, {}), "results and seed_list .*10,000 records x 5,000 seeds")


# --- C7 -------------------------------------------------------------------------------------------------------------

def _unit_mixture(S, d, seed=0):
    import numpy as np
    from fusion.estimates.mixtures import GaussianMixture
    rng = np.random.default_rng(seed)
    return GaussianMixture(np.full(S, 1.0 / S), rng.normal(size=(S, d)), np.broadcast_to(np.eye(d), (S, d, d)).copy())


def test_c7_gm_logpdf_refuses_components_times_points_before_the_work():
    # 2,500 components at 200,000 points: a raw MemoryError (3.73 GiB) after 22 CPU-s before
    import numpy as np
    from fusion.estimates.mixtures import gm_logpdf
    gm, x = _unit_mixture(2_500, 2), np.zeros((200_000, 2))
    _refused_fast(lambda: gm_logpdf(gm, x), "gm and x ask for an array .* beyond the memory budget")
    # the work alone (d = 10, 9.3 units an entry): 1,100 components at 100,000 points, two 0.9 GB stacks inside the
    # memory budget
    gm, x = _unit_mixture(1_100, 10), np.zeros((100_000, 10))
    _refused_fast(lambda: gm_logpdf(gm, x), r"gm and x ask for .* units of work")


def test_c7_density_budget_edges():
    import numpy as np
    from fusion._limits import MAX_WORK
    from fusion.estimates.mixtures import GaussianMixture, _density_work
    # d = 10: 9.3 units an entry and 2,000 a component, at 100,000 points: 1,072 components at the edge
    assert _density_work([_unit_mixture(1_050, 10)], 100_000, "gm and x") <= MAX_WORK
    with pytest.raises(ValueError, match="gm and x ask for .* units of work"):
        _density_work([_unit_mixture(1_100, 10)], 100_000, "gm and x")
    # a mixture's dead components are not evaluated, and log_densities sums its mixtures
    g = _unit_mixture(2_100, 10)
    half = GaussianMixture(np.r_[np.full(1_050, 1 / 1_050), np.zeros(1_050)], g.means, g.covs)
    assert _density_work([half], 100_000, "gm and x") <= MAX_WORK
    with pytest.raises(ValueError, match="gms and x ask for .* units of work"):
        _density_work([half, half], 100_000, "gms and x")
    # memory: two (components, points) stacks
    with pytest.raises(ValueError, match="gm and x ask for an array .* 2 arrays of 1400 x 100000"):
        _density_work([_unit_mixture(1_400, 1)], 100_000, "gm and x")


def test_c7_log_densities_and_grid_refuse_by_their_arguments():
    import numpy as np
    from fusion.estimates.chernoff import log_densities
    from fusion.scenarios.two_mixtures import grid_log_normaliser
    gms = [_unit_mixture(550, 10, 1), _unit_mixture(550, 10, 2)]
    _refused_fast(lambda: log_densities(gms, np.zeros((100_000, 10))), r"gms and x ask for .* units of work")
    # the default 601 x 601 grid: 374 components in all at the edge
    gms = [_unit_mixture(200, 2, 1), _unit_mixture(200, 2, 2)]
    _refused_fast(lambda: grid_log_normaliser(gms, [0.5, 0.5]), r"gms and n ask for .* units of work")


def test_c7_gm_logpdf_values_unchanged_inside():
    import numpy as np
    from fusion.estimates.chernoff import log_densities
    from fusion.estimates.mixtures import _gm_logpdf, gm_logpdf
    gm = _unit_mixture(30, 3)
    x = np.random.default_rng(1).normal(size=(500, 3))
    assert np.array_equal(gm_logpdf(gm, x), _gm_logpdf(gm, x))
    assert np.array_equal(log_densities([gm, gm], x), np.column_stack([_gm_logpdf(gm, x)] * 2))


# --- D1 -------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("method", ["reg_rts_smoother", "reg_fixed_lag"])
@pytest.mark.parametrize("sigma, q", [(1e-8, 0.0), (1e-10, 0.0), (1e-8, 1e-70)])
def test_d1_smoother_with_a_singular_predicted_covariance_names_sigma_q_v_q_a(method, sigma, q):
    # before: "register, z0, truth_at_query and sigma give a result that is not representable (LinAlgError: ...)";
    # p0 named too (fuzz 50b C2: a prior of 1e20 against sigma = 1 m reaches the same collapse)
    from fusion.scenarios.time_registration import expected
    with pytest.raises(ValueError, match=r"^sigma = .* m with q_v = .*, q_a = .* and p0 = .* leave the smoother's predicted "
                                         "covariance singular"):
        expected(method, sigma, q_v=q, q_a=q)


def test_d1_kalman_runs_names_its_arguments_and_valid_smoothing_is_unchanged():
    import numpy as np
    from fusion.registration.methods import kalman_runs
    t = np.arange(0.0, 20.0, 1.0)
    z = 0.5 * 0.3 * t**2 + 2 * t
    with pytest.raises(ValueError, match="q_v or q_a > 0, a larger sigma or a smaller p0"):
        kalman_runs(t, z, 1e-9, 0.0, 0.0, smooth=True)
    with pytest.raises(ValueError, match="q_v or q_a > 0, a larger sigma or a smaller p0"):
        kalman_runs(t, z, 1e-9, 0.0, 0.0, lag_one=True)
    # the same gain where the predicted covariance is invertible: the expression before the fix, by hand
    out = kalman_runs(t, z, 0.5, 1e-2, 1e-3, smooth=True)
    f = kalman_runs(t, z, 0.5, 1e-2, 1e-3)
    assert np.isfinite(out.x).all() and not np.array_equal(out.x, f.x)
