"""Fuzz 31b (chapter layer) fixes: glue keys printed by one printer, producers refusing what their readers cannot
compute, ``__index__`` integers read as their value and stored as plain ints, one tolerance for the swaps checks.

Each test builds only what it needs (no chapter registry is imported): the file's cost is well under 2 CPU-s.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fusion._counts import general, glue_part


class IDX:
    """An integer given only by ``__index__`` (no ``__eq__``, no ``__int__``): the fuzz's object."""

    def __init__(self, v: int) -> None:
        self.v = v

    def __index__(self) -> int:
        return self.v


_FIELD = re.compile(r"[0-9a-z]+")


# --------------------------------------------------------------------------- C1, C3, D4: one glue-key printer
@settings(max_examples=200, deadline=None)
@given(st.floats(allow_nan=False, allow_infinity=False, width=64))
def test_glue_part_is_an_identifier_part_and_keeps_the_plain_digits(x: float) -> None:
    """Every real number prints as identifier characters; a positive number without an exponent prints as before
    (``f"{x:g}"`` without its point), so the notebooks' glue keys stay byte-identical; a zero prints as ``0``, its
    sign dropped (fuzz 34b D3: -0.0 is ``0``, not ``-0``)."""
    part = glue_part(x)
    assert _FIELD.fullmatch(part), part
    g = general(abs(x) if x == 0 else x)
    if x >= 0 and "e" not in g:
        assert part == g.replace(".", "")


def test_a_negative_zero_glues_as_zero() -> None:
    assert glue_part(-0.0) == glue_part(0.0) == "0"


def test_glue_part_of_a_tuple_keeps_its_labels() -> None:
    assert glue_part(("strong direction", 3.5)) == ("strong direction", "35")


def test_fig6_periods_that_share_a_glue_key_are_refused_by_name() -> None:
    """1.5 s and 15 s gave one glue key ``ci_fig6_d_15`` (the check printed them with the point)."""
    from fusion._results import _check
    from fusion.book.chapters.ci.claim_inputs import _PAIRED_FIELDS, PeriodRuns

    runs = PeriodRuns(seed=1, fruit_fly=np.ones(3), grid=np.ones(3))
    spec = _PAIRED_FIELDS["fig6_periods"]
    assert set(_check(spec, {0.5: runs, 0.2: runs}, "fig6_periods", {})) == {0.5, 0.2}   # the chapter's periods
    with pytest.raises(ValueError, match="fig6_periods"):
        _check(spec, {1.5: runs, 15.0: runs}, "fig6_periods", {})


def _plugin(xs: tuple[float, ...], deltas: tuple[float, ...] = (1.0,)):
    from fusion.scenarios import ridge_sensors as rs

    return rs.plugin_study(xs=xs, m=5, sigma=1.0, runs=20, seed=1, curve=(0.0, 1.0), deltas=deltas)


def test_plugin_glue_of_negative_and_exponent_values_is_kept() -> None:
    """``glue_plugin`` of a study at -1 and 1e-05 gave keys the chapter's own ``keep`` refused."""
    from fusion.book.chapters import lecture_correlated as ch
    from fusion.book.chapters.lecture_correlated import ridge
    from fusion.scenarios import ridge_sensors as rs

    p = _plugin((-1.0, 0.0, 1e-05))
    g = ridge.glue_plugin(p, rs.vector_study(runs=20, scales=(3.5,)), ridge.plugin_exact(p))
    assert {"lec_rp_mse_pk_m1", "lec_rp_mse_pk_1em05", "lec_rp_v_ls_s35"} <= set(g)
    assert ch.keep({}, g) is not None


@pytest.mark.parametrize("xs, name", [((1.5, 15.0), "xs"), ((0.0, -1.5, -15.0), "xs")])
def test_plugin_xs_sharing_a_glue_key_refused(xs: tuple[float, ...], name: str) -> None:
    with pytest.raises(ValueError, match=f"^{name} "):
        _plugin(xs)


def test_vector_scales_sharing_a_glue_key_refused() -> None:
    from fusion.scenarios import ridge_sensors as rs

    with pytest.raises(ValueError, match="^scales "):
        rs.vector_study(runs=20, scales=(3.5, 35.0))


def test_tail_glue_keys_are_identifiers_and_alike_thresholds_refused() -> None:
    """``glue_tail`` keyed 10.5 as ``lec_tail_p_10.5`` (not an identifier); 10.5 and 105 now share a key: refused."""
    from fusion.book.chapters.lecture_weighting import estimators as ch
    from fusion.scenarios.lecture_weighting import estimators as es

    g = ch.glue_tail(es.tail_study(runs=200, chunk=100, k=10, thresholds=(10.0, 10.5, 100.0)))
    assert {"lec_tail_p_10", "lec_tail_p_105", "lec_tail_p_100"} <= set(g)
    with pytest.raises(ValueError, match="^thresholds "):
        es.tail_study(runs=200, chunk=100, k=10, thresholds=(10.5, 105.0))


# --------------------------------------------------------------------------- C4: the producer refuses what its reader cannot compute
@pytest.mark.parametrize("x", [5e7, -5e7])
def test_plugin_study_refuses_true_values_its_exact_risk_cannot_reach(x: float) -> None:
    with pytest.raises(ValueError, match="^xs, m and sigma "):
        _plugin((0.0, 1.0, x))


def test_plugin_exact_names_p_for_a_rebuilt_study() -> None:
    from fusion.book.chapters.lecture_correlated import ridge
    from fusion.scenarios.ridge_sensors import _plugin_range

    with pytest.raises(ValueError, match="^p.xs, p.m and p.sigma "):
        _plugin_range(np.array([0.0, 5e7]), 5, 1.0, "p.xs, p.m and p.sigma")
    ridge.plugin_exact(_plugin((0.0, 1e7)))  # within the range: computed


# --------------------------------------------------------------------------- C6: an __index__ zero is zero
@settings(max_examples=50, deadline=None)
@given(st.integers(-10**6, 10**6))
def test_scalar_reads_an_index_object_as_its_value(n: int) -> None:
    from fusion._validation import scalar

    assert scalar(IDX(n), "x") == float(n)


# --------------------------------------------------------------------------- C7: frozen records store plain ints
def test_bundle_stores_the_ints_read_not_the_callers_objects() -> None:
    """A bundle (``shared_post_init``, as chapter 05's LedgerInputs) kept a tuple of ``__index__`` objects."""
    from fusion._results import ResultSpec, dict_of, integer, shared_post_init, tuple_of

    @dataclasses.dataclass(frozen=True)
    class Bundle:
        seeds: tuple[int, int]
        band: dict
        arr: np.ndarray

        __result_spec__ = ResultSpec({"seeds": tuple_of(integer(0), count=2),
                                      "band": dict_of(tuple_of(integer(0), count=2))})
        __post_init__ = shared_post_init

    s = IDX(4)
    arr = np.ones(2)
    b = Bundle(seeds=(s, IDX(5)), band={"a": [IDX(1), 2]}, arr=arr)
    s.v = 99
    assert b.seeds == (4, 5) and all(type(v) is int for v in b.seeds)
    assert tuple(b.band["a"]) == (1, 2) and all(type(v) is int for v in b.band["a"])
    plain = Bundle(seeds=(4, 5), band={"a": (1, 2)}, arr=arr)
    assert plain.seeds == (4, 5) and plain.arr is arr   # shared values stay shared


def test_belief_parameter_study_stores_snapshots_as_an_int() -> None:
    from fusion.scenarios.lecture_weighting import belief as b

    s = b.belief_parameter_study(snapshots=4, params=(0.5, 1.0), grid=(0.5, 1.0), sigma=(0.5, 1.0))
    i = IDX(4)
    s2 = dataclasses.replace(s, snapshots=i)
    i.v = 7
    assert type(s2.snapshots) is int and s2.snapshots == 4


# --------------------------------------------------------------------------- D1, D2: the swaps check of mc_table's SDs
def _mc_studies():
    from fusion.book.chapters.ofs.studies import METHODS
    from fusion.scenarios import thermocouples as th

    m = {k: METHODS[k] for k in ("optimal_fusion_set", "mean")}
    return {"hs": th.paired_study(seed=0, n_runs=2, methods=m, sigma=th.DEFAULT_SIGMAS),
            "eq": th.paired_study(seed=0, n_runs=2, methods=m, sigma=1.0)}


def test_mc_table_accepts_the_same_sds_computed_another_way_and_refuses_a_swap() -> None:
    from fusion.book.chapters import ofs

    S = _mc_studies()
    sds = np.arange(3, 13) / 6   # 1 ulp off the chapter's SDs at some entries
    assert not np.array_equal(sds, S["hs"].sigma)
    assert ofs.mc_table(S, {"hs": sds, "eq": 1.0}).shape[0] == 4
    with pytest.raises(ValueError, match=r"^sigmas\['hs'\] must be the noise SDs"):
        ofs.mc_table(S, {"hs": 1.0, "eq": sds})
    with pytest.raises(ValueError, match=r"^sigmas\['hs'\] must be the noise SDs"):
        ofs.mc_table(S, {"hs": sds * (1 + 1e-9), "eq": 1.0})


def test_mc_table_one_element_sd_list_message_says_what_it_got() -> None:
    from fusion.book.chapters import ofs

    with pytest.raises(ValueError, match=r"^sigmas\['eq'\] .* one number for all, got a sequence of 1 SD$"):
        ofs.mc_table(_mc_studies(), {"hs": np.arange(3, 13) / 6, "eq": [1.0]})
