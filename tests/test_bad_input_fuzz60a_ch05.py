"""Fuzz 60a on chapter 05 (C2, D1, C4, C5): entries read and counted at the entry of the public function.

C2/D1: ``paired_studies`` never read ``fig6_omegas``' entries (an array entry reached numpy's raw truth-value error,
1.5 was refused naming ``omega`` after 1.7 CPU-s of scenarios, a repeat was counted twice and kept once). C4: under
``MAX_WORK`` ``ir_sigma_band`` refused the readings ``ir_readings`` returns from ~1,560 runs (its producer accepts
~4,200; the sweep's 10x reading, 2,000 runs, was refused though its band ran 6.3 CPU-s). C5: ``fig5_hypotheses``
counted ``flat_pair``'s grid on ``P1``'s size (m = 3,000, n_open = 8 refused naming ci_objective's P1 and P2 after 13.5
CPU-s).
"""

from __future__ import annotations

import numpy as np
import pytest

from test_study_budget61 import Ran, _accepts, _edge, _reaches_the_draw, no_draw  # noqa: F401

from _helpers import refused_quickly


@pytest.fixture(scope="module")
def pairs():
    from fusion.book.chapters.ci import studies as S

    return S.unequal_pair(S.SEED), S.aniso_pair(S.SEED, 100)


def test_paired_studies_reads_each_fig6_omega(pairs, no_draw):
    from fusion.book.chapters import ci

    Q, R1, R2 = ci.printed_covariances()

    def call(omegas):
        return ci.paired_studies(R1, R2, Q, (ci.W_PUB, ci.W_GRID), *pairs, runs=2_000, seeds=(1, 2, 3), weight_seed=4,
                                 fig6_omegas=omegas)

    refused_quickly(lambda: call((np.array([0.1, 0.2]), ci.W_PUB, ci.W_GRID)), TypeError, r"^fig6_omegas\[0\]")
    refused_quickly(lambda: call((ci.W_PUB, ci.W_GRID, np.full(261, 0.3))), TypeError, r"^fig6_omegas\[2\]")
    refused_quickly(lambda: call((ci.W_PUB, ci.W_GRID, 1.5)), ValueError, r"^fig6_omegas\[2\]")
    refused_quickly(lambda: call((ci.W_PUB, ci.W_GRID, "a")), TypeError, r"^fig6_omegas\[2\]")
    refused_quickly(lambda: call((ci.W_PUB, ci.W_PUB, ci.W_GRID)), ValueError, r"^fig6_omegas must not repeat")   # D1
    _reaches_the_draw(lambda: call((ci.W_PUB, ci.W_GRID, np.float64(0.5), 1)))   # weights in [0, 1], as fuse_tracks


@pytest.fixture(scope="module")
def readings():
    from fusion.book.chapters import ci

    return ci.ir_readings(0.1, 1, 3)


def test_ir_sigma_band_accepts_what_ir_readings_returns(readings, monkeypatch):
    from fusion.book.chapters import ci
    from fusion.book.chapters.ci import infrared_readings as R
    from fusion.scenarios import infrared_radar as ir

    names = "T, duration, runs and scaled_axes"
    edge = _edge(_accepts(lambda r: R._readings_budget(0.1, 10.0, r, 1, names)), hi=6_000)
    assert edge > 2_000   # the sweep's 10x reading, refused by the band at 1.28e9 units (fuzz 60a C4)
    parts = R._sigma_parts

    def ran(*args, **kwargs):
        raise Ran

    monkeypatch.setattr(ir, "cartesian_tracks", ran)
    # the band counted on readings of the producer's largest runs (its scans as the readings'): accepted
    monkeypatch.setattr(R, "_sigma_parts", lambda runs, K, levels, names: parts(edge, K, levels, names))
    _reaches_the_draw(lambda: ci.ir_sigma_band(readings))
    refused_quickly(lambda: ci.ir_sigma_band(readings, [1.0 + 1e-3 * i for i in range(200)]), ValueError,
             r"^scan \(with the runs and scans of readings\)")


def test_fig5_hypotheses_counts_the_flat_pair_at_entry(monkeypatch):
    from fusion._limits import DENSE_CUBE, MAX_WORK
    from fusion.book.chapters.ci import checks
    from fusion.book.chapters.ci.weights import fig5_hypotheses
    from fusion.scenarios.two_sensor import fruit_fly_over_seeds

    P1, P2 = np.diag([1.0, 4.0]), np.diag([4.0, 1.0])
    seeds = fruit_fly_over_seeds(P1, P2, [0, 1], iterations=2)
    names = r"^flat_pair and n_open \(the grid k/n_open on flat_pair's size\)"

    def call(m, n_open):
        F = np.eye(m)
        return fig5_hypotheses(P1, P2, seeds, 0, n_open=n_open, flat_pair=(F, F))

    refused_quickly(lambda: call(600, 300), ValueError, names + " ask for an array")   # named ci_objective's P1 and P2
    refused_quickly(lambda: call(3_000, 8), ValueError, names + " ask for")            # the same after 13.5 CPU-s
    # the work's edge at m = 1,500: n_open + 8 cubes of 0.01 units
    m = 1_500
    n = int(MAX_WORK / (DENSE_CUBE * m**3)) - 8
    F = np.eye(m)
    assert all(np.array_equal(g, F) for g in checks._flat_pair_read([F, F], n))   # inside: accepted by the budget
    refused_quickly(lambda: call(m, n + 1), ValueError, names + " ask for")
    assert checks._flat_pair_read(None, 10**9) is None


def test_d2_stream_of_reads_a_generator_by_the_one_rule():
    """Fuzz 60a D2: ``records.stream_of`` read a Generator subclass's state and raised a raw AttributeError for a
    non-Generator; now the package's rng rule (``fusion._counts.as_rng``), naming ``rng``."""
    from fusion.book.chapters.ci.records import stream_of

    class Sub(np.random.Generator):
        pass

    assert stream_of(np.random.default_rng(3)) == stream_of(np.random.default_rng(3)) != stream_of(np.random.default_rng(4))
    with pytest.raises(TypeError, match=r"^rng must be a numpy.random.Generator itself, not a subclass"):
        stream_of(Sub(np.random.PCG64(3)))
    with pytest.raises(TypeError, match=r"^rng must be a numpy.random.Generator, got int"):
        stream_of(3)
