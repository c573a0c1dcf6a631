"""Budgets of uncounted factors (fuzz 35a C7, C3, C2, D3, D1; rule 17): each test counts, never runs the work.

As in ``tests/test_budget35.py``, the function's first step of work is replaced by one that raises :class:`Ran`: a
call its budget accepts raises it at once, one it refuses raises a ValueError naming the caller's argument first.
"""
import itertools

import numpy as np
import pytest


class Ran(Exception):
    """The call passed its budget and reached its work."""


def _ran(*args, **kwargs):
    raise Ran


def _mixture():
    from fusion.estimates.mixtures import GaussianMixture
    return GaussianMixture(np.array([0.4, 0.6]), np.array([[0.0, 0.0], [1.0, 1.0]]), np.stack([np.eye(2), 2 * np.eye(2)]))


@pytest.mark.parametrize("n, refused", [(19, False), (20, True), (30, True), (1000, True)])
def test_fuse_mixtures_counts_the_product_mixture(monkeypatch, n, refused):
    # C7: N two-component mixtures fuse through 2**N component tuples (about 0.5 us a tuple-mixture at d = 2):
    # 18 took 2.4 CPU-s, 30 (hours) was accepted
    import fusion.estimates.chernoff.mixture as chm
    monkeypatch.setattr(chm, "_timed_fusion", _ran)
    with pytest.raises(ValueError if refused else Ran, match="^gms and n_samples" if refused else None):
        chm.fuse_mixtures([_mixture()] * n, np.random.default_rng(0), 200)


@pytest.mark.parametrize("n, refused", [(20, False), (21, True), (24, True)])
def test_first_order_fusion_counts_the_product_mixture(monkeypatch, n, refused):
    # C7: 24 two-component mixtures raised a raw MemoryError after 8 CPU-s (20: 7 CPU-s)
    import fusion.estimates.chernoff.mixture as chm
    monkeypatch.setattr(chm, "_first_order_arrays", _ran)
    with pytest.raises(ValueError if refused else Ran, match="^gms" if refused else None):
        chm.first_order_fusion([_mixture()] * n, np.full(n, 1.0 / n))


def test_fuse_mixtures_batch_counts_the_product_mixture(monkeypatch):
    import fusion.estimates.chernoff.mixture as chm
    monkeypatch.setattr(chm, "_timed_fusion", _ran)
    g = _mixture()

    def call(B, N):
        w, m, c = (np.broadcast_to(a, (B, N) + a.shape) for a in (g.weights, g.means, g.covs))
        chm.fuse_mixtures_batch(w, m, c, [np.random.default_rng(i) for i in range(B)], 200)
    with pytest.raises(Ran):
        call(1, 19)
    with pytest.raises(ValueError, match="^weights and n_samples"):
        call(1, 20)
    with pytest.raises(ValueError, match="^weights and n_samples"):  # problems count too
        call(16, 16)
    with pytest.raises(Ran):
        call(4, 16)


def _network(n, **kw):
    from fusion.scenarios.fusion_networks import NetworkNode, NetworkScenario
    nodes = tuple(NetworkNode((float(800 + 40 * np.cos(i)), float(700 + 40 * np.sin(i))), "bearing" if i % 2 else "range")
                  for i in range(n))
    tiny = dict(n_particles=30, n_samples=30, n_components=2, em_iterations=2, stages=1)
    return NetworkScenario("n", nodes, **{**tiny, **kw})


def test_run_network_study_counts_each_nodes_product_mixture(monkeypatch):
    # C7: 20 fully connected nodes raised a raw MemoryError (25 GiB); 15 took 8.2 CPU-s, the default 12-node
    # scenario (3**12 tuples) ran over 60 s for 2 runs
    import fusion.scenarios.fusion_networks as f
    monkeypatch.setattr(f, "_local_update", _ran)
    with pytest.raises(ValueError, match="sc.nodes, sc.edges and sc.n_components"):
        f.run_network_study(_network(20, edges=tuple(itertools.combinations(range(20), 2))), 1, 2)
    with pytest.raises(ValueError, match="^runs, sc.nodes, sc.edges"):
        f.run_network_study(_network(12, n_particles=400, n_samples=400, n_components=3, em_iterations=10, stages=3),
                            1, 2)
    with pytest.raises(Ran):  # 10 fully connected nodes: 0.14 CPU-s for 2 runs
        f.run_network_study(_network(10, edges=tuple(itertools.combinations(range(10), 2))), 1, 2)


def test_run_network_study_counts_its_rounds(monkeypatch):
    # C2: a round refits and exchanges again (~0.7-1.7 ms a run-node); 10**7 rounds (~40 h) were accepted
    import fusion.scenarios.fusion_networks as f
    monkeypatch.setattr(f, "_local_update", _ran)
    with pytest.raises(ValueError, match="sc.rounds"):
        f.run_network_study(_network(2, rounds=10**7), 1, 2)
    with pytest.raises(ValueError, match="sc.rounds"):
        f.run_network_study(_network(2, rounds=5_000), 1, 2)
    with pytest.raises(Ran):
        f.run_network_study(_network(2, rounds=500), 1, 2)


def _tracking(**kw):
    from fusion.scenarios.range_bearing import RangeBearingScenario
    return RangeBearingScenario(**{**dict(frames=2, n_particles=60, n_samples=60, n_central=100, em_iterations=2), **kw})


@pytest.mark.parametrize("kw, runs, refused", [
    (dict(n_components=1, n_initial=50_000), 39_000, True),   # ~2,000 CPU-s (2.6 CPU-s per 50 runs) was accepted
    (dict(n_components=1, n_initial=50_000), 1_000, False),
    (dict(n_components=60, n_particles=200), 20_000, True),   # ~38 h (13.6 CPU-s for 2 runs) was accepted
    (dict(n_components=30, n_particles=200), 1_000, True),    # 27,000 tuples: ~0.38 CPU-s a run-frame measured
    (dict(n_components=30, n_particles=200), 100, False),
])
def test_tracking_counts_n_initial_and_the_product_mixture(monkeypatch, kw, runs, refused):
    # C3: the first frame's n_initial particles and the fusion's n_components**3 tuples were left out of the budget
    import fusion.scenarios.range_bearing as rb
    monkeypatch.setattr(rb, "_run_block", _ran)
    monkeypatch.setattr(rb, "_pool_runs", _ran, raising=False)
    with pytest.raises(ValueError if refused else Ran, match="^runs, sc.frames, sc.sensors, sc.n_initial, "
                       "sc.n_components" if refused else None):
        rb.monte_carlo(_tracking(**kw), 1, runs, all_nodes_first=False)


_CFG = {"wavelet": "db4", "level": 2, "threshold": "universal", "mode": "soft"}


@pytest.mark.parametrize("kw, refused", [
    (dict(runs=60_000), True),                                  # ~250 CPU-s were accepted
    (dict(runs=2_000), False),                                  # 8.3 CPU-s measured
    (dict(length=64, runs=2, configs=(_CFG,) * 10**6), True),   # ~12 min were accepted
    (dict(length=64, runs=2, configs=(_CFG,) * 10_000), False),
])
def test_mechanism_study_counts_its_settings_and_samples(monkeypatch, kw, refused):
    # D3: ~0.57 ms a setting and ~0.06-0.1 us a setting's sample; only the memory budget was checked
    import fusion.scenarios.wavelet_sensors as ws
    monkeypatch.setattr(ws, "config_label", _ran)  # the first step after the budget
    with pytest.raises(ValueError if refused else Ran, match="^configs, runs, gains and length" if refused else None):
        ws.mechanism_study(**kw)


@pytest.mark.parametrize("length", [16, 63, 65, 100, 200])
def test_mechanism_study_refuses_a_length_off_its_period_by_name(monkeypatch, length):
    # D1: the bias's share at period 64 needs whole periods; the class refused it after the work with an inner name
    import fusion.scenarios.wavelet_sensors as ws
    monkeypatch.setattr(ws, "_case_arrays", _ran)
    with pytest.raises(ValueError, match="^length must be"):
        ws.mechanism_study(length=length, runs=3, configs=(_CFG,))


def test_mechanism_study_keeps_lengths_of_whole_periods():
    from fusion.scenarios.wavelet_sensors import mechanism_study
    for length in (64, 192):
        assert set(mechanism_study(length=length, runs=2, configs=(_CFG,)).bias_share_period) >= {64}


@pytest.mark.parametrize("n, refused", [(20, False), (21, True)])
def test_sigma_point_first_order_counts_the_product_mixture(monkeypatch, n, refused):
    # C7 (the same class in the chapter layer): ~0.3 us a tuple-mixture, as the first-order fusion
    import fusion.book.chapters.chernoff_first_order as cfo
    monkeypatch.setattr(cfo, "_sigma_point_fusion", _ran)
    with pytest.raises(ValueError if refused else Ran, match="^gms" if refused else None):
        cfo.sigma_point_first_order([_mixture()] * n, np.full(n, 1.0 / n))
