"""Fuzz 59b (fix 67c): regressions of C1 (an entropy list subclass's ``__iter__`` hid its words from seed_sequence),
C2 (ridge_risk's (k.size, d) arrays unbudgeted: a raw MemoryError), C3 (the ridge fusions' sensor blocks' dense work
never summed) and D1 (split_ci_objective's weights counted n**3 each, no per-weight floor). Report:
/work/tmp/fuzz59b/report.md."""

from __future__ import annotations

import numpy as np
import pytest

from fusion._limits import MAX_WORK

from _helpers import refused_quickly


# --- C1: only exact containers and integers in a SeedSequence's entropy and spawn key ------------------------------

_BIG = list(range(10**5))


class _Liar(list):
    """An entropy list whose second iteration (the package's check, after numpy's at construction) gives one word, and
    every other 10**5."""

    reads = 0

    def __iter__(self):
        type(self).reads += 1
        return iter([7]) if type(self).reads == 2 else iter(_BIG)


class _Tuple(tuple):
    pass


class _Int(int):
    pass


class _Int64(np.int64):
    pass


def test_c1_seed_sequence_refuses_a_sequence_subclass_in_its_entropy_by_name():
    from fusion._counts import seed_sequence
    _Liar.reads = 0
    liar = np.random.SeedSequence(_Liar([7]))   # numpy reads 10**5 words (its first read)
    refused_quickly(lambda: seed_sequence(liar, "seeds[0]"), TypeError, r"^seeds\[0\] .*_Liar")
    for entropy in ([1, _Tuple((2, 3))], _Tuple((1, 2))):
        refused_quickly(lambda: seed_sequence(np.random.SeedSequence(entropy), "seed"), TypeError, r"^seed .*_Tuple")


def test_c1_seed_sequence_refuses_an_integer_subclass_by_name():
    from fusion._counts import seed_sequence
    for entropy in (_Int(3), [1, _Int(3)], [_Int64(3)]):
        refused_quickly(lambda: seed_sequence(np.random.SeedSequence(entropy), "seed"), TypeError, r"^seed .*subclass")


def test_c1_seed_sequence_keeps_plain_containers_and_numpy_integers():
    from fusion._counts import seed_sequence
    for entropy in (5, np.uint64(5), [1, (2, 3)], (1, 2), range(3), np.arange(3), [np.uint32(5), np.int64(3)],
                    [np.arange(2, dtype=np.uint32), 4]):
        ss = np.random.SeedSequence(entropy)
        assert seed_sequence(ss, "seed") is ss
    child = np.random.SeedSequence(1).spawn(2)[1]
    assert seed_sequence(child, "seed") is child


def test_c1_run_tracking_batch_refuses_the_liar_before_any_spawn():
    from fusion.scenarios import range_bearing as rb
    sc = rb.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100, em_iterations=2,
                                 n_components=1)
    _Liar.reads = 0
    liar = np.random.SeedSequence(_Liar([7]))
    refused_quickly(lambda: rb.run_tracking_batch(sc, [liar], workers=1), TypeError, r"^seeds\[0\] ")


# --- C2: ridge_risk's (k.size, d) arrays -----------------------------------------------------------------------------

def test_c2_ridge_risk_refuses_k_against_a_by_memory_before_the_work():
    from fusion.readings.biased import ridge_risk
    refused_quickly(lambda: ridge_risk(np.eye(1000), np.ones(1000), np.ones(10**7)), ValueError, r"^k and A ask for an array")
    # 5 arrays of (k.size, d) held (tracemalloc, measured): 536,871 x 100 is just beyond 2**28 float64, 536,870 inside
    refused_quickly(lambda: ridge_risk(np.eye(100), np.ones(100), np.ones(536_871)), ValueError, r"^k and A ask for an array")


def test_c2_ridge_risk_edge_is_inside_both_budgets():
    from fusion._counts import allocation
    from fusion._limits import work
    from fusion.readings.biased import ridge_risk
    allocation((536_870, 100), "k and A", arrays=5)
    assert work((536_870, 100), "k and A", weight=3) <= MAX_WORK
    out = ridge_risk(2 * np.eye(3), np.ones(3), np.array([0.0, 0.5, 1.0]))
    assert out.shape == (3,) and out[0] == pytest.approx(1.5)


# --- C3: the ridge fusions' summed block work ------------------------------------------------------------------------

@pytest.mark.parametrize("fusion_name", ["ridge_centralised", "ridge_distributed", "ridge_fusion_plugin"])
def test_c3_ridge_fusions_sum_their_blocks_dense_work(fusion_name):
    from fusion.readings import biased
    m = 3000   # each block alone about 4 CPU-s (fuzz 59b); three together beyond the budget
    H, R, y = np.ones((m, 1)), np.eye(m) + 0.1, np.ones(m)
    last = 1.0 if fusion_name != "ridge_fusion_plugin" else "distributed"
    refused_quickly(lambda: getattr(biased, fusion_name)([H] * 3, [R] * 3, [y] * 3, last), ValueError,
             r"^Hs, Rs and ys ask for .* units of work")


def test_c3_two_blocks_of_3000_and_small_blocks_are_inside():
    from fusion.readings import biased
    for step in (biased._BLOCK_STEP, biased._CENTRAL_BLOCK_STEP):
        assert biased._blocks_work([(3000, 1)] * 2, step) <= MAX_WORK
        assert biased._blocks_work([(3, 2)] * 100_000, step) <= MAX_WORK
    H = np.array([[1.0, 0.5], [0.2, 1.0], [1.0, 1.0]])
    y = np.array([1.0, 2.0, 2.5])
    a = biased.ridge_centralised([H] * 3, [np.eye(3)] * 3, [y] * 3, 0.5)
    b = biased.ridge_distributed([H] * 3, [np.eye(3)] * 3, [y] * 3, 0.5)
    np.testing.assert_allclose(a, b, rtol=1e-12)


# --- D1: split_ci_objective's per-weight floor -----------------------------------------------------------------------

def test_d1_split_ci_objective_counts_each_weight_at_least_its_overhead():
    from fusion.estimates.ci import split_ci_objective
    eye = np.eye(1)   # 14,925,371 weights at n = 1: just beyond the budget at 67 units a weight (580-680 ns measured)
    refused_quickly(lambda: split_ci_objective(np.full(14_925_371, 0.5), eye, 0.5 * eye, 2 * eye, eye), ValueError,
             r"^omega, P1d, P1i, P2d and P2i ask for .* units of work")


def test_d1_split_ci_objective_edge_is_inside():
    from fusion.estimates.ci import _split_omega_units, split_ci_objective
    assert (14_925_370 + 3) * _split_omega_units(1) <= MAX_WORK < (14_925_371 + 3) * _split_omega_units(1)
    eye = np.eye(1)
    assert split_ci_objective(np.full(3, 0.4), eye, 0.5 * eye, 2 * eye, eye).shape == (3,)
