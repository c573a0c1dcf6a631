"""Chapter 01 (the optimal fusion set, Yang, Feng & Fan 2012): source, methods, seed and noise readings."""

from __future__ import annotations

from collections.abc import Mapping
from enum import StrEnum

import numpy as np

from fusion._frozen import constant
from fusion.book.style import METHOD_LABELS
from fusion.scenarios import thermocouples
from fusion._options import flag, one_of
from fusion._shown import shown

__all__ = [
    "SOURCE",
    "METHODS",
    "SEED",
    "N_RUNS",
    "NOISE",
    "CHAPTER",
    "FailureCase",
]


#: BibTeX key of the source.
SOURCE = "yang2012optimal"

#: Docname of the chapter.
CHAPTER = "notebooks/01_optimal_fusion_set"

#: The three methods of the source's comparison, as :func:`fusion.readings.fusion_set.fuse_epochs` specs.
METHODS: dict[str, dict[str, object]] = constant({
    "optimal_fusion_set": {"method": "optimal_fusion_set"},
    "mean": {"method": "mean"},
    "support_degree": {"method": "support_degree"},
})


class FailureCase(StrEnum):
    """Keys of the chapter's two cases (labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    NONE
        Every sensor healthy (samples 1-100).
    FAILURE
        Sensors 4 and 10 biased at samples 50-80 (the source's Fig. 3).
    """

    NONE = "ofs_no_failure"
    FAILURE = "ofs_failure"


# --------------------------------------------------------------------------- studies (cached)
#: Seed and Monte-Carlo runs of the chapter's primary readings.
SEED, N_RUNS = 2012, 500

#: Readings of the noise levels the source does not give: the primary (unequal, evenly spaced), equal noise, and
#: geometric spreads σ_max/σ_min = r from r^-1/2 to r^1/2 °C (the fair study's spread sweep; r = 4 is 0.5-2.0 °C).
NOISE: dict[str, object] = constant({"unequal": thermocouples.DEFAULT_SIGMAS, "equal": 1.0,
                            **{f"geometric-{r}": np.geomspace(r ** -0.5, r ** 0.5, 10) for r in (2, 4, 8, 16)}})


def _noise_key(noise: object, name: str = "noise") -> str:
    """A key of :data:`NOISE` given as text (a ``str``, ``numpy.str_`` or a :class:`~enum.StrEnum` member, matched by
    its text), as a plain ``str``; TypeError naming ``name`` for anything else (never ``str()`` of an object: fuzz
    22b, NS), ValueError for another text."""
    return one_of(noise, tuple(sorted(NOISE)), name)


def _noise(settings: Mapping[str, object]) -> str:
    """The noise reading of a record's settings (``settings['noise']``, default ``"unequal"``), by :func:`_noise_key`."""
    return _noise_key(settings.get("noise", "unequal"), "settings['noise']")


def _setting(settings: Mapping[str, object], key: str, default: str, allowed: tuple[str, ...]) -> str:
    """The text option ``settings[key]`` (``default`` when absent), one of ``allowed``, as the plain ``str`` its check
    returns (rule 19 of ``fusion._validation``; never ``str()`` of the caller's object: fuzz 32b C1, a ``(str, Enum)``
    member prints as ``K.M``); TypeError/ValueError naming ``settings[key]``."""
    return one_of(settings.get(key, default), allowed, f"settings['{key}']")


def _flag(settings: Mapping[str, object], key: str, default: bool) -> bool:
    """The yes/no option ``settings[key]`` (``default`` when absent) as a ``bool``: a bool or ``numpy.bool_`` only,
    TypeError naming ``settings[key]`` otherwise (fuzz 52 C7's class: ``bool("no")`` read ``"no"`` as true)."""
    return flag(settings.get(key, default), f"settings['{key}']")


def _failure(settings: Mapping[str, object]) -> str:
    """The failure reading of a record's settings (``settings['failure']``, default ``"fixed"``), one of
    :data:`fusion.scenarios.thermocouples.FAILURE_MODES`, by :func:`_setting`."""
    return _setting(settings, "failure", "fixed", tuple(thermocouples.FAILURE_MODES))


def _case(settings: Mapping[str, object]) -> FailureCase:
    """The case a reading names by its label (``settings['case']``, default no failure): the claim files keep the text."""
    by_label = {METHOD_LABELS[c]: c for c in FailureCase}
    case = one_of(settings.get("case", METHOD_LABELS[FailureCase.NONE]), tuple(sorted(by_label)), "settings['case']")
    if case not in by_label:
        raise ValueError(f"settings['case'] must be one of {sorted(by_label)}, got {shown(case)}")
    return by_label[case]
