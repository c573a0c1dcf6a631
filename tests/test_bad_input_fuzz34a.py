"""Fuzz 34a (issue 35): the study cache's keys and folder, claim paths, and the batched EM's collapsed components."""

from __future__ import annotations

import enum
import os
from collections import namedtuple

import numpy as np
import pytest

from fusion.book import study_cache as sc_mod
from fusion.book.study_cache import study_cache


def test_rebound_namedtuple_and_enum_are_other_keys_in_process(monkeypatch):
    """C1: a class re-bound under its name (a notebook cell re-run) is keyed by identity in the process."""
    monkeypatch.delenv(sc_mod.ENV, raising=False)

    @study_cache(8)
    def first(p):
        return p.x

    @study_cache(8)
    def name(m):
        return m.name

    global P, Mode
    P = namedtuple("P", "x y")
    assert first(P(1, 2)) == 1
    P = namedtuple("P", "y x")
    assert first(P(1, 2)) == 2

    class Mode(enum.Enum):
        A = 1
        B = 2
    assert name(Mode.B) == "B"

    class Mode(enum.Enum):  # noqa: F811 - re-bound on purpose
        A = 2
        B = 1
    assert name(Mode.B) == "B"


def test_disk_key_tells_rebound_classes_apart():
    """C1: on disk (no identity across processes) the key holds a fingerprint of the class's definition."""
    global Q
    Q = namedtuple("Q", "x y")
    k1 = sc_mod.study_key("m.f", {"p": Q(1, 2)}, digest="d")
    Q = namedtuple("Q", "y x")
    k2 = sc_mod.study_key("m.f", {"p": Q(1, 2)}, digest="d")
    assert k1 != k2

    global E
    E = enum.Enum("E", [("A", 1), ("B", 2)])
    e1 = sc_mod.study_key("m.f", {"p": E.B}, digest="d")
    E = enum.Enum("E", [("A", 2), ("B", 1)])
    e2 = sc_mod.study_key("m.f", {"p": E.A}, digest="d")
    assert e1 != e2


def test_relative_cache_folder_is_resolved_when_checked(tmp_path, monkeypatch):
    """C2: a relative FUSION_STUDY_CACHE is the folder under the working directory of each check."""
    (tmp_path / "wA" / "sub").mkdir(parents=True)
    (tmp_path / "wB").mkdir()
    (tmp_path / "wB" / "sub").write_text("a file")
    monkeypatch.setenv(sc_mod.ENV, "sub/c")
    monkeypatch.delenv(sc_mod.LOG_ENV, raising=False)

    @study_cache(0)
    def double(x):
        return 2 * x

    monkeypatch.chdir(tmp_path / "wA")
    assert double(1) == 2
    monkeypatch.chdir(tmp_path / "wB")
    with pytest.raises(ValueError, match=sc_mod.ENV):
        double(2)


def test_cache_folder_replaced_after_the_check(tmp_path, monkeypatch):
    """C2: a folder that became unusable after it was probed: ValueError naming the variable, before the work."""
    (tmp_path / "sub").mkdir()
    monkeypatch.setenv(sc_mod.ENV, str(tmp_path / "sub" / "c"))
    monkeypatch.delenv(sc_mod.LOG_ENV, raising=False)
    calls = []

    @study_cache(0)
    def double(x):
        calls.append(x)
        return 2 * x

    assert double(1) == 2
    (tmp_path / "sub" / "c").rename(tmp_path / "old")
    (tmp_path / "sub").rmdir()
    (tmp_path / "sub").write_text("a file")
    with pytest.raises(ValueError, match=sc_mod.ENV):
        double(2)
    assert calls == [1]


def test_claims_load_nul_names_path():
    """C5: a NUL byte in the path is refused naming ``path``."""
    from fusion.book import claims
    with pytest.raises(ValueError, match="^path "):
        claims.load("a\0b")


def test_em_drops_a_component_collapsed_below_the_floor():
    """C6: a component collapsed onto coincident light samples came out of the M-step indefinite (a raw
    LinAlgError in run_network_study's batched EM): it is dropped, as a component whose weight vanished."""
    from fusion.estimates.mixtures import weighted_em

    for seed in (34, 36, 37):   # each refused ("Matrix is not positive definite") before the fix
        r = np.random.default_rng(seed)
        x = np.vstack([r.normal(0, 1, (10, 2)), np.tile(r.normal(300, 50, (1, 2)), (10, 1)) + r.normal(0, 1e-9, (10, 2))])
        w = np.r_[np.ones(10), np.full(10, 1e-3)]
        fit = weighted_em(x, w, 2, rng=np.random.default_rng(seed), floor=0.0)
        assert np.all(np.linalg.eigvalsh(fit.mixture.covs) > 0)
        assert np.all(np.isfinite(fit.loglik))
        assert 1 <= fit.mixture.weights.size <= 2
