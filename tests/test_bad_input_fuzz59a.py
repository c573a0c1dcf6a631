"""Fuzz 59a: a list or tuple subclass trusted by the sequence rule (C4), an array in a pair of ``named_crossings`` (C3),
and ``batch_budget``'s charge quadratic in its problems (C1; the chapter's edges are in test_study_budget64)."""

import itertools
import time

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, strategies as st

from fusion._counts import sequence


def _lying(base: type, items: list, stated: int | None = None, endless: bool = False) -> object:
    """A ``base`` (list or tuple) subclass holding ``items`` whose ``len()`` says ``stated`` and whose ``__iter__``
    yields its items (endlessly the first one when ``endless``)."""
    class Lying(base):  # type: ignore[misc, valid-type]
        def __len__(self) -> int:
            return len(items) if stated is None else stated

        def __iter__(self):
            return itertools.repeat(items[0]) if endless else iter(items)

    return Lying(items)


@pytest.mark.parametrize("base", [list, tuple])
@given(items=st.lists(st.floats(0.1, 0.9), min_size=0, max_size=6), stated=st.integers(0, 8))
def test_c4_a_subclass_whose_len_disagrees_with_its_items_is_refused(base: type, items: list, stated: int) -> None:
    """Fuzz 59a C4: ``len()`` lying up or down (``__len__`` and ``__iter__`` of a list or tuple subclass disagreeing)
    is refused naming the argument; an honest one gives its items."""
    value = _lying(base, items, stated)
    if stated == len(items):
        assert sequence(value, "x") == items
    else:
        with pytest.raises(ValueError, match=r"^x has len\(\) "):
            sequence(value, "x")


@pytest.mark.parametrize("base", [list, tuple])
def test_c4_an_endless_subclass_is_read_one_item_past_its_len(base: type) -> None:
    """An endless ``__iter__`` (fuzz 59a: a raw MemoryError after 4.7 CPU-s) is refused after ``len() + 1`` items."""
    from fusion.book.chapters.ci.fruit_fly_step import fruit_fly_step_targets
    t = time.process_time()
    with pytest.raises(ValueError, match=r"^targets has len\(\) 1 but more items"):
        fruit_fly_step_targets(0, _lying(base, [0.5], endless=True), seeds=2)
    with pytest.raises(ValueError, match=r"^targets has len\(\) 1 but more items"):
        fruit_fly_step_targets(0, _lying(base, [0.5, 0.6], stated=1), seeds=2)
    assert time.process_time() - t < 1.0


def test_c4_exact_lists_and_tuples_keep_their_items() -> None:
    assert sequence([1, 2], "x") == [1, 2] and sequence((1, 2), "x") == [1, 2] and sequence(range(3), "x") == [0, 1, 2]


def _crossings() -> pd.DataFrame:
    from fusion.book.chapters import time_registration_closed as t
    return pd.DataFrame({t.BETTER_BELOW: ["a", "b"], t.BETTER_ABOVE: ["b", "c"], t.SIGMA_STAR: [0.1, 0.2]})


@pytest.mark.parametrize("pair", [(np.array(["a", "b"]), "b"), ("a", np.array(["b"])), (1, "b"), ("a", float("nan")),
                                  (None, "b"), (b"a", "b")])
def test_c3_named_crossings_reads_each_method_as_text(pair: tuple) -> None:
    """Fuzz 59a C3: an array in a pair raised numpy's "truth value of an array is ambiguous" from the lookup, naming
    nothing; every entry of a pair is read by the text rule, a TypeError naming the pair."""
    from fusion.book.chapters.time_registration_closed import named_crossings
    with pytest.raises(TypeError, match=r"^pairs\[1\]\[[01]\] must be a string"):
        named_crossings(_crossings(), [("a", "b"), pair])


def test_c3_named_crossings_takes_text_subclasses() -> None:
    from fusion.book.chapters.time_registration_closed import BETTER_ABOVE, named_crossings
    out = named_crossings(_crossings(), [(np.str_("b"), "c"), ("a", np.str_("b"))])
    assert list(out[BETTER_ABOVE]) == ["c", "b"]


def test_c1_batch_budget_is_linear_in_the_problems() -> None:
    """Fuzz 59a C1: ``batch_budget`` charged ``(n + iterations) x 4 n population`` units, quadratic in ``n`` (a
    study of 1,931 seeds refused though it runs ~2 CPU-s). Linear now: 8 units a fly and generation (measured 48 to
    77 ns), so the edge of a 30 x 200 batch is some 20,800 problems (6-10 CPU-s), and one past it is refused at once."""
    from fusion._limits import MAX_WORK
    from fusion.optimise.scalar import batch_budget, fruit_fly_batch
    assert batch_budget(2_000, 30, 200, "n") == 2 * batch_budget(1_000, 30, 200, "n") - batch_budget(0, 30, 200, "n")
    edge = (MAX_WORK // 200 - 3_000) // (8 * 30)
    assert 20_000 < edge < 21_000
    batch_budget(edge, 30, 200, "n")
    rngs = [np.random.default_rng(i) for i in range(edge + 1)]
    t = time.process_time()
    with pytest.raises(ValueError, match="^rngs, population and iterations ask for"):
        fruit_fly_batch(lambda w: w, rngs)
    assert time.process_time() - t < 1.0
