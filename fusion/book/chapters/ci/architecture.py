"""The feedback architecture of the source's Fig. 2 beside independent filters: tables, figure and numbers."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter
from numpy.typing import ArrayLike

from fusion._docstrings import reads_results
from fusion._validation import count, shown, text, instance_of, scalar
from fusion._counts import general, seeds as check_seeds, sequence
from fusion._limits import work
from fusion.book.style import METHOD_LABELS, METHOD_SHORT_LABELS, color, new_figure, _panels
from fusion.book.tables import rounded
from fusion.book.glue import GlueValues
from fusion.scenarios import two_sensor
from fusion.scenarios.two_sensor import Architecture, ArchitectureStudy, ArchRule
from fusion.book.chapters.ci.checks import _arch_pair, _frame, _results
from fusion.book.chapters.ci.constants import (BSC_N, CI_N, CVX_N, FB, FBC, IND, LIT, LIT_OWN, LOSSLESS_N, PRINTED,
                                               PRINTED_OWN, SOURCE_T, SPLIT_O, SPLIT_S)
from fusion.book.chapters.ci.text import _glue_doc, nees_band, paired_text
from fusion.book.chapters.ci.tracking import ANISO_LABEL, ANISO_R, IDENTICAL_LABEL
from fusion._shown import shown
from fusion.book._t_interval import constant_to_round_off, mean_interval

__all__ = ["architecture_numbers", "architecture_table", "architecture_figure", "q_scaling_table", "q_numbers",
           "architecture_studies", "rule_label", "architecture_row"]

#: A fixed-weight rule key of :func:`fusion.scenarios.two_sensor.fixed_weight_rule`: (base rule key, weight).
_FIXED_WEIGHT = re.compile(r"(arch_printed_(?:shared|own))_w(.+)")


def rule_label(rule: str) -> str:
    """Display label of a rule key of :class:`~fusion.scenarios.two_sensor.ArchitectureStudy`.

    An :class:`~fusion.scenarios.two_sensor.ArchRule` is labelled by :data:`fusion.book.style.METHOD_LABELS`; a key of
    :func:`~fusion.scenarios.two_sensor.fixed_weight_rule` by its base rule's label with the weight after "as printed"
    (``"eqs. 11-12 as printed, ω = 0.0018, Q in shared part"``).

    Parameters
    ----------
    rule : str
        A rule key.

    Returns
    -------
    str
        The rule's label in :data:`fusion.book.style.METHOD_LABELS`, or for a fixed weight its base rule's label with
        ``as printed, ω = <weight>``.

    Raises
    ------
    TypeError
        ``rule`` is not a string.
    ValueError
        ``rule`` is not a rule key (an enum member's name such as ``"CONVEX"`` is not its value).
    """
    return _rule_label(rule, "rule")


def _rule_label(rule: str, name: str) -> str:
    """:func:`rule_label`, naming the argument ``name`` in its refusals."""
    rule = text(rule, name)  # its plain text (rule 19), the one looked up below
    fixed = _FIXED_WEIGHT.fullmatch(rule)
    base = rule if fixed is None else fixed[1]
    if base not in METHOD_LABELS:
        raise ValueError(f"{name} must be a rule key of the architecture study (an ArchRule value or a fixed-weight "
                         f"rule key), got {shown(rule)}")
    if fixed is None:
        return METHOD_LABELS[rule]
    return METHOD_LABELS[fixed[1]].replace("as printed, ", f"as printed, ω = {fixed[2]}, ", 1)


def architecture_row(key: tuple[str, str]) -> tuple[str, str]:
    """The row of :func:`architecture_table` of an (architecture, rule) key: (architecture's short label, rule's label).

    Parameters
    ----------
    key : (str, str)
        An (:class:`~fusion.scenarios.two_sensor.Architecture`, rule key) key of the study.

    Returns
    -------
    (str, str)
        The architecture's short label (:data:`fusion.book.style.METHOD_SHORT_LABELS`) and the rule's label
        (:func:`rule_label`).

    Raises
    ------
    TypeError
        ``key`` is not a pair of strings.
    ValueError
        ``key[0]`` is not an architecture or ``key[1]`` not a rule key.
    """
    if isinstance(key, (str, bytes)) or not isinstance(key, Sequence) or len(key) != 2:
        raise TypeError(f"key must be an (architecture, rule) pair, got {shown(key)}")
    arch = text(key[0], "key[0]")
    if arch not in {a.value for a in Architecture} or arch not in METHOD_SHORT_LABELS:
        raise ValueError(f"key[0] must be an Architecture value {tuple(a.value for a in Architecture)}, "
                         f"got {shown(arch)}")
    return METHOD_SHORT_LABELS[arch], _rule_label(key[1], "key[1]")


@reads_results("qs", "ai")
def q_scaling_table(qs: two_sensor.QScaling, ai: ArchitectureStudy) -> pd.DataFrame:
    r"""The Q-scaling control beside split CI fed back, on the same paired runs.

    Parameters
    ----------
    qs : QScaling
        :func:`fusion.scenarios.two_sensor.q_scaling_study` drawn with the seed of ``ai`` (the same noise).
    ai : ArchitectureStudy
        The identical-sensor :func:`fusion.scenarios.two_sensor.architecture_study`.

    Returns
    -------
    pandas.DataFrame
        Rows: CI of independent filters running :math:`cQ` for each scale, then split CI fed back (Q in the shared
        part); columns: mean per-run RMSE on x on the path (m), its paired 95 % difference from CI with the
        filters' :math:`Q` (m), the same on targets that follow the model, and the mean NEES there.
    """
    _same_runs(qs, ai, (1.0,))
    base, base_m = qs.run_rmse[1.0], qs.model_rmse[1.0]

    def d(v: np.ndarray, b: np.ndarray) -> str:
        m, h = _mean_ci(v - b)
        return "0 (same estimate)" if h == 0.0 and m == 0.0 else f"{m:+.2f} ± {h:.2f}"

    rows = {f"CI, independent filters running {c:g} Q": (float(qs.run_rmse[c].mean()), d(qs.run_rmse[c], base),
                                                          float(qs.model_rmse[c].mean()), d(qs.model_rmse[c], base_m),
                                                          qs.nees[c]) for c in qs.scales}
    key = (FB, SPLIT_S)
    rows["split CI fed back (Fig. 2), filters running Q"] = (float(ai.run_rmse[key].mean()), d(ai.run_rmse[key], base),
                                                            float(ai.model_rmse[key].mean()), d(ai.model_rmse[key], base_m),
                                                            ai.nees[key])
    t = pd.DataFrame.from_dict(rows, orient="index", columns=[
        "path: RMSE x (m)", "path: − CI with Q (m, 95 %)", "model targets: RMSE x (m)",
        "model targets: − CI with Q (m, 95 %)", "NEES (model targets)"])
    return t.round(2)


# --------------------------------------------------------------------------- architectures
_ARCH_BASE = (IND, CI_N)


def _same_runs(qs: object, ai: object, scales: tuple[float, ...]) -> None:
    """``qs`` a Q-scaling study with the ``scales`` read, drawn on the runs of ``ai`` (issue 35: paired arguments
    agree): CI with the filters' own Q (scale 1) is the same in both, else a ValueError names them."""
    instance_of(qs, two_sensor.QScaling, "qs")
    instance_of(ai, ArchitectureStudy, "ai")
    assert isinstance(qs, two_sensor.QScaling) and isinstance(ai, ArchitectureStudy)
    missing = [c for c in scales if c not in qs.run_rmse]
    if missing:
        raise ValueError(f"qs lacks the scales {missing} (it must hold {list(scales)})")
    if _ARCH_BASE not in ai.run_rmse or not np.array_equal(qs.run_rmse[1.0], ai.run_rmse[_ARCH_BASE]):
        raise ValueError("qs and ai must share their runs (the same seed): CI with Q differs between them")


def _mean_ci(x: np.ndarray) -> tuple[float, float]:
    """Mean and half-width of Student's 95 % interval of the mean (scipy.stats); 0 for data constant to round-off
    (``fusion.book._t_interval``: scipy warned of precision loss on differences equal up to round-off, fuzz 37b C3)."""
    x = np.asarray(x, dtype=float)
    if constant_to_round_off(x):
        return float(x.mean()), 0.0
    lo, hi = mean_interval(x, 0.95)
    return float(x.mean()), float(hi - x.mean())


def _studies(studies: object, name: str) -> Mapping[str, ArchitectureStudy]:
    """Architecture studies by label (fuzz 19, D17/F14/F15): a non-empty mapping of ArchitectureStudy, each
    holding the baseline rule (CI on independent filters)."""
    studies = _results(studies, name, ArchitectureStudy, "architecture_studies")  # read once (decision 31a C2)
    for label, st in studies.items():
        if _ARCH_BASE not in st.run_rmse:
            raise ValueError(f"{name}[{shown(label)}] lacks CI on independent filters, the baseline of the table")
    return studies


#: Units of work of one row of one study in :func:`architecture_table` (its paired 95 % interval, labels and cells):
#: 440-500 us measured (a study of 19 rows under 100 and 300 labels, 3 and 2,000 runs: 8.4-9.4 ms a study, the
#: shared machine, other helpers running; fix71d), on top of ``_TABLE_RUN_UNITS`` a run.
_TABLE_ROW_UNITS = 50_000
#: Units of one run of one row in :func:`architecture_table` (the difference, mean and interval: vectorised passes).
_TABLE_RUN_UNITS = 5


def _table_budget(studies: Mapping[str, ArchitectureStudy]) -> int:
    """Rule 17 of :func:`architecture_table` before its loop (fuzz 63a C4: the studies were never counted, one small
    study under 5,000 labels was accepted after 48.0 CPU-s): every study's rows, each ``_TABLE_ROW_UNITS`` plus
    ``_TABLE_RUN_UNITS`` a run, refused naming ``studies``."""
    units = sum(len(st.run_rmse) * (_TABLE_ROW_UNITS + _TABLE_RUN_UNITS * int(np.size(st.run_rmse[_ARCH_BASE])))
                for st in studies.values())
    return work((1,), "studies", weight=units)


def architecture_table(studies: Mapping[str, ArchitectureStudy]) -> pd.DataFrame:
    r"""Every rule with and without the source's Fig. 2 feedback, per sensor pair.

    Parameters
    ----------
    studies : mapping of str to ArchitectureStudy
        One :func:`fusion.scenarios.two_sensor.architecture_study` per sensor pair, keyed by a label.

    Returns
    -------
    pandas.DataFrame
        Indexed by (architecture, rule), their display labels (:func:`architecture_row`); per sensor pair: mean per-run RMSE on x (m), the paired
        95 % interval of its difference from CI without feedback (m; ``ttest_rel``), the reported
        :math:`\sqrt{P_{xx}}` (m) and the mean NEES (4 when consistent). Rounded to 2 decimals.

    Raises
    ------
    TypeError
        ``studies`` not a mapping, or an entry not an ArchitectureStudy.
    ValueError
        ``studies`` empty, or a study without CI on independent filters (the baseline of the differences); studies
        whose rows (their (architecture, rule) keys, each a paired interval) are beyond the work budget
        (``fusion._limits.MAX_WORK``, 50,000 units a row plus 5 a run: about 1,000 studies of chapter 05's 19 rows),
        before the first.
    """
    studies = _studies(studies, "studies")
    _table_budget(studies)
    cols = {}
    for label, st in studies.items():
        base = st.run_rmse[_ARCH_BASE]
        rmse, diff, rep, nee = {}, {}, {}, {}
        for key, v in st.run_rmse.items():
            d = v - base
            m, h = _mean_ci(d)
            row = architecture_row(key)
            rmse[row] = float(v.mean())
            diff[row] = "0 (same estimate)" if h == 0.0 and m == 0.0 else f"{m:+.2f} ± {h:.2f}"
            # fuzzy clustering reports no covariance: no reported √P and no NEES
            rep[row], nee[row] = st.reported.get(key, np.nan), st.nees.get(key, np.nan)
        cols[(label, "RMSE x (m)")] = pd.Series(rmse).round(2)
        cols[(label, "− CI indep. (m, 95 %)")] = pd.Series(diff)
        cols[(label, "reported √P (m)")] = pd.Series(rep).round(2)
        cols[(label, "NEES")] = pd.Series(nee).round(2)
    table = pd.DataFrame(cols)
    table.index.names = ["architecture", "rule"]
    return table


def _short_rule(name: str) -> str:
    """A rule's label shortened for the tick labels of :func:`architecture_figure` ("eqs. 11-12, ω = 0.0018, Q shared")."""
    return (name.replace("eqs. 11-12 as printed", "eqs. 11-12").replace(", Q in shared part", ", Q shared")
            .replace(", Q in own part", ", Q own").replace(" (fed-back prior removed once)", "").replace(" (closed-form ω)", ""))


def architecture_figure(studies: Mapping[str, ArchitectureStudy]) -> Figure:
    """Mean per-run RMSE on x (filled, 95 % interval) and the reported √P (open) of every rule and architecture.

    Parameters
    ----------
    studies : mapping of str to ArchitectureStudy
        As for :func:`architecture_table`; one panel each, one row per rule run on every pair.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per pair of sensors, one row per rule: each architecture's mean RMSE on x (m, log axis) with its 95 %
        interval, open markers at the reported √P.

    Raises
    ------
    TypeError
        ``studies`` not a mapping, or an entry not an ArchitectureStudy.
    ValueError
        ``studies`` empty, holding more than 16 studies (one panel each, the book style's limit), or a study without CI
        on independent filters.
    """
    studies = _studies(studies, "studies")
    fig, axes = new_figure(1, _panels(len(studies), "studies", "studies"), figsize=(7.5, 6.8), sharey=True,
                           squeeze=False)
    first = next(iter(studies.values()))
    # the rules run on every pair (a reading run on one pair only, e.g. a fixed weight, is in the table only)
    rules = [name for name in dict.fromkeys(name for _, name in first.run_rmse)
             if all(any(n == name for _, n in st.run_rmse) for st in studies.values())]
    archs = list(dict.fromkeys(arch for arch, _ in first.run_rmse))
    offsets = {a: (i - (len(archs) - 1) / 2) * 0.2 for i, a in enumerate(archs)}
    markers = dict(zip(archs, "osD^"))
    for ax, (label, st) in zip(axes[0], studies.items()):
        for arch in archs:
            ys, xs, hs, reps = [], [], [], []
            for i, name in enumerate(rules):
                if (arch, name) in st.run_rmse:
                    m, h = _mean_ci(st.run_rmse[(arch, name)])
                    ys.append(i + offsets[arch])
                    xs.append(m)
                    hs.append(h)
                    reps.append(st.reported.get((arch, name), np.nan))   # none for fuzzy clustering
            ax.errorbar(xs, ys, xerr=hs, fmt=markers[arch], color=color(arch), ms=6, capsize=2,
                        label=METHOD_LABELS[arch])
            ax.plot(reps, ys, markers[arch], mfc="none", color=color(arch), ms=8)
        ax.set(xscale="log", title=label.split(" (")[0] if len(label) > 30 else label, xlabel="RMSE on x (m)")
        shown_v = [v for line in ax.get_lines() for v in np.atleast_1d(line.get_xdata()) if np.isfinite(v) and v > 0]
        ax.set_xlim(min(shown_v) / 1.15, max(shown_v) * 1.15)   # room for the open markers at both ends
        lo, hi = ax.get_xlim()
        ticks = (20, 50, 100, 200, 500, 1000) if hi / lo > 12 else (15, 20, 30, 40, 50, 100, 200)
        ax.xaxis.set_major_locator(FixedLocator([v for v in ticks if lo <= v <= hi]))
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.xaxis.set_minor_formatter(NullFormatter())
    axes[0][0].set_yticks(range(len(rules)), [_short_rule(rule_label(r)) for r in rules])
    axes[0][0].invert_yaxis()
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=9)
    return fig


@_glue_doc("rounded as the prose shows it")
def architecture_numbers(arch: Mapping[str, ArchitectureStudy], arch_table: pd.DataFrame, arch_runs: int,
                         k_steady: int) -> GlueValues:
    """The numbers the prose quotes from the feedback-architecture study (glue keys ``ci_fb_*``, ``ci_model_*``, ``ci_arch_*``).

    Parameters
    ----------
    arch : mapping
        Identical-sensor and anisotropic-pair :class:`~fusion.scenarios.two_sensor.ArchitectureStudy`, in that order,
        keyed by ``IDENTICAL_LABEL`` and ``ANISO_LABEL``; the first run with the published weight among its
        ``printed_omegas`` (and 0.1, 0.5).
    arch_table : pandas.DataFrame
        :func:`architecture_table` of ``arch``.
    arch_runs : int
        Monte-Carlo runs of each study.
    k_steady : int
        Steps averaged (t ≥ 20 s), for the eq. 13 slip √(Σe²)/n = RMSE/√n of the printed rule; at most the
        steps of the chapter's path at T = ``SOURCE_T``.

    Raises
    ------
    TypeError
        ``arch`` not a mapping of ArchitectureStudy, ``arch_table`` not a DataFrame, a count not an integer.
    ValueError
        ``arch`` not the two studies keyed ``IDENTICAL_LABEL`` then ``ANISO_LABEL`` or lacking a rule read here, or
        its studies swapped or one twice (told apart by the rules they record: architecture_studies runs Q's
        placement on the identical sensors only);
        ``arch_table`` not :func:`architecture_table` of ``arch``; ``arch_runs`` not the studies' runs;
        ``k_steady`` not in 1 .. the path's steps.
    """
    arch = _studies(arch, "arch")
    if list(arch) != [IDENTICAL_LABEL, ANISO_LABEL]:
        raise ValueError(f"arch must hold the two studies of architecture_studies, keyed {shown(IDENTICAL_LABEL)} then "
                         f"{shown(ANISO_LABEL)}, got the keys {shown(list(arch), 200)}")
    ai, an = arch.values()
    _arch_pair(ai, an, (f"arch[{shown(IDENTICAL_LABEL)}]", f"arch[{shown(ANISO_LABEL)}]"))
    _frame(arch_table, "arch_table", (), maker="architecture_table")
    if not arch_table.equals(architecture_table(arch)):
        raise ValueError("arch_table must be architecture_table(arch): it differs (a table of other studies?)")
    arch_runs = count(arch_runs, "arch_runs")
    if arch_runs != ai.runs or arch_runs != an.runs:
        raise ValueError(f"arch_runs = {arch_runs} is not the studies' runs ({ai.runs}, {an.runs})")
    k_steady = count(k_steady, "k_steady")
    steps = two_sensor.trajectory(SOURCE_T).t.size
    if k_steady > steps:
        raise ValueError(f"k_steady = {k_steady} exceeds the {steps} steps of the chapter's path")
    try:
        return _architecture_numbers(ai, an, arch_table, arch_runs, k_steady)
    except KeyError as exc:   # a study run without a rule the prose quotes (another printed_omegas)
        raise ValueError(f"arch lacks the rule {shown(exc.args[0])}, which architecture_studies runs") from None


def _architecture_numbers(ai: ArchitectureStudy, an: ArchitectureStudy, arch_table: pd.DataFrame, arch_runs: int,
                          k_steady: int) -> GlueValues:
    """The values of :func:`architecture_numbers`, from its checked arguments."""
    SPL, SPL_OWN, LOSS, BSC = SPLIT_S, SPLIT_O, LOSSLESS_N, BSC_N
    col_d = (IDENTICAL_LABEL, "− CI indep. (m, 95 %)")
    col_a = (ANISO_LABEL, "− CI indep. (m, 95 %)")
    row = architecture_row
    central = (Architecture.CENTRALISED, ArchRule.CENTRALISED_KF)
    m = lambda st, k: rounded(float(st.run_rmse[k].mean()), 1)   # noqa: E731
    return {"ci_arch_runs": arch_runs,
            "ci_fb_ci": m(ai, (FB, CI_N)),
            "ci_fb_cvx": m(ai, (FB, CVX_N)),
            "ci_fb_cvx_rep": rounded(ai.reported[(FB, CVX_N)], 1), "ci_fb_cvx_nees": rounded(ai.nees[(FB, CVX_N)], 0),
            "ci_fb_split_d": arch_table.loc[row((FB, SPL)), col_d], "ci_fb_split_d_a": arch_table.loc[row((FB, SPL)), col_a],
            "ci_fb_split_nees": rounded(ai.nees[(FB, SPL)], 2), "ci_fb_split_nees_a": rounded(an.nees[(FB, SPL)], 2),
            "ci_fb_own": m(ai, (FB, SPL_OWN)),
            "ci_fbc_split": m(ai, (FBC, SPL)), "ci_fbc_split_nees": rounded(ai.nees[(FBC, SPL)], 2),
            "ci_fb_bsc": m(ai, (FB, BSC)), "ci_fb_bsc_rep": rounded(ai.reported[(FB, BSC)], 1),
            "ci_fb_loss": m(ai, (FB, LOSS)), "ci_fb_loss_rep": rounded(ai.reported[(FB, LOSS)], 1),
            "ci_fb_loss_nees": rounded(ai.nees[(FB, LOSS)], 2),
            "ci_model_loss": rounded(float(ai.model_rmse[(FB, LOSS)].mean()), 1),
            "ci_model_bsc": rounded(float(ai.model_rmse[(FB, BSC)].mean()), 1),
            "ci_model_bsc_a": rounded(float(an.model_rmse[(FB, BSC)].mean()), 1),
            "ci_model_bsc_ind_a": rounded(float(an.model_rmse[(IND, BSC)].mean()), 1),
            "ci_model_loss_a": rounded(float(an.model_rmse[(FB, LOSS)].mean()), 1),
            "ci_model_split": rounded(float(ai.model_rmse[(FB, SPL)].mean()), 1),
            "ci_model_ci": rounded(float(ai.model_rmse[(FB, CI_N)].mean()), 1),
            "ci_model_split_a": rounded(float(an.model_rmse[(FB, SPL)].mean()), 1),
            "ci_model_ci_a": rounded(float(an.model_rmse[(FB, CI_N)].mean()), 1),
            "ci_arch_central": m(ai, central),
            "ci_arch_avg": m(ai, (IND, CI_N)),
            "ci_model_central": rounded(float(ai.model_rmse[central].mean()), 1),
            "ci_model_avg": rounded(float(ai.model_rmse[(IND, CI_N)].mean()), 1),
            "ci_nees_band": rounded(nees_band(ai.nees_runs), 2),
            "ci_fb_printed_d": paired_text(ai.run_rmse[(FB, PRINTED)],
                                           ai.run_rmse[(FB, CI_N)], 3),
            "ci_fb_printed": m(ai, (FB, PRINTED)),
            "ci_fb_printed_own": m(ai, (FB, PRINTED_OWN)),
            "ci_fb_printed_gain": rounded(ai.local_gain[(FB, PRINTED)], 3),
            "ci_fb_printed_model_d": paired_text(ai.model_rmse[(FB, PRINTED)],
                                                 ai.model_rmse[(FB, CI_N)], 3),
            "ci_fb_lit_gain": rounded(ai.local_gain[(FB, LIT)], 3),
            "ci_fb_lit_own": rounded(float(ai.run_rmse[(FB, LIT_OWN)].mean()), 2),
            "ci_fb_lit_common": rounded(float(ai.run_rmse[(FBC, LIT)].mean()), 2),
            "ci_fb_lit_2": rounded(float(ai.run_rmse[(FB, LIT)].mean()), 2),
            "ci_raw_avg": rounded(150.0 / np.sqrt(2.0), 2),
            "ci_fb_lit_d": paired_text(ai.run_rmse[(FB, LIT)], ai.run_rmse[(FB, CI_N)], 3),
            "ci_fb_lit_model_d": paired_text(ai.model_rmse[(FB, LIT)], ai.model_rmse[(FB, CI_N)], 3),
            "ci_fb_lit_nees": rounded(ai.nees[(FB, LIT)], 2), "ci_fb_lit_rep": rounded(ai.reported[(FB, LIT)], 1),
            "ci_slip_lit": rounded(float(ai.run_rmse[(FB, LIT)].mean()) / np.sqrt(k_steady), 1),
            "ci_slip_printed": rounded(float(ai.run_rmse[(FB, PRINTED)].mean())
                                       / np.sqrt(k_steady), 1),
            "ci_lit_indep_d": arch_table.loc[row((IND, LIT)), col_d],
            "ci_fb_w01_d": paired_text(ai.run_rmse[(FB, two_sensor.fixed_weight_rule("shared", 0.1))],
                                       ai.run_rmse[(FB, CI_N)], 3),
            "ci_fb_w05_d": paired_text(ai.run_rmse[(FB, two_sensor.fixed_weight_rule("shared", 0.5))],
                                       ai.run_rmse[(FB, CI_N)], 3),
            "ci_a_cvx_d": arch_table.loc[row((IND, CVX_N)), col_a], "ci_a_split_d": arch_table.loc[row((IND, SPL)), col_a],
            "ci_a_bsc_d": arch_table.loc[row((IND, BSC)), col_a], "ci_a_central_d": arch_table.loc[row(central), col_a],
            "ci_a_ci": m(an, (IND, CI_N))}


@reads_results("qs", "ai")
def q_numbers(qs: two_sensor.QScaling, ai: ArchitectureStudy) -> GlueValues:
    """The numbers the prose quotes from the Q-scaling control (glue keys ``ci_q_*``).

    Parameters
    ----------
    qs : QScaling
        :func:`fusion.scenarios.two_sensor.q_scaling_study` on the runs of ``ai``.
    ai : ArchitectureStudy
        The identical-sensor architecture study.

    Returns
    -------
    dict
        Glue key -> value.

    Raises
    ------
    TypeError
        ``qs`` not a QScaling, ``ai`` not an ArchitectureStudy.
    ValueError
        ``qs`` without the scales 1 and 0.5, or not on the runs of ``ai`` (another seed or pair).
    """
    _same_runs(qs, ai, (1.0, 0.5))
    key = (FB, SPLIT_S)
    return {"ci_q_half_d": paired_text(qs.run_rmse[0.5], qs.run_rmse[1.0], 3),
            "ci_q_half_vs_split": paired_text(qs.run_rmse[0.5], ai.run_rmse[key], 2),
            "ci_q_half_model": rounded(float(qs.model_rmse[0.5].mean()), 1),
            "ci_q_half_nees": rounded(qs.nees[0.5], 2)}


def _arch_banks(fixed: int) -> tuple[int, int]:
    """Fixed-weight filter banks of :func:`architecture_studies`' two ``architecture_study`` runs with ``fixed``
    further weights: on the identical sensors the published weight and each further weight printed twice, and the
    placement at the published weight (two banks, as ``architecture_study`` counts a placement weight: fuzz 65b C1);
    on the anisotropic pair the published weight printed twice."""
    return 2 * (1 + fixed) + 2, 2 * 1


def _arch_parts(steps: int, runs: int, nees_runs: int, fixed: int, names: str) -> list[Callable[[], int]]:
    """The parts of :func:`architecture_studies` (``fusion.book._study_budget.studies_first``'s ``parts``): each
    ``architecture_study``'s own memory and units (``_architecture_units``) at its banks (:func:`_arch_banks`),
    refused naming ``names``; a chapter study that runs them beside others sums them with its own."""
    from fusion.scenarios.two_sensor.architecture import _architecture_units

    return [lambda b=b: _architecture_units(steps, runs, nees_runs, b, names) for b in _arch_banks(fixed)]


def _arch_budget(T: float, runs: int, nees_runs: int, fixed: int, names: str) -> int:
    """Rules 9 and 17 of :func:`architecture_studies` before either study: both studies' units summed
    (``fusion.book._study_budget.studies_first``) within the entry of ``fusion._limits.STUDY_WORK`` the reseeding
    sweep's call serves (fuzz 57a C5: each study was checked alone against the single study's entry, so 6,738 runs,
    3.0e9 and 2.6e9 units, were accepted and ran 68.9 CPU-s), refused naming ``names``."""
    from fusion._limits import ARCHITECTURE_STUDIES, STUDY_WORK
    from fusion.book._study_budget import studies_first

    steps = two_sensor.trajectory(T).t.size
    return studies_first(_arch_parts(steps, runs, nees_runs, fixed, names), names,
                         STUDY_WORK[ARCHITECTURE_STUDIES], ARCHITECTURE_STUDIES)


def architecture_studies(R1: ArrayLike, R2: ArrayLike, Q: ArrayLike, seeds: Sequence[int], w_pub: float, runs: int,
                         nees_runs: int, T: float = 1.0, fixed_omegas: Sequence[float] = (0.1, 0.5)
                         ) -> dict[str, ArchitectureStudy]:
    """The feedback-architecture study (:func:`fusion.scenarios.two_sensor.architecture_study`) on both sensor pairs.

    Parameters
    ----------
    R1, R2 : array_like, shape (2, 2)
        Measurement covariances of the printed identical sensors (m²).
    Q : array_like, shape (4, 4)
        Process-noise covariance (m², m²/s²).
    seeds : (int, int)
        Seeds of the identical sensors' and of the anisotropic pair's (``ANISO_R``) runs.
    w_pub : float
        The weight the source publishes for plain CI: eqs. 11-12 run at it on both pairs, and Q's placement is
        compared at it on the identical sensors.
    runs, nees_runs : int
        Runs on the path and with targets that follow the model.
    T : float
        Sampling period (s).
    fixed_omegas : sequence of float
        Further fixed weights of eqs. 11-12 on the identical sensors.

    Returns
    -------
    dict
        ``IDENTICAL_LABEL`` and ``ANISO_LABEL`` -> ArchitectureStudy.

    Raises
    ------
    TypeError
        A seed not an integer, a weight not a number.
    ValueError
        If ``seeds`` does not hold two seeds (integers >= 0), ``w_pub`` or an entry of ``fixed_omegas`` is not in
        (0, 1], or an entry of ``fixed_omegas`` repeats ``w_pub`` or another entry as printed (``f"{w:g}"``, as the
        studies are keyed); ``runs``, ``nees_runs``, ``T`` and ``fixed_omegas`` whose two studies together hold or run
        beyond the memory or work budget (their sum, the entry of ``fusion._limits.STUDY_WORK`` the reseeding sweep's
        call serves, 5e9 units: about 5,700 runs of each kind at T = 1 s), before either study.
    """
    seeds = tuple(check_seeds(seeds, "seeds"))
    w_pub = scalar(w_pub, "w_pub", 0.0, 1.0, lo_open=True)
    if len(seeds) != 2:
        raise ValueError(f"seeds must hold two seeds (identical sensors, anisotropic pair), got {shown(seeds)}")
    items = sequence(fixed_omegas, "fixed_omegas")
    # the budget by len(fixed_omegas) before any entry is read (fuzz 61a C1: 10**7 weights were read and compared
    # first, refused after 32.8 CPU-s); a repeat, refused below, is counted here as its own weight
    _arch_budget(T, count(runs, "runs"), count(nees_runs, "nees_runs"), len(items),
                 "runs, nees_runs, T and fixed_omegas")
    seen = {general(w_pub): "w_pub"}
    fixed = []   # the floats read (fuzz 29b B1: a checked value is the one used)
    for i, w in enumerate(items):
        w = scalar(w, f"fixed_omegas[{i}]", 0.0, 1.0, lo_open=True)
        # the studies are keyed by the weights as printed (``_counts.general``, as architecture_study keys them: fuzz
        # 67b's note, 0.0018000001 beside w_pub 0.0018 was refused there naming printed_omegas)
        if general(w) in seen:
            raise ValueError(f"fixed_omegas[{i}] repeats {seen[general(w)]} as printed ({shown(w)} prints as "
                             f"{shown(general(w))}): every weight is run once, keyed by its printed value")
        seen[general(w)] = f"fixed_omegas[{i}]"
        fixed.append(w)
    return {IDENTICAL_LABEL: two_sensor.architecture_study(np.random.default_rng(seeds[0]), R1, R2, Q, runs=runs,
                                                           nees_runs=nees_runs, T=T, printed_omegas=(w_pub, *fixed),
                                                           placement_omegas=(w_pub,)),
            ANISO_LABEL: two_sensor.architecture_study(np.random.default_rng(seeds[1]), *ANISO_R, Q, runs=runs,
                                                       nees_runs=nees_runs, T=T, printed_omegas=(w_pub,))}
