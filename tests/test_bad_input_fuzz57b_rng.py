"""Fuzz 57b C1: a random generator argument is a ``numpy.random.Generator`` itself, over one of numpy's bit generators.

A Generator subclass whose ``uniform``/``normal``/``random`` returned NaN, 1e300 or raised was accepted by the shared
readers (``as_rng``/``as_rngs``) and by ``gauss_markov_gap``'s own check: the gap came out NaN, ``systematic_resample``
gave a plausible wrong resample, ``weighted_em`` a raw IndexError. The sweep below runs over every registry entry
(package and chapter layer) with a Generator (or a list of them) among its arguments: each refuses a subclass, and a
Generator over a bit generator other than numpy's own, with a TypeError naming the argument.
"""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from test_bad_input import CALLABLES, REG, _fresh, public_callables  # noqa: E402

#: The chapter registries with an rng-taking function (ch010307 has none).
_CHAPTER_REGISTRIES = ("test_bad_input_calls_ch0204", "test_bad_input_calls_ch05", "test_bad_input_calls_ch06")


class _NaNGenerator(np.random.Generator):
    """Draws NaN (fuzz 57b C1's first probe)."""

    def uniform(self, *a: Any, **k: Any) -> Any:
        return np.full(k.get("size") or 1, np.nan)

    normal = random = uniform


class _OtherBits(np.random.PCG64):
    """A bit generator subclass: it may hand the Generator other C functions through ``capsule``."""


def _subclass(i: int) -> np.random.Generator:
    return _NaNGenerator(np.random.PCG64(i))


def _other_bits(i: int) -> np.random.Generator:
    return np.random.Generator(_OtherBits(i))


def _is_generators(v: Any) -> bool:
    return isinstance(v, np.random.Generator) or (isinstance(v, (list, tuple)) and len(v) > 0
                                                  and all(isinstance(g, np.random.Generator) for g in v))


def _cases() -> list[Any]:
    out = []
    for name, spec in sorted(REG.items()):
        out += [pytest.param("fusion", name, arg, id=f"{name}-{arg}") for arg, a in spec.items() if _is_generators(a.value)]
    return out


def _check(fn: Any, spec: dict[str, Any], arg: str) -> None:
    valid = _fresh({k: a.value for k, a in spec.items()})
    for make in (_subclass, _other_bits):
        kwargs = dict(valid)
        v = valid[arg]
        kwargs[arg] = make(7) if isinstance(v, np.random.Generator) else [make(7 + i) for i in range(len(v))]
        with pytest.raises(TypeError) as info:
            fn(**kwargs)
        assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])", str(info.value)), str(info.value)


def test_the_sweep_finds_the_rng_taking_functions() -> None:
    names = {p.values[1] for p in _cases()}
    assert {"fusion.readings.correlated.gauss_markov_gap", "fusion.filtering.particles.systematic_resample",
            "fusion.estimates.mixtures.weighted_em", "fusion.optimise.scalar.fruit_fly_batch"} <= names


@pytest.mark.parametrize(("layer", "name", "arg"), _cases())
def test_a_generator_subclass_or_foreign_bit_generator_is_refused_naming_the_argument(layer: str, name: str,
                                                                                         arg: str) -> None:
    _check(CALLABLES[name], REG[name], arg)


@pytest.mark.parametrize("module", _CHAPTER_REGISTRIES)
def test_chapter_functions_refuse_a_generator_subclass(module: str) -> None:
    mod = importlib.import_module(module)
    reg = mod.registry()
    callables = public_callables()
    checked = 0
    for name, spec in sorted(reg.items()):
        for arg, a in spec.items():
            if _is_generators(a.value):
                _check(callables[name], spec, arg)
                checked += 1
    assert checked, f"{module}: no rng-taking function swept"


def test_gauss_markov_gap_refuses_the_nan_generator_of_the_report() -> None:
    from fusion.readings.correlated import gauss_markov_gap

    with pytest.raises(TypeError, match="^rng must be a numpy.random.Generator itself, not a subclass"):
        gauss_markov_gap(np.ones((3, 1)), np.eye(3), _subclass(1), 20)


@pytest.mark.parametrize("bits", ["PCG64", "PCG64DXSM", "MT19937", "Philox", "SFC64"])
def test_every_numpy_bit_generator_is_accepted(bits: str) -> None:
    from fusion._validation import as_rng, as_rngs

    g = np.random.Generator(getattr(np.random, bits)(3))
    assert as_rng(g) is g
    assert len(as_rngs([g, np.random.Generator(getattr(np.random, bits)(4))])) == 2


def test_a_bit_generator_subclass_draws_plain_numbers_unless_it_replaces_its_capsule() -> None:
    """The measurement behind the rule: a Python override of ``random_raw`` does not change what a Generator draws
    (it reads the C functions of the capsule), so only the type can tell a bit generator that replaced them."""

    class Raw(np.random.PCG64):
        def random_raw(self, size: Any = None, output: bool = True) -> Any:
            return np.zeros(size or 1, dtype=np.uint64)

    assert np.array_equal(np.random.Generator(Raw(1)).normal(size=5), np.random.default_rng(1).normal(size=5))
    with pytest.raises(TypeError, match=r"^rng must be a numpy.random.Generator over one of numpy's bit generators.*Raw"):
        from fusion._validation import as_rng
        as_rng(np.random.Generator(Raw(1)))
