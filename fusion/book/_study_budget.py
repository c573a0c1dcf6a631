"""Rule 17 of a chapter study that runs several budgeted studies: their SUM counted at its entry (fuzz 54a C2-C4, D4).

A chapter's composite study (chapter 04's ``cached_studies``, chapter 07's ``cached_study``, chapter 01's studies
that fuse their own draws, chapter 05's ``paired_study``) passes its ``runs`` to several inner studies, each of which
checks its own budget when it starts. Checked one by one, a ``runs`` that each accepts alone ran them all (16-27
CPU-s, once a raw MemoryError), and a ``runs`` that only a later one refuses ran the earlier ones first (8-11 CPU-s)
and was then refused naming the inner study's arguments (``x``, ``z``, ``scales and runs``), not the caller's
``runs``. :func:`studies_first` runs every inner study's OWN budget function (its memory, input and work rules, the
weights its comment states: no new numbers) before any work, sums their units against the one work budget
(``fusion._limits.work``) and refuses by the caller's arguments.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from fusion._limits import MAX_WORK, work

__all__: list[str] = []


def studies_first(parts: Iterable[Callable[[], object]], names: str, limit: int = MAX_WORK,
                  served: str | None = None) -> int:
    """Count, before any work, what a chapter study will run: each inner study's own budget, then their sum.

    Parameters
    ----------
    parts : iterable of callable
        One per inner study (or per pass of one), each calling that study's own budget function on the counts the
        caller will pass it and returning its units of work (an int; ``None`` for a memory or input check only). Its
        ``ValueError`` (the inner study's memory, input or work budget) is re-raised naming ``names``.
    names : str
        The caller's arguments that set the counts (``"runs"``, ``"seed and runs"``), named first in every refusal.
    limit : int
        The budget of the sum (``fusion._limits.MAX_WORK``; a ``STUDY_WORK`` entry where the chapter's own call has
        one).
    served : str, optional
        The key of ``STUDY_WORK`` whose entry ``limit`` is (``fusion._limits.work``'s ``served``).

    Returns
    -------
    int
        The summed units of work.

    Raises
    ------
    ValueError
        An inner study's own refusal, or the sum beyond ``limit``, naming ``names``, before any study runs.
    """
    prefix = f"{names} ask for studies beyond the budget, refused before any study: "
    total = 0
    for part in parts:
        try:
            units = part()
        except ValueError as e:
            # a part that is itself a summed study refuses with the same words: said once
            raise ValueError(str(e) if str(e).startswith(prefix) else prefix + str(e)) from None
        total += 0 if units is None else int(units)  # type: ignore[call-overload]
    try:
        work((total,), "the studies' summed units", limit=limit, served=served)
    except ValueError as e:
        raise ValueError(prefix + str(e)) from None
    return total


def repeated(part: Callable[[], object], times: int) -> Callable[[], int | None]:
    """One part of :func:`studies_first` standing for ``times`` identical passes of an inner study (one per entry of
    a caller's sequence): ``part``'s units once, times ``times`` (a closed form; ``None`` stays ``None``).

    A list of one part per entry called every part before the sum was checked, after every entry was converted:
    ``fruit_fly_step_targets`` with 2,000,000 targets was refused after 10.7-14.9 CPU-s (fuzz 58a C3). A caller
    counts its sequence's entries with this before it converts them.
    """
    def whole() -> int | None:
        units = part()
        return None if units is None else int(units) * times  # type: ignore[call-overload]

    return whole
