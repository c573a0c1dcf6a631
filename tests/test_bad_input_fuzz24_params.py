"""Fuzz 24a, classes U, T, W and the debatable D3, D4 (issue 35): parameters no sweep ever set, wrong names in
messages, and validation that changed process-global state.

* U: :data:`test_bad_input.REG` left 105 parameters at their defaults, so the mutation sweep never tried them and
  ten were not checked at all (``fruit_fly(step=())`` an IndexError, ``minimise_on_simplex(ftol=inf)`` the start
  returned as the minimum, ...). The class remedy: :func:`test_every_parameter_is_set_in_the_registry` requires each
  parameter of each registry callable to be set in its valid call (with mutations) or exempt below, with a reason.
* T: the objective at fault is named (not the result's field ``OptimumResult.fun``), the argument ``periods`` (not
  the internal ``Ts``).
* W: the shared array and mask readers used ``warnings.catch_warnings()``, which saves and restores the
  process-global filter list: threads interleaving left an ``error`` filter behind for every later warning.
* D3 (decided): one generator object given for two problems of a batch is refused by name (``rngs[1] draws from the
  same stream as rngs[0]``): each problem's result is documented as what the single call gives with its generator,
  impossible when two problems draw from one stream.
* D4 (decided): every option is checked whatever the method, also where the chosen method does not use it
  (``robust_fuse(x, "median", cut="abc")``, ``time_registration.expected(..., window="abc")``).
* D7 (lying ``__len__`` / ``__str__`` subclasses): listed only, not changed.
"""

from __future__ import annotations

import inspect
import threading
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from test_bad_input import CALLABLES, REG, _excluded

#: Parameters a valid call need not set, with the reason (every other parameter of every registry callable must
#: be set in ``tests/test_bad_input.py``, with its mutations).
UNSET_EXEMPT: dict[tuple[str, str], str] = {}

_SKIP_KINDS = (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)


def _unset_parameters() -> list[str]:
    out = []
    for name, spec in sorted(REG.items()):
        if _excluded(name):
            continue
        try:
            sig = inspect.signature(CALLABLES[name])
        except (TypeError, ValueError):  # no signature (a builtin): nothing to set
            continue
        for p in sig.parameters.values():
            if p.kind in _SKIP_KINDS or p.name == "self" or p.name in spec or (name, p.name) in UNSET_EXEMPT:
                continue
            out.append(f"{name}({p.name})")
    return out


def test_every_parameter_is_set_in_the_registry() -> None:
    missing = _unset_parameters()
    assert not missing, ("parameters the bad-input registry never sets (so never mutates): set them in "
                         f"tests/test_bad_input.py or exempt them here with a reason: {missing}")


def test_the_exemptions_name_real_parameters() -> None:
    for (name, param), reason in UNSET_EXEMPT.items():
        assert reason.strip(), (name, param)
        assert param in inspect.signature(CALLABLES[name]).parameters, (name, param)
        assert param not in REG[name], f"{name}({param}) is set in the registry: drop its exemption"


# --------------------------------------------------------------------------------------------
# U: the parameters the fuzzer found unchecked
# --------------------------------------------------------------------------------------------

def _quad(x):
    return (x - 0.3) ** 2


_BAD_PAIRS = st.one_of(
    st.tuples(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.none(),
    st.tuples(st.text(min_size=1, max_size=3), st.text(min_size=1, max_size=3)),
    st.tuples(st.sampled_from([np.nan, np.inf, -np.inf, 1e300]), st.floats(-10, 10)),
    st.tuples(st.floats(-10, 10), st.sampled_from([np.nan, np.inf, -np.inf, 1e300])),
    st.tuples(st.floats(-10, 10), st.floats(-10, 10), st.floats(-10, 10)),
)


@settings(max_examples=60, deadline=None)
@given(step=_BAD_PAIRS)
def test_fruit_fly_step_is_checked_by_name(step) -> None:
    from fusion.optimise.scalar import fruit_fly, fruit_fly_batch

    for call in (lambda: fruit_fly(_quad, np.random.default_rng(0), 5, 5, step),
                 lambda: fruit_fly_batch(lambda s: (s - 0.3) ** 2, [np.random.default_rng(0)], 5, 5, step)):
        with pytest.raises((ValueError, TypeError), match=r"\bstep\b"):
            call()


def test_fruit_fly_step_valid_pairs_still_work() -> None:
    from fusion.optimise.scalar import fruit_fly, fruit_fly_batch

    a = fruit_fly(_quad, np.random.default_rng(0), 5, 5, [30.0, -10.0])
    b = fruit_fly(_quad, np.random.default_rng(0), 5, 5, np.array([30, -10]))
    c = fruit_fly_batch(lambda s: (s - 0.3) ** 2, [np.random.default_rng(0)], 5, 5, (30.0, -10.0))[0]
    assert a == b == c


@pytest.mark.parametrize("ftol", [np.inf, -1.0, 0.0, np.nan, "abc", None])
def test_minimise_on_simplex_refuses_a_bad_ftol(ftol) -> None:
    from fusion.optimise.simplex import minimise_on_simplex

    with pytest.raises((ValueError, TypeError), match=r"\bftol\b"):
        minimise_on_simplex(lambda e: float(np.sum((e - np.array([0.2, 0.3, 0.5])) ** 2)), 3, ftol=ftol)


@settings(max_examples=60, deadline=None)
@given(ndim=st.integers(1, 3), axis=st.one_of(st.integers(-10**13, 10**13), st.floats(), st.text(max_size=2),
                                              st.none(), st.booleans()))
def test_effective_sample_size_axis(ndim, axis) -> None:
    from fusion.filtering.particles import effective_sample_size

    w = np.full((2,) * (ndim - 1) + (4,), 0.25)
    if isinstance(axis, int) and not isinstance(axis, bool) and -ndim <= axis < ndim:
        if axis % ndim == ndim - 1:
            np.testing.assert_allclose(effective_sample_size(w, axis=axis), 4.0)
        return
    with pytest.raises((ValueError, TypeError), match=r"\baxis\b"):
        effective_sample_size(w, axis=axis)


@pytest.mark.parametrize("method", ["median", "trimmed_mean", "grubbs", "biweight", "huber", "mad_reject"])
@pytest.mark.parametrize("param, bad", [("cut", "abc"), ("cut", None), ("cut", 0.5), ("alpha", "abc"), ("alpha", None),
                                        ("alpha", 1.0), ("c", None), ("k", -1.0), ("c_biweight", np.nan),
                                        ("sigma", "abc"), ("sigma", [1.0, 2.0])])
def test_robust_fuse_checks_every_option_whatever_the_method(method, param, bad) -> None:
    from fusion.readings.robust import robust_fuse

    x = np.array([[1.0, 1.1, 0.9, 1.05, 5.0]] * 3)
    with pytest.raises((ValueError, TypeError), match=rf"\b{param}\b"):
        robust_fuse(x, method, **{param: bad})


def test_weighted_em_batch_init_and_network_edges_and_faults_and_readings_are_named() -> None:
    from fusion.estimates.mixtures import weighted_em_batch
    from fusion.scenarios.fusion_networks import premise_scenarios
    from fusion.scenarios.lecture_weighting.readings_benchmark import benchmark
    from fusion.scenarios.two_sensor import path_by_period
    import dataclasses

    x = np.random.default_rng(0).normal(size=(1, 20, 2))
    for init in (5, 2.5):
        with pytest.raises(TypeError, match=r"\binit\b"):
            weighted_em_batch(x, np.full((1, 20), 0.05), 1, [np.random.default_rng(0)], init=init)
    sc = next(iter(premise_scenarios().values()))
    for edges in (5, ((1.0,),), (0.5,)):
        with pytest.raises((ValueError, TypeError), match=r"\bedges\b"):
            dataclasses.replace(sc, edges=edges)
    for faults in (0.1, None, (0.1,)):
        with pytest.raises((ValueError, TypeError), match=r"\bfaults\b"):
            benchmark(seeds=(5,), runs=10, samples=10, faults=faults)
    for readings in (0.1, None, ()):
        with pytest.raises((ValueError, TypeError), match=r"\breadings\b"):
            path_by_period(np.array([1.0]), 150.0, 10.0, readings=readings)


def test_ridge_study_ks_fixed_is_named() -> None:
    from fusion.scenarios.lecture_correlated import ridge_study

    kw = dict(xs=(0.5, 3.0), ms=(1, 5), m0=5, sigma=1.0, seed=1, seed_vector=2, draws=20)
    for ks in ((), ("a", "a"), (np.nan,), (-1.0,), 0.5):
        with pytest.raises((ValueError, TypeError), match=r"\bks_fixed\b"):
            ridge_study(**kw, ks_fixed=ks)


@pytest.mark.parametrize("all_nodes", ["no", 2, np.nan, None])
def test_run_tracking_all_nodes_is_a_bool(all_nodes) -> None:
    from test_bad_input import _objects
    from fusion.scenarios.range_bearing import run_tracking

    with pytest.raises(TypeError, match=r"\ball_nodes\b"):
        run_tracking(_objects()["sc"], np.random.SeedSequence(1), all_nodes=all_nodes)


# --------------------------------------------------------------------------------------------
# T: the argument at fault is named
# --------------------------------------------------------------------------------------------

def test_an_objective_beyond_the_representable_range_names_the_objective() -> None:
    from fusion.optimise.swarm import particle_swarm

    def fitness(x):
        return 1e160 * (1.0 + np.sum(x**2, axis=-1))

    with pytest.raises(ValueError, match=r"^fitness returned a value of magnitude"):
        particle_swarm(fitness, 2, np.random.default_rng(0), n_particles=5, iterations=3)
    from fusion.optimise.scalar import fruit_fly

    with pytest.raises(ValueError, match=r"^f returned a value of magnitude"):
        fruit_fly(lambda x: 1e160 * (1.0 + x), np.random.default_rng(0), 5, 5)


def test_path_by_period_names_periods_not_ts() -> None:
    from fusion.scenarios.two_sensor import path_by_period

    with pytest.raises(ValueError) as exc:
        path_by_period(np.array([1e8]), 150.0, 10.0)
    assert "periods" in str(exc.value) and "Ts" not in str(exc.value)


# --------------------------------------------------------------------------------------------
# W: validation changes no process-global state
# --------------------------------------------------------------------------------------------

def _leaks(target, args, threads=4, calls=3000) -> bool:
    saved = list(warnings.filters)
    try:
        warnings.resetwarnings()
        before = list(warnings.filters)

        def work():
            for _ in range(calls):
                target(*args)

        ts = [threading.Thread(target=work) for _ in range(threads)]
        for t in ts:
            t.start()
        for t in ts:
            t.join()
        return warnings.filters != before
    finally:
        warnings.filters[:] = saved


def test_validation_leaves_the_warning_filters_alone_across_threads() -> None:
    from fusion.readings.fusion_set import arithmetic_mean
    from fusion.scenarios.lecture_weighting.estimators import delete_weights

    assert not _leaks(delete_weights, (np.array([[1.0, 2.0, 3.0]]), [[True, False, True]]))
    assert not _leaks(arithmetic_mean, ([1.0, 2.0, 3.0],))


def test_validation_changes_no_filter_even_in_one_thread() -> None:
    """No catch_warnings anywhere on the path: a filter added *during* the conversion would show here."""
    from fusion._selections import as_mask
    from fusion._validation import as_array

    seen = []
    real = warnings.simplefilter

    def spy(*a, **k):
        seen.append(a)
        return real(*a, **k)

    warnings.simplefilter = spy
    try:
        as_array([1.0, 2.0], "x")
        as_array(np.array([1, 2]), "x")
        as_mask([True, False], "mask")
    finally:
        warnings.simplefilter = real
    assert not seen


def test_complex_entries_of_an_object_array_are_still_refused_without_a_warning_filter() -> None:
    from fusion._validation import as_array

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the refusal must not depend on the caller's filters
        for x in (np.array([np.complex128(1 + 1j)], dtype=object), np.array([1.0, 1 + 2j], dtype=object)):
            with pytest.raises(TypeError, match=r"\bx\b.*complex|complex.*\bx\b"):
                as_array(x, "x")


# --------------------------------------------------------------------------------------------
# D3: one stream per problem of a batch
# --------------------------------------------------------------------------------------------

def test_a_generator_given_twice_to_a_batch_is_refused() -> None:
    from fusion.estimates.mixtures import weighted_em_batch
    from fusion.optimise.scalar import fruit_fly_batch
    from fusion.optimise.swarm import particle_swarm_batch

    g = np.random.default_rng(0)
    twin = np.random.Generator(g.bit_generator)  # another Generator object drawing from the same stream
    x = np.random.default_rng(1).normal(size=(2, 20, 2))
    for rngs in ([g, g], [g, twin]):
        with pytest.raises(ValueError, match=r"rngs\[1\] draws from the same stream as rngs\[0\]"):
            weighted_em_batch(x, np.full((2, 20), 0.05), 1, rngs)
        with pytest.raises(ValueError, match=r"rngs\[1\]"):
            fruit_fly_batch(lambda s: (s - 0.3) ** 2, rngs, 5, 5)
        with pytest.raises(ValueError, match=r"rngs\[1\]"):
            particle_swarm_batch(lambda active, e: np.sum(e**2, axis=-1), 2, rngs, n_particles=5, iterations=3)
    # distinct streams, even from one seed sequence, are accepted
    a, b = (np.random.default_rng(s) for s in np.random.SeedSequence(3).spawn(2))
    assert len(fruit_fly_batch(lambda s: (s - 0.3) ** 2, [a, b], 5, 5)) == 2


# --------------------------------------------------------------------------------------------
# D4: options the chosen method does not use are still checked
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kw", [dict(window="abc"), dict(window=-1.0), dict(t_change="abc"), dict(t_change=np.nan),
                                dict(kf="abc")])
def test_time_registration_checks_options_the_method_does_not_use(kw) -> None:
    from fusion.scenarios import time_registration as tr

    (param,) = kw
    with pytest.raises((ValueError, TypeError), match=rf"\b{param}\b"):
        tr.expected("reg_kalman_predict", 2.0, **kw)
