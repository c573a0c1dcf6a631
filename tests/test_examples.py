"""The ``Examples`` sections of the entry points run and print what they say (doctest, filterpy-style).

Only the functions listed here are run (``pytest --doctest-modules`` on the whole package would also
collect the chapter modules); each must have at least one example.
"""
from __future__ import annotations

import doctest

import numpy as np
import pytest

from fusion.estimates.ci import ci_weight, covariance_intersection
from fusion.filtering.tracks import fuse_tracks
from fusion.readings.fusion_set import optimal_fusion_set
from fusion.registration.methods import three_point

ENTRY_POINTS = [ci_weight, covariance_intersection, optimal_fusion_set, three_point, fuse_tracks]


@pytest.mark.parametrize("func", ENTRY_POINTS, ids=lambda f: f.__name__)
def test_examples_run_as_written(func) -> None:  # noqa: ANN001
    assert "\n    Examples\n    --------\n" in func.__doc__
    tests = doctest.DocTestFinder(recurse=False).find(func, func.__name__, globs={})
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    with np.printoptions(legacy=False):
        for t in tests:
            runner.run(t)
    result = runner.summarize(verbose=False)
    assert result.attempted >= 3 and result.failed == 0
