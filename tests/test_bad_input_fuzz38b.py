"""Fuzz 38b (chapter layer, issue 35): stability records as make stability writes them (C1), a caller's
{method: value} mapping beside a study (C2, D3), glue_27 at correlated_study's conditioning edge (C3), figure glue keys
(C4), the benchmark's speed ratio (C5), nees_start's default T (D1), hand-made cache entries (D2) and explain's order
shape (D4). Chapter registries are not imported here: each test builds only what it needs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

# ---------------------------------------------------------------- C1: stability records of make stability

_RID, _SEEDS = "lec-awf-estimated", [11, 12, 13, 14, 15]


def _sweep(tmp_path: Path, runs_factor: int, fail_seed: int | None = None, fail_scaled: bool = False,
           status: str = "reproduced") -> Path:
    """A stability file written as ``stability.main`` writes it (records by ``summarise``), under a book root."""
    from fusion.book import stability as S
    res = []
    for s in _SEEDS:
        t = S.Task("lec", _RID, "primary", "primary", s, 300)
        res.append(S.TaskResult(t, None, 1.0, "RuntimeError('x')") if s == fail_seed else S.TaskResult(t, status, 1.0))
    if runs_factor > 1:
        t = S.Task("lec", _RID, "primary", "primary", _SEEDS[0], 300 * runs_factor, scaled=True)
        res.append(S.TaskResult(t, None, 1.0, "RuntimeError('x')") if fail_scaled else S.TaskResult(t, status, 1.0))
    records = S.summarise(res, _SEEDS, {_RID: "reproduced"})
    for v in records.values():
        v.update(commit="abc", runs_factor=runs_factor)
    doc = {"root_seed": 1, "K": 5, "seeds": _SEEDS, "runs_factor": runs_factor, "readings": {}, "records": records}
    (tmp_path / "book/ledger").mkdir(parents=True)
    (tmp_path / "_toc.yml").write_text("format: jb-book\n")
    (tmp_path / "book/ledger/stability.json").write_text(json.dumps(doc, indent=1) + "\n")
    return tmp_path


def _line(root: Path) -> str:
    from fusion.book.chapters.lecture_weighting.records import reseeding_glue
    return reseeding_glue([{"id": _RID, "status": "reproduced", "runs": 300}], root)["lec_rs_awf_estimated"]


@pytest.mark.parametrize("runs_factor, fail_seed, fail_scaled, want", [
    (3, None, False, "stable in 5 of 5 reseeds and at 3× the runs"),
    (1, None, False, "stable in 5 of 5 reseeds"),
    (3, 13, False, "stable in 4 of 5 reseeds and at 3× the runs (1 of 5 reseeds failed to run)"),
    (3, None, True, "stable in 5 of 5 reseeds (the run at 3× the runs failed)"),
    (1, 11, False, "stable in 4 of 5 reseeds (1 of 5 reseeds failed to run)"),
])
def test_c1_records_make_stability_writes_are_glued(tmp_path: Path, runs_factor: int, fail_seed: int | None,
                                                     fail_scaled: bool, want: str) -> None:
    line = _line(_sweep(tmp_path, runs_factor, fail_seed, fail_scaled))
    assert line == f"reproduced at the chapter's 300 runs, {want}"


def test_c1_a_failed_reseed_beside_a_moved_one(tmp_path: Path) -> None:
    """A record that moved names its failures too; one that only failed is not said to move."""
    root = _sweep(tmp_path, 3, 13, status="contradicted")
    line = _line(root)
    assert "moves under reseeding" in line and "1 of 5 reseeds failed to run" in line


@pytest.mark.parametrize("k", [5, -1])
def test_c1_k_above_the_reseeds_that_ran_is_refused(tmp_path: Path, k: int) -> None:
    root = _sweep(tmp_path, 3, 13)
    f = root / "book/ledger/stability.json"
    doc = json.loads(f.read_text())
    doc["records"][_RID]["k"] = k
    f.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"root: .*'k' must count the reseeds that ran"):
        _line(root)


# ---------------------------------------------------------------- C2, D3: {method: value} beside a study

@pytest.fixture(scope="module")
def _ci_leg():
    import numpy as np
    from fusion.book.chapters import ci
    from fusion.scenarios import two_sensor
    Q, R1, R2 = ci.printed_covariances()
    sc = two_sensor.two_sensor_scenario(R1, R2, Q, np.random.default_rng(0), runs=2, T=8.0)
    study = two_sensor.fusion_study(sc, np.full(sc.t.size, 0.5), np.full(sc.t.size, 0.5), published_omega=0.5)
    return ci, study, ci.straight_leg(study, 8.0, 150.0)


def test_c2_rmse_numbers_takes_exactly_the_methods_straight_leg_gives(_ci_leg) -> None:
    ci, study, leg = _ci_leg
    ci.rmse_numbers(study, leg.floor, leg.steady, leg.rmse, leg.causal)   # valid: every method, any mapping order
    ci.rmse_numbers(study, leg.floor, leg.steady, dict(reversed(list(leg.rmse.items()))), leg.causal)
    extra = {**leg.rmse, "zz_extra": 1.0}
    with pytest.raises(ValueError, match=r"^leg_rmse must hold exactly the study's methods.* holds \['zz_extra'\]"):
        ci.rmse_numbers(study, leg.floor, leg.steady, extra, leg.causal)
    first = next(iter(leg.rmse))
    lacking = {k: v for k, v in leg.rmse.items() if k != first}
    with pytest.raises(ValueError, match=r"^leg_rmse must hold exactly the study's methods.* lacks"):
        ci.rmse_numbers(study, leg.floor, leg.steady, lacking, leg.causal)


# ---------------------------------------------------------------- C3: glue_27 at correlated_study's edge

@pytest.mark.parametrize("sigma, env", [((1e-3, 1.0, 2.0), 316.227), ((0.003, 1.0), 948.6823), ((1.0, 1.0), 223607.0)])
def test_c3_glue_27_glues_every_study_correlated_study_accepts_at_its_edge(sigma: tuple, env: float) -> None:
    """sigma_env bisected to the producer's own edge (60 halvings): the last accepted study is glued."""
    from fusion.scenarios.lecture_correlated import correlated_study
    from fusion.book.chapters.lecture_correlated.correlated import glue_27

    def study(e: float):
        try:
            return correlated_study(sigma=sigma, sigma_env=e, runs=2, sizes=(600,))
        except ValueError:
            return None

    lo, hi = env * 0.9, env * 1.1
    assert study(lo) is not None and study(hi) is None
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if study(mid) is not None else (lo, mid)
    glue_27(study(lo))


# ---------------------------------------------------------------- C4: one whole-key rule for every glue path

_KEYS_REFUSED = ["lec-fig a", "lec-fig-e\u0301", "lec-fig\n", "\ufb01g", "\uff46ig", ""]


@pytest.mark.parametrize("key", _KEYS_REFUSED)
def test_c4_figure_glue_keys_follow_glue_alls_rule(key: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from fusion.book.chapters.lecture import glue_figures
    from fusion.book.figures import glue_figure
    from fusion.book.glue import glue_all

    fig = plt.figure()
    try:
        with pytest.raises(ValueError, match="^values must have glue keys of ASCII"):
            glue_all({key: 1.0})
        with pytest.raises(ValueError, match="^figures must have glue keys of ASCII"):
            glue_figures({"lec-fig-ok": fig, key: fig})   # checked before the first is glued
        with pytest.raises(ValueError, match="^key must be a non-empty glue key of ASCII"):
            glue_figure(key, fig)
        assert plt.fignum_exists(fig.number)   # nothing glued, nothing closed
    finally:
        plt.close(fig)


# ---------------------------------------------------------------- C5: the swarm's time ratio in words

def _bench_text(tmp_path: Path, ratio: float) -> str:
    from fusion.book.chapters.chernoff import swarm
    root = Path(__file__).resolve().parents[1]
    doc = json.loads((root / "benchmarks/results/chernoff.json").read_text())
    for m in doc["measurements"]:
        if m.get("key") == "pso_over_slsqp":
            m["value"] = ratio
    path = tmp_path / "bench.json"
    path.write_text(json.dumps(doc))
    return swarm.benchmark_cost(path)[1]["chf_pso_ratio_text"].split(" (benchmark of")[0]


@pytest.mark.parametrize("ratio, want", [(6.837220283231126, "7 times slower"), (1.2, "1.20 times slower"),
                                         (1.0, "about as fast"), (0.995, "about as fast"),
                                         (0.6, "1.67 times faster"), (0.4, "3 times faster"),
                                         (1e-6, "1000000 times faster")])
def test_c5_a_ratio_below_one_is_glued_as_faster(tmp_path: Path, ratio: float, want: str) -> None:
    assert _bench_text(tmp_path, ratio) == want


# ---------------------------------------------------------------- D1: nees_start's default T named by the study

def test_d1_nees_start_default_T_is_named_by_true_start() -> None:
    import numpy as np
    from fusion.book.chapters import ci
    Q, R1, R2 = ci.printed_covariances()
    x0 = np.array([0.0, 0.0, 100.0, 50.0])
    st = {s: ci.nees_per_step(np.random.default_rng(1), Q, R1, R2, x0, 30, 3, T=8.0, random_velocity=s)
          for s in (False, True)}
    exact = ci.split_ci_exactness(Q, R1, 8.0, 30)
    with pytest.raises(ValueError, match=r"^true_start does not fit nees_start_table's default T = 1\.0 .*pass T"):
        ci.nees_start_table(st[False], st[True], 3, t_steady=16.0)
    with pytest.raises(ValueError, match=r"^true_start does not fit nees_start_numbers's default T = 1\.0"):
        ci.nees_start_numbers(st[False], st[True], 3, exact, t_steady=16.0)
    with pytest.raises(ValueError, match=r"^T = 2 s must be the sampling period"):   # passed: the caller's T named
        ci.nees_start_table(st[False], st[True], 3, T=2.0, t_steady=6.0)
    ci.nees_start_table(st[False], st[True], 3, T=8.0, t_steady=16.0)


# ---------------------------------------------------------------- D2: a hand-made cache entry keyed by an array

_D2_CALLS: list = []


def _d2_cached_impl(seed: int) -> tuple:
    _D2_CALLS.append(seed)
    return (seed, "computed")


def _d2_cached(seed: int) -> tuple:   # replaced below by its cached form, under its module name (fuzz 34a D2)
    return _d2_cached_impl(seed)


def _d2_setup() -> None:
    from fusion.book import study_cache as sc
    global _d2_cached
    if not hasattr(_d2_cached, "cache_clear"):
        _d2_cached = sc.study_cache(maxsize=4)(_d2_cached)


@pytest.mark.parametrize("make_key", ["array", "array of the key", "series"])
def test_d2_an_entry_keyed_by_anything_but_its_str_is_a_miss(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                              make_key: str) -> None:
    import pickle

    import numpy as np
    import pandas as pd
    from fusion.book import study_cache as sc
    _d2_setup()
    monkeypatch.setenv(sc.ENV, str(tmp_path))
    _D2_CALLS.clear()
    _d2_cached.cache_clear()
    assert _d2_cached(3) == (3, "computed")
    (entry,) = tmp_path.glob("*.pkl")
    key = pickle.loads(entry.read_bytes()[sc._DIGEST:])[0]   # the key the cache wrote for the call (after its digest)
    bad = {"array": np.array([1, 2]), "array of the key": np.array([key]), "series": pd.Series([key, key])}[make_key]
    entry.write_bytes(sc._entry(bad, "forged"))   # with a matching digest (fuzz 40b C3): only the key makes it a miss
    _d2_cached.cache_clear()
    assert _d2_cached(3) == (3, "computed") and _D2_CALLS == [3, 3]   # a miss: recomputed, never the forged value


# ---------------------------------------------------------------- D4: explain's order, one order of six

def test_d4_explain_takes_one_order_as_a_row_or_a_single_row_array() -> None:
    import numpy as np
    from fusion.book.chapters import ofs_audit as oa
    c = oa.Correction(0, 0, np.nan, "none")
    program = next(iter(oa.PROGRAMS))
    o = np.array([5, 4, 3, 2, 1, 0])
    want = oa.explain(c, program, order=o)
    assert want.equals(oa.explain(c, program, order=o.reshape(1, 6)))   # the documented (1, 6)
    assert want.equals(oa.explain(c, program, order=[o.tolist()]))
    with pytest.raises(ValueError, match=r"^order must have shape \(6,\) or \(1, 6\) \(one order .*got \(1, 1, 6\)"):
        oa.explain(c, program, order=o.reshape(1, 1, 6))
    with pytest.raises(ValueError, match=r"^order must have shape .*got \(2, 6\)"):
        oa.explain(c, program, order=np.stack([o, o]))
