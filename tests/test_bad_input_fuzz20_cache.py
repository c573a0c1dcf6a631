"""Fuzz 20, classes H, P and S: cached functions' unhashable arguments, ``premise_mixture_scaled``'s ``factor``,
and the study cache's own helpers (``source_digest``, ``study_key``)."""

from __future__ import annotations

import importlib
import inspect
import math
import pkgutil
import re
from pathlib import Path
from typing import Any

import pandas as pd
import pytest

import fusion
from fusion.book import study_cache as sc
from fusion.book.chapters import chernoff as chf


def _cached_public_functions() -> dict[str, Any]:
    """Every public function of the package wrapped by ``process_cache`` or ``study_cache`` (it has ``cache_info``)."""
    found = {}
    for info in pkgutil.walk_packages(fusion.__path__, "fusion."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if (not name.startswith("_") and callable(obj) and hasattr(obj, "cache_info")
                    and hasattr(obj, "__wrapped__") and str(getattr(obj, "__module__", "")).startswith("fusion.")):
                found[f"{obj.__module__}.{obj.__qualname__}"] = obj
    return found


CACHED = _cached_public_functions()
#: The cached functions that take arguments (the others have nothing to hash).
WITH_ARGUMENTS = sorted(k for k, fn in CACHED.items() if inspect.signature(fn).parameters)


def test_the_enumeration_finds_the_reported_cached_functions() -> None:
    from fusion.book.chapters import time_registration_ledger as trl
    from fusion.book.chapters.lecture_correlated import records as lcr

    for fn in (trl.cached_study, lcr.cached_studies, chf.checks_study, chf.common_study, chf.isv_study,
               chf.premise_mixture_scaled):
        assert any(fn is found for found in CACHED.values()), fn.__qualname__


@pytest.mark.parametrize("qualname", WITH_ARGUMENTS)
def test_an_unhashable_argument_of_a_cached_function_is_a_type_error_naming_it(qualname: str) -> None:
    fn = CACHED[qualname]
    params = [p for p in inspect.signature(fn).parameters.values()
              if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
    assert params
    for bad in params:
        for value in (pd.Series([2024]), {2024}):
            kwargs = {p.name: (value if p is bad else 2024) for p in params}
            with pytest.raises(TypeError, match=rf"\b{re.escape(bad.name)}\b.*hashable"):
                fn(**kwargs)


def test_an_unhashable_argument_is_named_positionally_too() -> None:
    with pytest.raises(TypeError, match=r"^seed must be hashable"):
        chf.isv_study({2024})
    with pytest.raises(TypeError, match=r"^seed must be hashable"):
        chf.common_study(pd.Index([2024]))


def test_a_type_error_of_the_function_itself_is_not_renamed() -> None:
    @sc.process_cache(maxsize=2)
    def f(x: int) -> int:
        raise TypeError("f's own")

    with pytest.raises(TypeError, match="^f's own$"):
        f(1)


@pytest.mark.parametrize("factor", [2.5, "10", True, None, math.nan, [10]])
def test_premise_mixture_scaled_refuses_a_factor_that_is_not_an_integer(factor: Any) -> None:
    with pytest.raises(TypeError, match="factor"):
        chf.premise_mixture_scaled(2024, 100, factor)


@pytest.mark.parametrize("factor", [0, -1])
def test_premise_mixture_scaled_refuses_a_factor_below_one(factor: int) -> None:
    with pytest.raises(ValueError, match="factor"):
        chf.premise_mixture_scaled(2024, 100, factor)


def test_source_digest_takes_a_str_path_as_its_path() -> None:
    assert sc.source_digest(str(sc._PACKAGE)) == sc.source_digest(sc._PACKAGE) == sc.source_digest()


@pytest.mark.parametrize("package", [5, ["fusion"], None, b"fusion"])
def test_source_digest_refuses_what_is_not_a_path(package: Any) -> None:
    with pytest.raises(TypeError, match="package"):
        sc.source_digest(package)


def test_study_key_refuses_an_argument_nested_too_deeply_by_name() -> None:
    deep: list[Any] = []
    for _ in range(5000):
        deep = [deep]
    with pytest.raises(TypeError, match=r"arguments\['a'\].*nested too deeply"):
        sc.study_key("m.f", {"a": deep})


@pytest.mark.parametrize("digest", [b"x", 5, Path("d")])
def test_study_key_refuses_a_digest_that_is_not_a_string(digest: Any) -> None:
    with pytest.raises(TypeError, match="digest"):
        sc.study_key("m.f", {"a": 1}, digest)


def test_study_key_takes_a_given_digest() -> None:
    assert sc.study_key("m.f", {"a": 1}, "abc") != sc.study_key("m.f", {"a": 1}, "abd")
