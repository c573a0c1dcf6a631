"""Fuzz 57a D1: summarise checked ``committed`` through ``items()`` and then read it again by ``get``: a mapping
answering differently the second time put an unchecked value in the summary. It is now read once into a plain dict.
The same class in ``fusion._structures.records_of`` (the records checked, then the sequence read again)."""

from collections.abc import Mapping, Sequence

import pytest


class _TwoFaced(Mapping):
    """A mapping whose items() give a valid status and whose __getitem__ gives another value."""

    def __iter__(self):
        return iter(["rec-a"])

    def __len__(self) -> int:
        return 1

    def __getitem__(self, k):
        if k != "rec-a":
            raise KeyError(k)
        return 12345

    def items(self):
        return iter([("rec-a", "reproduced")])


def _results():
    from fusion.book import stability as S
    ts = [S.Task("src", "rec-a", "primary", "primary", s, 100) for s in (11, 12)]
    return [S.TaskResult(t, "reproduced", 1.0) for t in ts]


def test_d1_committed_is_read_once() -> None:
    from fusion.book import stability as S
    out = S.summarise(_results(), [11, 12], _TwoFaced())
    assert out["rec-a"]["committed"] == "reproduced" and out["rec-a"]["flag"] is False
    with pytest.raises(TypeError, match=r"^committed\['rec-a'\] must be a status"):
        S.summarise(_results(), [11, 12], {"rec-a": 12345})   # the value the second read gave, refused
    assert S.summarise(_results(), [11, 12], {"rec-a": "reproduced"}) == out


class _Shifting(Sequence):
    """A sequence whose second pass yields another record."""

    def __init__(self) -> None:
        self.passes = 0

    def __len__(self) -> int:
        return 1

    def __getitem__(self, i):
        if i != 0:
            raise IndexError(i)
        return {"id": "a"}

    def __iter__(self):
        self.passes += 1
        yield {"id": "a"} if self.passes == 1 else 12345


def test_records_of_reads_once() -> None:
    from fusion._structures import records_of
    assert records_of(_Shifting(), "records", ("id",)) == [{"id": "a"}]
