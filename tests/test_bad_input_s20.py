"""Session 20's own fixes to the bad-input rules (issue 35)."""

from __future__ import annotations

import numpy as np
import pytest

from fusion import _covariances
from fusion._covariances import COVARIANCE_RTOL, as_covariance, as_semidefinite
from fusion.filtering import tracks
from fusion.filtering.kalman import nees
from fusion.scenarios import _infrared_budget


def test_one_covariance_tolerance_for_readers_and_producers() -> None:
    # the producers that repair or refuse round-off before a reader sees it use the readers' own tolerance
    assert tracks._SYMMETRY_RTOL == COVARIANCE_RTOL
    assert _infrared_budget._SEMIDEFINITE_RTOL == COVARIANCE_RTOL
    import inspect
    for reader in (_covariances.as_covariance, _covariances.as_covariances, _covariances.covariance_pair,
                   _covariances.as_semidefinite):
        assert inspect.signature(reader).parameters["rtol"].default == COVARIANCE_RTOL


@pytest.mark.parametrize(("off", "rel"), [(1e-20, 0.1), (1e-12, 0.01), (0.3, 1e-12)])
def test_nees_reads_symmetry_by_the_readers_rule(off: float, rel: float) -> None:
    # a covariance whose small off-diagonal entries differ by a fraction of the matrix's scale far below the
    # tolerance is a covariance to every reader; nees refused it (elementwise relative rule) before
    P = np.array([[1.0, off], [off * (1 + rel), 2.0]])
    as_covariance(P)
    as_semidefinite(P, 2)
    value = nees(np.array([1.0, 1.0]), P)
    assert np.isfinite(value)
    assert value == pytest.approx(float(np.array([1.0, 1.0]) @ np.linalg.solve(0.5 * (P + P.T), [1.0, 1.0])),
                                  rel=1e-6)


def test_nees_refuses_what_the_readers_refuse() -> None:
    P = np.array([[1.0, 0.5], [0.5 + 3e-9, 1.0]])   # asymmetric by 3e-9 of its largest entry
    with pytest.raises(ValueError, match="P must be symmetric"):
        as_covariance(P)
    with pytest.raises(ValueError, match="covariances must be symmetric"):
        nees(np.array([1.0, 1.0]), P)
    # per matrix: a batch with one asymmetric step is refused, the symmetric steps' scale does not hide it
    batch = np.stack([np.eye(2) * 1e6, P])
    with pytest.raises(ValueError, match="covariances must be symmetric"):
        nees(np.ones((2, 2)), batch)


@pytest.mark.parametrize("method", ["uniform_set", "optimal_fusion_set"])
def test_fair_errors_names_z_for_its_methods_limits(method: str) -> None:
    # the inner fusion named its own ``x`` (fix52a's report); the entry checks each method's limits naming z
    from fusion.book.chapters.ofs_fair import fair_errors

    with pytest.raises(ValueError, match=r"^z \(30,000 readings"):
        fair_errors(np.zeros((1, 1, 30_000)), np.ones(30_000), methods=(method,))


def test_mixture_readers_read_symmetry_by_the_covariance_rule() -> None:
    # fuzz 46a C5: np.allclose's absolute 1e-8 accepted a 9 % asymmetric small covariance, and gm_logpdf then
    # depended on which triangle held the entry
    from fusion.estimates.chernoff.mixture import fuse_mixtures_batch
    from fusion.estimates.mixtures import GaussianMixture

    A = np.array([[1e-7, 0.0], [9e-9, 1e-7]])
    with pytest.raises(ValueError, match="covs must be symmetric"):
        GaussianMixture([1.0], [[0.0, 0.0]], [A])
    w = np.full((1, 2, 1), 1.0)
    m = np.zeros((1, 2, 1, 2))
    c = np.broadcast_to(A, (1, 2, 1, 2, 2)).copy()
    with pytest.raises(ValueError, match="covs must be symmetric"):
        fuse_mixtures_batch(w, m, c, [np.random.default_rng(0)], n_samples=10)
    # within the tolerance of its own scale: accepted (a large matrix elsewhere does not matter)
    B = np.array([[1e-7, 1e-9], [1e-9 * (1 + 1e-12), 1e-7]])
    GaussianMixture([0.5, 0.5], [[0.0, 0.0], [1.0, 1.0]], [B, 1e6 * np.eye(2)])
