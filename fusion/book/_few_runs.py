"""Rule R4's refusal of a short paired comparison, named by the caller's argument (fuzz 22b, class A2).

:class:`fusion.book.ledger.Comparison` refuses fewer than :data:`fusion.book.rulebook.MIN_RUNS` runs without a
``reason``, naming its own ``a and b`` and its argument ``reason``. A chapter function that builds comparisons
from its caller's study and takes no ``reason`` passes that message on unactionable (the caller has no ``a``, ``b``
or ``reason``); :func:`runs_named` turns it into one naming the caller's argument and the minimum.
"""

from __future__ import annotations

import contextlib
import functools
import inspect
import numbers
from collections.abc import Callable, Iterator, Mapping
from typing import Any, TypeVar

_F = TypeVar("_F", bound=Callable[..., Any])


class FewRunsError(ValueError):
    """Rule R4: a paired comparison of fewer than ``MIN_RUNS`` runs without a reason (a ValueError).

    Parameters
    ----------
    message : str
    runs, minimum : int, optional
        The comparison's run count and the rule's minimum (``None`` only while a caller's path prefix rebuilds it,
        ``fusion._structures.within``, which copies them).
    """

    def __init__(self, message: str, runs: int | None = None, minimum: int | None = None) -> None:
        super().__init__(message)
        self.runs = runs
        self.minimum = minimum


def few_runs(name: str, runs: int, minimum: int, how: str) -> FewRunsError:
    """Rule R4's refusal of paired comparisons of ``runs`` runs, fewer than ``minimum``, naming the caller's argument
    ``name`` (the one message of :func:`runs_named`; a caller that knows its comparisons' run count raises it before
    any study, fuzz 27b B4).

    Parameters
    ----------
    name : str
        The caller's argument that sets the run count (``"runs"``).
    runs, minimum : int
        The comparisons' run count and the rule's minimum.
    how : str
        How the caller gives more runs (``"the argument runs"``), ended into the message.

    Returns
    -------
    FewRunsError
        The refusal, to raise.
    """
    return FewRunsError(f"{name} gives paired comparisons of {runs} runs, fewer than the {minimum} rule R4 asks "
                        f"without a reason (this function takes none): give at least {minimum} runs ({how})",
                        runs, minimum)


def runs_first(runs: object, name: str = "runs", how: str = "the argument runs") -> int:
    """Rule R4 before the work: ``runs`` of a reader whose evidence certainly holds a paired comparison of exactly
    ``runs`` runs without a reason, refused below the rulebook's ``MIN_RUNS`` before any study is computed.

    A chapter's reader that builds its record's readings from studies of ``runs`` runs refused too few runs only
    when the comparison was made, after the studies (fuzz 57c: ``ev_fig7_improved_vs_ci({}, seed=2024, runs=3)``
    computed chapter 05's studies, ~9 CPU-s, then refused). The caller calls this where the refusal is certain
    (the record's readings are built together and one compares ``runs`` runs without a reason; its settings
    already read), before the studies; the refusal is :func:`few_runs`'s, so a surrounding :func:`runs_named`
    re-raises it as before.

    Parameters
    ----------
    runs : int
        The caller's run count (a count of at least 1, checked here by name).
    name : str
        The caller's argument.
    how : str
        How the caller gives more runs, ended into the message.

    Returns
    -------
    int
        ``runs``, checked (a plain int).

    Raises
    ------
    TypeError
        ``runs`` not an integer.
    ValueError
        ``runs`` below 1; :class:`FewRunsError` (a ValueError) when below ``MIN_RUNS``.
    """
    from fusion._counts import count
    from fusion.book.rulebook import MIN_RUNS

    n = count(runs, name)
    if n < MIN_RUNS:
        raise few_runs(name, n, MIN_RUNS, how)
    return n


@contextlib.contextmanager
def runs_named(name: str, how: str) -> Iterator[None]:
    """Re-raise rule R4's refusal inside the block as a ValueError naming ``name`` and the minimum.

    Parameters
    ----------
    name : str
        The caller's argument that sets the run count (``"runs"``, ``"study"``).
    how : str
        How the caller gives more runs (e.g. ``"fair_study(n_runs=...)"``), ended into the message.
    """
    try:
        yield
    except FewRunsError as e:
        # still a FewRunsError (a ValueError): a caller further out that names its own argument renames it, so the
        # message names the argument of the function the user called (glue_21(s) calls awf_log_comparison(s21))
        raise few_runs(name, e.runs, e.minimum, how) from e  # type: ignore[arg-type]


def study_runs_named(name: str) -> Callable[[_F], _F]:
    """Decorator: a chapter function that builds paired comparisons from its argument ``name`` (a study, or a mapping
    of studies) and takes no ``reason`` refuses a study of fewer than ``MIN_RUNS`` runs by a ValueError naming
    ``name`` (:func:`runs_named`; issue 35: the message named the comparison's own ``a and b``); signature and
    docstring kept.

    Parameters
    ----------
    name : str
        The argument that holds the runs.

    Returns
    -------
    callable
        The decorator.
    """
    def decorate(fn: _F) -> _F:
        @functools.wraps(fn)
        def named(*args: Any, **kwargs: Any) -> Any:
            with runs_named(name, f"a study of more runs as {name}"):
                return fn(*args, **kwargs)
        return named  # type: ignore[return-value]
    return decorate


def paired_runs(runs: object, name: str = "runs") -> int:
    """``runs`` of a function whose readings compare paired runs: a count of at least 2, refused by the caller's
    ``name`` before any study (fuzz 26b R1b, 35b B1: one run was refused by the comparison's own ``a and b``).

    Parameters
    ----------
    runs : int
        The caller's run count.
    name : str
        The caller's argument.

    Returns
    -------
    int
        ``runs``, checked.
    """
    from fusion._counts import count

    return count(runs, name, minimum=2)


def reader_runs_named(fn: _F) -> _F:
    """An evidence function ``fn(settings, *, seed, runs)`` whose rule R4 refusal names its argument ``runs``
    (:func:`runs_named`; one run without a reason is such a refusal too: ``Comparison``); signature and docstring
    kept."""
    @functools.wraps(fn)
    def named(*args: Any, **kwargs: Any) -> Any:
        with runs_named("runs", "the argument runs"):
            return fn(*args, **kwargs)
    return named  # type: ignore[return-value]


def studies_runs_named(*names: str) -> Callable[[_F], _F]:
    """A function that builds comparisons from the studies it is given as the arguments ``names`` (each with a
    ``runs``) and takes no ``reason``: its rule R4 refusal names the study arguments with fewer runs than the
    minimum (every one of ``names`` if none has a ``runs`` below it); signature and docstring kept."""
    def rename(given: dict[str, Any], e: FewRunsError) -> None:
        short = [n for n in names if isinstance(getattr(given.get(n), "runs", None), numbers.Integral)
                 and given[n].runs < e.minimum] or list(names)   # type: ignore[operator]
        raise ValueError(f"{' and '.join(short)} gives paired comparisons of {e.runs} runs, fewer than the "
                         f"{e.minimum} rule R4 asks without a reason (this function takes none): give a study "
                         f"of at least {e.minimum} runs") from e
    return lambda fn: _renamed(fn, rename)


def _renamed(fn: _F, rename: Callable[[dict[str, Any], FewRunsError], None]) -> _F:
    """``fn`` whose rule R4 refusal is re-raised by ``rename(arguments bound by name, the refusal)``; signature and
    docstring kept."""
    signature = inspect.signature(fn)

    @functools.wraps(fn)
    def named(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except FewRunsError as e:
            rename(signature.bind(*args, **kwargs).arguments, e)
            raise
    return named  # type: ignore[return-value]


def _short_fields(record: object, minimum: int | None) -> list[str]:
    """The fields of the result record ``record`` (a dataclass) holding a study of fewer than ``minimum`` runs: a
    field whose value, or an entry of it (a tuple of studies, a mapping of them: a dict or the read-only mapping a
    record stores, fuzz 27a D6), has an integer ``runs`` below it."""
    import dataclasses

    if minimum is None or not dataclasses.is_dataclass(record):
        return []
    short = []
    for f in dataclasses.fields(record):
        value = getattr(record, f.name, None)
        parts = (list(value.values()) if isinstance(value, Mapping) else list(value) if isinstance(value, (tuple, list))
                 else [value])
        if any(isinstance(getattr(p, "runs", None), numbers.Integral) and p.runs < minimum for p in parts):
            short.append(f.name)
    return short


def inputs_runs_named(name: str) -> Callable[[_F], _F]:
    """Decorator: a function of a record of results (its argument ``name``, e.g. a chapter's ``LedgerInputs``
    ``r``) that builds paired comparisons from the studies it holds and takes no ``reason`` refuses a study of fewer
    than ``MIN_RUNS`` runs by a FewRunsError naming the record's fields that hold one (``r.arch``; ``r`` when none
    is found) and the minimum (fuzz 26c A5: the message named the comparison's ``a and b`` and ``reason``);
    signature and docstring kept.

    Parameters
    ----------
    name : str
        The argument that holds the record.

    Returns
    -------
    callable
        The decorator.
    """
    def rename(given: dict[str, Any], e: FewRunsError) -> None:
        fields = [f"{name}.{f}" for f in _short_fields(given.get(name), e.minimum)] or [name]
        with runs_named(" and ".join(fields), f"studies of at least {e.minimum} runs in {name}"):
            raise e
    return lambda fn: _renamed(fn, rename)
