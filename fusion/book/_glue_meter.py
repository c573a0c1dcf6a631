"""The work meter of ``fusion.book.glue._finite``: what one ``glue_all`` call may still visit, and what it has
already found (the types and objects whose attributes were scanned for a text of their own)."""

from __future__ import annotations

import collections.abc
import types

from fusion._limits import MAX_WORK
from fusion._shown import shown

__all__: list[str] = []

#: The entries ``glue._finite`` may reach inside containers the caller did not count, in one call (``glue``'s
#: comment above ``_GLUE_VISITS`` gives the measurements).
GLUE_VISITS = 10**6
#: Units (about 10 ns each) of one attribute scanned by ``glue._own_text`` (a class's ``__dict__`` along the MRO of
#: an atom's or container's type, or an instance's ``__dict__``) for a text method or an override of its base
#: (fuzz 66a C1, C2: an int subclass with 10**5 class attributes, or one instance with 10**5 instance attributes,
#: was rescanned for each of 400 values or entries, 27.4 and 30.5 CPU-s accepted, charged ~4e6 units). Measured by
#: ``glue_all`` on 10**5 attributes (time.process_time, OPENBLAS_NUM_THREADS=1, minimum of 2, machine shared with
#: other helpers), us an attribute: an int subclass's class attributes 0.51, a datetime's 0.57, a list's 0.49, a
#: Series subclass's 0.85; an int's, a list's, a datetime's instance attributes 0.45, 0.44, 0.51: weighed about twice
#: the largest, 170 units. A type is scanned once a call, an object's instance attributes once a call (the same
#: object reached again is the same object): 400 values of one such class now 0.06 CPU-s.
GLUE_ATTR = 170


class Meter:
    """What ``glue._finite`` may still visit in one call: ``units`` of the work budget (``fusion._limits.MAX_WORK``
    by default) and ``entries`` (``GLUE_VISITS``); ``plain``: the types found to print their base type's text,
    ``scanned``: by id, the objects whose instance attributes were found so (kept alive: no id is reused)."""

    def __init__(self, units: int = MAX_WORK) -> None:
        self.units, self.entries = units, GLUE_VISITS
        self.plain: set[type] = set()
        self.scanned: dict[int, object] = {}

    def charge(self, n: int, weight: int, key: str) -> None:
        """Take ``n`` entries of ``weight`` units each; ValueError naming ``values[key]`` beyond either allowance."""
        self.take(n, n * weight, key)

    def take(self, n: int, units: int, key: str) -> None:
        """Take ``n`` entries of ``units`` units in all (a container reached again: its printed entries, fuzz 47
        C3); ValueError naming ``values[key]`` beyond either allowance."""
        if n == 0 and units == 0:
            return
        self.units -= units
        self.entries -= n
        if self.units < 0 or self.entries < 0:
            raise ValueError(f"values[{shown(key)}] ask for more work than the work budget allows (fusion."
                             f"_validation.MAX_WORK, about 10 CPU-s): a container inside it (or with the values "
                             f"before it) prints {n:,} more entries ({units:,} units) than remain of the budget or "
                             f"of the {GLUE_VISITS:,} entries printed inside containers in one call")

    def scan(self, attrs: int, key: str) -> None:
        """Take the scan of ``attrs`` attributes (``GLUE_ATTR`` units each) before it is made; ValueError naming
        ``values[key]`` beyond the budget."""
        if self.units < attrs * GLUE_ATTR:
            raise ValueError(f"values[{shown(key)}] ask for more work than the work budget allows (fusion."
                             f"_validation.MAX_WORK, about 10 CPU-s): checking that a type or an object defines no "
                             f"text of its own scans {attrs:,} attributes ({attrs * GLUE_ATTR:,} units), more than "
                             f"remain of the budget")
        self.units -= attrs * GLUE_ATTR


def stored_len(attrs: object) -> int:
    """The attributes ``attrs`` (a class's ``__dict__``, an instance's, or None) stores: a dict subclass's by dict's
    own ``len`` (an instance's ``__dict__`` may be one whose ``len`` and ``items`` are its own, fuzz 67a C1: 10**5
    attributes billed as 0 and walked, 34.4 CPU-s accepted), 0 for anything but a dict or a class's mapping."""
    if isinstance(attrs, dict):
        return dict.__len__(attrs)
    return len(attrs) if isinstance(attrs, types.MappingProxyType) else 0


def stored_keys(attrs: object) -> collections.abc.Set:
    """The names ``attrs`` stores (``stored_len``'s rule: a dict subclass's by dict's own ``keys``)."""
    return dict.keys(attrs) if isinstance(attrs, dict) else attrs.keys() if stored_len(attrs) else frozenset()


def stored_items(attrs: object) -> list[tuple[object, object]]:
    """The attributes ``attrs`` stores, as a list (``stored_len``'s rule: a dict subclass's by dict's own ``items``)."""
    return list(dict.items(attrs) if isinstance(attrs, dict) else attrs.items())
