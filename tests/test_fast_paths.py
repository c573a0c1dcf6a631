"""The fast paths of speed58 give what the paths they skip give (results unchanged, nothing shared)."""

from __future__ import annotations

import copy
import shutil
from pathlib import Path

import numpy as np
import pytest

from fusion._validation import _numeric, as_array
from fusion.book import _parsed_claims, claims


def _read_only(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


@pytest.mark.parametrize("make", [lambda a: a, lambda a: a[:, ::2], lambda a: a.T, np.asfortranarray, _read_only])
def test_a_plain_float_array_is_copied_never_shared(make) -> None:  # noqa: ANN001
    a = make(np.arange(12.0).reshape(3, 4))
    out = _numeric(a, "x")
    assert out.dtype == np.float64 and out.shape == a.shape and np.array_equal(out, a)
    assert not np.shares_memory(out, a) and out.flags.writeable
    out[...] = -1.0
    assert np.array_equal(a, make(np.arange(12.0).reshape(3, 4)))


@pytest.mark.parametrize("bad, error", [
    (np.ma.masked_array([1.0, 2.0], mask=[0, 1]), TypeError),          # a subclass: not the fast path
    (np.array([1.0, np.nan]), ValueError),                            # checked after the conversion, as before
    (np.array([1.0, 1e300]), ValueError),
    (np.broadcast_to(np.float64(1.0), (2**13, 2**13)), ValueError),   # beyond the input budget, refused by its shape
])
def test_the_fast_path_keeps_every_refusal(bad, error) -> None:  # noqa: ANN001
    with pytest.raises(error, match=r"^x "):
        as_array(bad, "x")


def test_a_claim_file_parsed_again_is_the_same_and_unshared(tmp_path: Path) -> None:
    src = claims.claims_dir() / "shi2023time.yaml"
    first = claims.load(src)
    assert src.read_text(encoding="utf-8") in _parsed_claims._KEPT          # kept by its text
    second = claims.load(src)
    assert second == first and second.records == first.records and second.quantities is not first.quantities
    # the same text under another name: the file's own name and path
    other = tmp_path / "other.yaml"
    shutil.copy(src, other)
    third = claims.load(other)
    assert third.path == other and third.records == first.records
    # a caller's edit of its document never reaches a later load
    kept = _parsed_claims.kept(src.read_text(encoding="utf-8"))
    kept["records"].clear()
    assert claims.load(src).records == first.records


def test_a_changed_claim_file_is_parsed_again(tmp_path: Path) -> None:
    src = claims.claims_dir() / "shi2023time.yaml"
    path = tmp_path / "shi2023time.yaml"
    text = src.read_text(encoding="utf-8")
    path.write_text(text, encoding="utf-8")
    claims.load(path)
    path.write_text(text + "\nsource: again\n", encoding="utf-8")   # a repeated key: refused, not the kept document
    with pytest.raises(claims.ClaimsFileError, match="repeated key"):
        claims.load(path)


def _tiny_runs(n: int, **kw: object) -> tuple[object, list]:
    from fusion.scenarios import range_bearing as rb

    sc = rb.RangeBearingScenario(frames=3, n_particles=200, n_components=2, n_samples=200, n_central=400, em_iterations=3,
                                 variants=False, **kw)
    return sc, rb.monte_carlo(sc, 1, n)


def test_runs_of_one_scenario_copy_it_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """``_check_runs`` compares every run's scenario with the first's without the guard's fields: one unguarded copy
    per scenario object (each copy validates the scenario again: 200 copies for 100 runs before, 16 ms)."""
    import dataclasses

    from fusion.scenarios import range_bearing as rb

    sc, runs = _tiny_runs(100)
    made = []
    monkeypatch.setattr(rb, "_unguarded", lambda s: made.append(s) or rb.dataclasses.replace(s, guard=0.0,
                                                                                              central_guard=0.0))
    assert rb._check_runs(runs, True, sc) == runs and len(made) == 1
    # a run of another scenario (the guard's fields aside) is still refused, naming it and the field
    def with_scenario(run: object, scenario: object) -> object:
        out = copy.copy(run)
        object.__setattr__(out, "scenario", scenario)
        return out

    other = with_scenario(runs[1], dataclasses.replace(sc, q=0.25))
    with pytest.raises(ValueError, match=r"^runs\[1\] was computed with another scenario .*\['q'\]"):
        rb._check_runs([runs[0], other, *runs[2:]], True)
    guarded = with_scenario(runs[1], dataclasses.replace(sc, guard=0.5))
    assert rb._check_runs([runs[0], guarded], True)[1] is guarded
