"""The infrared readers' ``rules`` (``rule_errors``, ``cartesian_errors``): each key of RULES at most once, refused
by the length before any entry is read (10**7 repeats of one key were read, converted and merged into one rule:
14.5 CPU-s, then accepted), a repeat within the length naming both positions."""

from __future__ import annotations

import functools

import pytest

from _helpers import refused_quickly


def test_more_rules_than_keys_are_refused_by_the_length() -> None:
    from fusion.scenarios import infrared_radar as ir

    many = ["convex_ml"] * 10**7
    refused_quickly(functools.partial(ir._rule_subset, many), ValueError, r"^rules must name each of the 4 keys")


def test_a_repeated_rule_is_refused_naming_both_entries() -> None:
    from fusion.scenarios import infrared_radar as ir

    with pytest.raises(ValueError, match=r"rules\[0\] and rules\[2\] are both 'split_ci'"):
        ir._rule_subset(["split_ci", "convex_ml", "split_ci"])
    assert list(ir._rule_subset(["split_ci", "convex_ml"])) == [ir.IrMethod.SPLIT_CI, ir.IrMethod.CONVEX]
    assert list(ir._rule_subset(list(ir.RULES))) == list(ir.RULES)


def test_a_sequence_whose_length_lies_is_refused() -> None:
    """A ``__len__`` of 2 over 10**7 items: refused by the sequence rule, not iterated to its end."""
    from collections.abc import Sequence

    from fusion.scenarios import infrared_radar as ir

    class Liar(Sequence):
        def __len__(self) -> int:
            return 2

        def __getitem__(self, i):
            if i >= 10**7:
                raise IndexError(i)
            return "split_ci"

    refused_quickly(functools.partial(ir._rule_subset, Liar()), ValueError, r"rules")
