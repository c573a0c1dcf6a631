"""Fuzz 48's findings (issue 35) fixed this session: C3-C6 (C1, C2 left open: glue_all's memo inside a cycle)."""

from __future__ import annotations

import decimal
import time
from decimal import Decimal
from fractions import Fraction

import pytest

from fusion.book.tables import _roundings, rounded, sci


def test_sci_rounds_a_long_fraction_in_near_linear_time() -> None:
    # C3: a Decimal division of the numerator and denominator was superlinear (N = 1e6: 6.3 CPU-s)
    q = Fraction(3**1_000_000 + 1, 3**1_000_000)
    t = time.process_time()
    assert sci(q, 4) == "1"
    assert time.process_time() - t < 0.5
    assert sci(Fraction(2675, 1000), 3) == "2.68" and sci(Fraction(99995, 10000), 4) == "10"
    assert sci(Fraction(-5, 2), 1) == "-2" and sci(Fraction(1, 3), 3) == "0.333"


def test_rounding_does_not_depend_on_the_callers_decimal_context() -> None:
    # C5: the rounding step was built in the caller's context (prec 3: 1.23457 for 1.23456789; prec 1: a bare
    # decimal.InvalidOperation)
    with decimal.localcontext(decimal.Context(prec=3, Emin=-3)):
        assert rounded(Decimal("1.23456789"), 10) == 1.23456789
        assert _roundings(0.125, 2) == (0.12, 0.13)
    with decimal.localcontext(decimal.Context(prec=1, Emin=-3)):
        assert rounded(Decimal("2.675"), 10) == 2.675 and rounded(Decimal("2.675"), 2) == 2.68


def test_linearised_errors_names_sc_for_singular_covariances() -> None:
    # C4: a bare numpy LinAlgError "Singular matrix" from np.linalg.inv
    from fusion.scenarios.range_bearing import RangeBearingScenario, linearised_errors

    for kw in ({"p0_std": (1e7,) * 4, "sigma_r": 1e-2}, {"sigma_r": 1e-8}):
        with pytest.raises(ValueError, match=r"^sc \(its noise levels"):
            linearised_errors(RangeBearingScenario(**kw))


def test_bounded_minimum_refuses_an_interval_its_iterations_cannot_reach() -> None:
    # C6: scipy's 500 iterations ran out on [-1e150, 1e150] and its x (9.9e7 for 0.3) was returned
    from fusion.optimise.scalar import bounded_minimum

    with pytest.raises(ValueError, match=r"^lo and hi: the interval"):
        bounded_minimum(lambda x: abs(x - 0.3), -1e150, 1e150)
    assert abs(bounded_minimum(lambda x: abs(x - 0.3), -1e100, 1e100).x - 0.3) < 1e-8


def test_glue_all_refuses_a_container_of_a_cycle_reached_by_two_paths() -> None:
    # C1, C2: a container's printed size was memoised while an outer container of its cycle was open (printed [...]
    # there) and charged so at a second path, where it prints in full: 38.7 CPU-s accepted; 20 such pairs printed
    # 1,200 deep past the nesting check. A container holding itself, or shared outside any cycle, is still glued.
    from fusion.book.glue import _finite

    inner = [0.5] * 1000
    big = [inner] * 300
    Y: list = [None, big]
    X = [Y]
    Y[0] = X
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^values\['k'\] must not reach a container of a cycle"):
        _finite([X] * 60 + [Y], "k")
    assert time.process_time() - t < 3.0
    a: list = []
    a.append(a)
    assert _finite({"x": [a, a]}, "k")
    c = [1.0]
    d: list = [c, None]
    d[1] = d
    assert _finite([d, c, d], "k")


def test_fuzz49a_c5_positive_definiteness_is_judged_on_the_symmetric_part_returned() -> None:
    """Within the asymmetry tolerance, the symmetric part (what the readers return) is judged, not the lower triangle:
    [[1, 1 + 5e-10], [1 - 1e-10, 1]] has a positive-definite lower triangle and an indefinite symmetric part."""
    import numpy as np
    import pytest
    from fusion._covariances import as_covariance, as_covariances, covariance_pair
    from fusion.estimates import covariance_intersection

    P1 = np.array([[1.0, 1.0 + 5e-10], [1.0 - 1e-10, 1.0]])
    assert np.linalg.eigvalsh(0.5 * (P1 + P1.T)).min() < 0 < np.linalg.cholesky(P1)[1, 1]
    for call in (lambda: as_covariance(P1, name="P1"), lambda: covariance_pair(P1, np.eye(2)),
                 lambda: covariance_intersection(np.zeros(2), P1, np.ones(2), np.eye(2), omega=1.0)):
        with pytest.raises(ValueError, match="P1 must be positive definite"):
            call()
    with pytest.raises(ValueError, match=r"covs\[1\] must be positive definite"):
        as_covariances(np.stack([np.eye(2), P1]), name="covs")
    Q = np.array([[2.0, 1.0 + 1e-12], [1.0, 2.0]])   # a valid one within the tolerance: its symmetric part
    assert np.array_equal(as_covariance(Q), 0.5 * (Q + Q.T))


def test_fuzz49a_d1_a_signalling_nan_decimal_is_a_nan() -> None:
    """Decimal('sNaN') is a NaN (a bad value: ValueError naming the argument, '—' where a NaN prints as a dash), not
    a wrong type: float() refuses it, which the readers turned into a TypeError."""
    from decimal import Decimal
    import pytest
    from fusion._validation import as_array, positive_scalar
    from fusion.book.ledger import fmt
    from fusion.book.tables import rounded, sci

    s = Decimal("sNaN")
    for call, name in ((lambda: rounded(s), "value"), (lambda: positive_scalar(s, "x"), "x"),
                       (lambda: as_array([1.0, s], "x"), "x")):
        with pytest.raises(ValueError, match=f"^{name} "):
            call()
    assert sci(s) == sci(Decimal("NaN")) and fmt(s) == fmt(Decimal("NaN"))



def test_no_source_file_of_the_package_holds_a_tab() -> None:
    r"""A literal tab in a raw docstring is what ``"\top"`` became when a script wrote it through a non-raw string:
    the API page printed ``F^	op`` (found by fix56b in ``linearised_errors`` and ``filter_moments``)."""
    from pathlib import Path
    root = Path(__file__).resolve().parents[1] / "fusion"
    tabs = [f"{p.relative_to(root)}:{i}" for p in sorted(root.rglob("*.py"))
            for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if "\t" in line]
    assert not tabs, tabs


def test_no_docstring_of_the_package_holds_a_control_character_nor_an_invalid_escape() -> None:
    r"""A non-raw docstring turns ``\top`` into a tab and ``\Phi`` into a DeprecationWarning (an error in 3.12+):
    ``_smoother_gain``'s ``P\Phi^\top`` and ``_random_sensors``' ``AA^\top`` did, which the source-tab test above
    cannot see (found by fix59a). Every module compiles with warnings as errors and no docstring's value holds a
    control character other than the line break."""
    import ast
    import re
    import warnings
    from pathlib import Path
    root = Path(__file__).resolve().parents[1] / "fusion"
    bad = []
    for p in sorted(root.rglob("*.py")):
        text = p.read_text(encoding="utf-8")
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            try:
                tree = compile(text, str(p), "exec", flags=ast.PyCF_ONLY_AST)
            except SyntaxError as exc:   # a warning turned error is raised as a SyntaxError
                bad.append(f"{p.relative_to(root)}:{exc.lineno}: {exc.msg}")
                continue
        for node in ast.walk(tree):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                doc = ast.get_docstring(node, clean=False)
                if doc and re.search(r"[\x00-\x09\x0b-\x1f\x7f]", doc):
                    bad.append(f"{p.relative_to(root)}: {getattr(node, 'name', '<module>')}")
    assert not bad, bad


def test_fuzz50a_d6_a_signalling_nan_is_told_by_the_entry_not_by_a_message() -> None:
    """An entry whose __float__ raises ValueError('signaling NaN') is not a number (TypeError); a Decimal sNaN is a
    NaN (ValueError)."""
    from decimal import Decimal
    import pytest
    from fusion._validation import as_array

    class Odd:
        def __float__(self) -> float:
            raise ValueError("signaling NaN")

    with pytest.raises(TypeError, match="^x "):
        as_array([1.0, Odd()], "x")
    with pytest.raises(ValueError, match="^x contains NaN"):
        as_array([1.0, Decimal("-sNaN")], "x")
