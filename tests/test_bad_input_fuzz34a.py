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
    _DOUBLED.clear()
    assert double(1) == 2
    (tmp_path / "sub" / "c").rename(tmp_path / "old")
    (tmp_path / "sub").rmdir()
    (tmp_path / "sub").write_text("a file")
    with pytest.raises(ValueError, match=sc_mod.ENV):
        double(2)
    assert _DOUBLED == [1]


_DOUBLED: list = []


@study_cache(0)
def double(x):
    """Module-level: only a function its module holds under its name reaches the disk (fuzz 34a D2)."""
    _DOUBLED.append(x)
    return 2 * x


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
        far = np.tile(r.normal(300, 50, (1, 2)), (10, 1)) + r.normal(0, 1e-9, (10, 2))
        x = np.vstack([r.normal(0, 1, (10, 2)), far])
        w = np.r_[np.ones(10), np.full(10, 1e-3)]
        fit = weighted_em(x, w, 2, rng=np.random.default_rng(seed), floor=0.0)
        assert np.all(np.linalg.eigvalsh(fit.mixture.covs) > 0)
        assert np.all(np.isfinite(fit.loglik))
        assert 1 <= fit.mixture.weights.size <= 2


def _special(tmp_path, kind, name):
    path = tmp_path / name
    if kind == "fifo":
        os.mkfifo(path)
    else:   # a sparse file above the size limit: no disk used
        with open(path, "wb") as fh:
            fh.truncate((16 << 20) + 1)
    return path


@pytest.mark.parametrize("kind", ["fifo", "huge"])
def test_claim_readers_refuse_special_and_huge_files(tmp_path, kind):
    """C3, C4: a FIFO (it hung) or a file above 16 MB (a MemoryError at 30 GB) is refused by name before reading."""
    from fusion.book import claims
    path = _special(tmp_path, kind, "a.yaml")
    with pytest.raises(ValueError, match="^path .*not a readable file"):
        claims.load(path)
    with pytest.raises(ValueError, match="not a readable file"):
        claims.load_all(tmp_path)


def test_claims_load_refuses_a_device():
    """C3: ``/dev/zero`` never ends."""
    from fusion.book import claims
    with pytest.raises(ValueError, match="^path .*not a regular file"):
        claims.load("/dev/zero")


@pytest.mark.parametrize("kind", ["fifo", "huge"])
def test_source_digest_refuses_special_and_huge_sources(tmp_path, kind):
    """C3, C4: a package holding a FIFO or a huge ``.py`` is refused naming ``package``."""
    (tmp_path / "__init__.py").write_text("")
    _special(tmp_path, kind, "m.py")
    with pytest.raises(ValueError, match="^package: .*not a readable file"):
        sc_mod.source_digest(tmp_path)


def test_json_record_refuses_huge_file(tmp_path):
    """C4: a benchmark result above the size limit is refused by name before reading."""
    from fusion.book._json import read_object
    path = _special(tmp_path, "huge", "ci.json")
    with pytest.raises(ValueError, match="^benchmark result .*larger than"):
        read_object(path, "benchmark result")


@pytest.mark.parametrize("log", ["fifo", "/dev/full"])
def test_log_variable_refuses_special_files_before_the_work(tmp_path, monkeypatch, log):
    """C3: FUSION_STUDY_CACHE_LOG naming a FIFO hung every cached call; ``/dev/full`` failed after the work."""
    monkeypatch.setenv(sc_mod.ENV, str(tmp_path / "c"))
    monkeypatch.setenv(sc_mod.LOG_ENV, str(_special(tmp_path, "fifo", "log")) if log == "fifo" else log)
    calls = []

    @study_cache(0)
    def double(x):
        calls.append(x)
        return 2 * x

    with pytest.raises(ValueError, match=sc_mod.LOG_ENV):
        double(1)
    assert calls == []
