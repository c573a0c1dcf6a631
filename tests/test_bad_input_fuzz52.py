"""Fuzz 52: glue_all's walk of structured scalars and of a Decimal signalling NaN in a table."""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pandas as pd
import pytest

from fusion.book.glue import glue_all


@pytest.mark.parametrize("make", [lambda v: v, lambda v: [v], lambda v: {"x": v}, lambda v: pd.DataFrame({"a": [v]})])
def test_c3_a_structured_scalar_is_checked_as_its_fields(make) -> None:
    """np.void (1.0, nan) was glued as '(1.0, nan)' (np.generic is an atom); a 0-d structured array was refused."""
    v = np.array([(1.0, np.nan)], dtype=[("a", "f8"), ("b", "f8")])[0]
    with pytest.raises(ValueError, match=r"values\['k'\]"):
        glue_all({"k": make(v)})


@pytest.mark.parametrize("table", [lambda: pd.DataFrame({"a": [Decimal("sNaN"), "x"]}),
                                   lambda: pd.DataFrame({"a": [1]}, index=[Decimal("sNaN")])])
def test_c4_a_signalling_nan_in_a_table_is_no_missing_word(table) -> None:
    """A Decimal('sNaN') cell or label passed as the table's missing word; pandas cannot print it, nothing glued."""
    with pytest.raises(ValueError, match=r"values\['k'\]"):
        glue_all({"k": table()})
