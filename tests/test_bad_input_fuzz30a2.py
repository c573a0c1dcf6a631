"""Fuzz 30a (issue 35), cases C4, C5, C7, C8, D3 and D4 (report /work/tmp/fuzz30a/report.md).

C4: a claim-file text holding a lone surrogate (Unicode Cs) is refused by the field's name (it cannot be written
as UTF-8). D3: the Hangul fillers and the braille blank are not visible characters; ZWNJ and ZWJ stay refused.
C5: an objective returning one 0-d array it overwrites at each call: every optimiser keeps each value as it was
returned (``fusion._validation.value_copy``). C7: a ragged nested list is refused naming the argument (not numpy's
unnamed "inhomogeneous shape" error). C8/D4: a container that contains itself or is nested more than 64 deep is
refused naming the argument (frozen records, glued values), and an error message never recurses into the value.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion._shown import shown
from fusion.book import claims
from fusion.book.claims import ReadingSpec
from fusion.book.glue import _checked_keep, glue_all
from fusion.book.ledger.evidence import PublishedValues
from fusion.optimise.scalar import bounded_minimum, fruit_fly, fruit_fly_batch, grid_search
from fusion.optimise.simplex import minimise_on_simplex
from fusion.optimise.swarm import particle_swarm
from fusion.scenarios import thermocouples as th
from fusion.scenarios import time_registration as tr

from test_bad_input import REG

FEW = settings(settings.get_profile("fusion"), max_examples=8)


def _deep(n: int) -> list:
    """A list holding a list ... ``n`` levels below the outer one (``n + 1`` lists)."""
    out = inner = []
    for _ in range(n):
        inner.append([])
        inner = inner[0]
    return out


@functools.lru_cache(maxsize=1)
def _spec() -> claims.ClaimSpec:
    return claims.load(claims.claims_dir() / "lecture003.yaml").records[0]


@pytest.fixture
def spec() -> claims.ClaimSpec:
    return _spec()


# C4 -------------------------------------------------------------------------------------------------------------

@FEW
@given(st.integers(0xD800, 0xDFFF), st.sampled_from(["claim", "where", "published"]))
def test_a_lone_surrogate_is_refused_naming_the_field(code: int, field: str) -> None:
    spec = _spec()
    with pytest.raises(ValueError, match=rf"^{field} holds the lone surrogate U\+{code:04X}"):
        dataclasses.replace(spec, **{field: f"a {chr(code)} b"})


def test_a_claim_file_with_a_lone_surrogate_is_refused_by_record_and_field(tmp_path) -> None:
    src = (claims.claims_dir() / "lecture003.yaml").read_text(encoding="utf-8")
    i = src.index("\n  where:")
    j = src.index("\n", i + 1)
    path = tmp_path / "lecture003.yaml"
    path.write_text(src[:i] + '\n  where: "\u00a72.1 \\uD800 here"' + src[j:], encoding="utf-8")
    with pytest.raises(claims.ClaimsFileError, match=r"record lec-[a-z-]+: field where holds the lone surrogate"):
        claims.load(path)


# D3 -------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("blank", ["\u3164", "\uffa0", "\u115f", "\u2800", " \u3164 \u2800 "])
def test_a_text_of_only_blank_letters_is_empty(spec: claims.ClaimSpec, blank: str) -> None:
    with pytest.raises(ValueError, match="^where must not be empty"):
        dataclasses.replace(spec, where=blank)
    assert dataclasses.replace(spec, where=f"Sec. 2{blank}").where == f"Sec. 2{blank}"  # beside text: as a space


@pytest.mark.parametrize("joiner", ["\u200c", "\u200d"])
def test_zero_width_joiners_stay_refused(spec: claims.ClaimSpec, joiner: str) -> None:
    with pytest.raises(ValueError, match=rf"^claim holds the invisible control or format character U\+{ord(joiner):04X}"):
        dataclasses.replace(spec, claim=f"a{joiner}b")


# C5 -------------------------------------------------------------------------------------------------------------

def _buffered(vectorised: bool = False):
    """``(x - 0.3)**2`` written into one array it returns at every call (a reused output buffer)."""
    buf = np.empty(())

    def f(x):
        if vectorised:
            return np.asarray((np.asarray(x) - 0.3) ** 2, dtype=float)
        buf[...] = (x - 0.3) ** 2
        return buf
    return f


def _plain(x):
    return (x - 0.3) ** 2


@pytest.mark.parametrize("run", [
    lambda f: grid_search(f, 11),
    lambda f: fruit_fly(f, np.random.default_rng(1), population=5, iterations=5),
    lambda f: bounded_minimum(f),
], ids=["grid_search", "fruit_fly", "bounded_minimum"])
def test_an_objective_reusing_its_output_buffer_gives_the_plain_result(run) -> None:
    got, want = run(_buffered()), run(_plain)
    assert (got.x, got.fun) == (want.x, want.fun)
    assert got.fun == _plain(got.x)


def test_every_batch_optimiser_keeps_each_value_as_returned() -> None:
    """The vectorised optimisers (one call per generation) with a fitness that overwrites one returned array."""
    buf = np.empty(5)

    def fitness(eps):
        buf[:] = -((eps[:, 0] - 0.3) ** 2)
        return buf
    got = particle_swarm(fitness, 2, np.random.default_rng(2), n_particles=5, iterations=5)
    want = particle_swarm(lambda e: -((e[:, 0] - 0.3) ** 2), 2, np.random.default_rng(2), n_particles=5, iterations=5)
    assert got.fun == want.fun and np.array_equal(got.x, want.x)
    out = np.empty(1)

    def f1(e):
        out[0] = (e[0] - 0.3) ** 2
        return out[0:1].reshape(())
    assert minimise_on_simplex(f1, 2).fun == minimise_on_simplex(lambda e: (e[0] - 0.3) ** 2, 2).fun
    b2 = np.empty((1, 5))

    def fb(s):
        b2[...] = (s - 0.3) ** 2
        return b2
    [r] = fruit_fly_batch(fb, [np.random.default_rng(3)], population=5, iterations=5)
    [w] = fruit_fly_batch(lambda s: (s - 0.3) ** 2, [np.random.default_rng(3)], population=5, iterations=5)
    assert (r.x, r.fun) == (w.x, w.fun)


# C7 -------------------------------------------------------------------------------------------------------------

_RAGGED = st.lists(st.integers(0, 9), max_size=3)  # [row, 2]: a list beside a number, always ragged


def _unnamed_numpy(exc: BaseException) -> bool:
    return "inhomogeneous" in str(exc) or "array element with a sequence" in str(exc)


@pytest.mark.parametrize("fn", ["inject_failure", "random_failure"])
def test_ragged_samples_are_refused_by_name(fn: str) -> None:
    kwargs = {k: a.value for k, a in REG[f"fusion.scenarios.thermocouples.{fn}"].items()}
    with pytest.raises(TypeError, match="^samples ") as info:
        getattr(th, fn)(**{**kwargs, "samples": [[50], 80]})
    assert not _unnamed_numpy(info.value)


@FEW
@given(_RAGGED)
def test_ragged_decimals_are_refused_by_name(ragged: list) -> None:
    with pytest.raises(TypeError, match="^decimals ") as info:
        PublishedValues([1.0, 2.0], [1.0, 2.0], [ragged, 2])
    assert not _unnamed_numpy(info.value)


@pytest.mark.parametrize("run", [bounded_minimum, lambda f: grid_search(f, 5), lambda f: fruit_fly(
    f, np.random.default_rng(0), population=2, iterations=2)], ids=["bounded_minimum", "grid_search", "fruit_fly"])
def test_a_ragged_objective_value_is_refused_naming_f(run) -> None:
    with pytest.raises(TypeError, match=r"^the values returned by f must be an array_like") as info:
        run(lambda x: [[1], 2])
    assert not _unnamed_numpy(info.value)


# C8 / D4 --------------------------------------------------------------------------------------------------------

def _itself_list() -> list:
    out: list = [1]
    out.append(out)
    return out


def _itself_dict() -> dict:
    out: dict = {"a": 1}
    out["b"] = out
    return out


@pytest.mark.parametrize("settings_", [{"x": _itself_list()}, _itself_dict(), {"x": _deep(3000)}, {"x": _deep(63)}],
                         ids=["list-itself", "dict-itself", "3000-deep", "65-deep"])
def test_reading_settings_containing_themselves_or_too_deep_are_refused(settings_: dict) -> None:
    with pytest.raises(ValueError, match=r"^settings must not (hold a container that contains itself|nest contain)"):
        ReadingSpec("primary", "c", "r", "primary", settings_, None)


def test_reading_settings_64_deep_and_shared_are_kept() -> None:
    shared = [1.0]
    r = ReadingSpec("primary", "c", "r", "primary", {"x": _deep(62), "a": shared, "b": [shared, shared]}, None)
    assert r.settings["b"] == ((1.0,), (1.0,)) and isinstance(r.settings["x"], tuple)


@pytest.mark.parametrize("names", [_deep(1000), ["ekf", _deep(1000)], [_itself_list()]], ids=["deep", "entry", "itself"])
def test_an_unknown_name_is_refused_without_recursing_into_it(names: list) -> None:
    kwargs = {k: a.value for k, a in REG["fusion.scenarios.time_registration.monte_carlo"].items()}
    with pytest.raises(ValueError, match="^names must be keys of METHODS"):
        tr.monte_carlo(**{**kwargs, "names": names})


def test_shown_cuts_a_long_list_without_building_its_whole_repr() -> None:
    class Loud(float):
        calls = 0

        def __repr__(self) -> str:
            Loud.calls += 1
            return "1.0"
    text = shown([Loud(1.0)] * 10**4)
    assert text.endswith("... (10,000 entries)") and Loud.calls <= 80
    assert shown(_deep(5000)) == "a list"


def test_a_glued_value_nested_too_deep_is_refused_naming_its_key() -> None:
    with pytest.raises(ValueError, match=r"^values\['x-a'\] must not nest containers more than 64 deep"):
        glue_all({"x-a": _deep(500)})
    store: dict = {}
    _checked_keep(store, {"x_a": _deep(63), "x_b": _itself_list()})  # 64 deep (numpy's limit) and [1, [...]]: kept
