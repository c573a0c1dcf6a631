"""Fuzz 24b (chapter 06), classes PR, LB, DR, OR, WN and debatables D1, D3, D4, D5, D7.

PR: a run list is identified by its runs' truths (a run and its unguarded twin share the seed, so the truth):
the chapter's one run-list check (``fusion.book.chapters.chernoff.settings._check_study``) refuses a run given twice
and, for the paired list ``plain``, runs of another seed (truths not those of ``runs``), naming the argument; the
same runs in another order are paired by truth.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest

from test_bad_input_calls_ch06 import _o


def _seed2() -> Any:
    from fusion.book.chapters import chernoff as chc

    return chc.tracking_study(2, 3, _o()["sc"])


# ---- PR: paired run lists of another seed, a run repeated ------------------------------------------------------


def test_pr_plain_of_another_seed_is_refused_by_every_paired_function() -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    plain_b, guarded_b = _seed2()
    calls = {"method_table": lambda p: chc.method_table(o["guarded"], o["crb"], p),
             "guard_usability": lambda p: chc.guard_usability(o["guarded"], p, o["sc"]),
             "consistency_figure": lambda p: chc.consistency_figure(o["guarded"], p, o["sc"])}
    mixed = [o["plain"][0], plain_b[1], o["plain"][2]]
    for name, call in calls.items():
        for bad in (plain_b, mixed):
            with pytest.raises(ValueError, match=r"^plain holds no run with the truth of"):
                call(bad)
    # the guarded list of another seed against this seed's plain: the same rule, whichever list is the other
    with pytest.raises(ValueError, match="^plain holds no run"):
        chc.method_table(guarded_b, o["crb"], o["plain"])


def test_pr_plain_reordered_is_paired_by_truth() -> None:
    """The same runs in another order are the same study: accepted, paired run by run (same results)."""
    import matplotlib.pyplot as plt

    from fusion.book.chapters import chernoff as chc

    o = _o()
    rev = o["plain"][::-1]
    assert chc.method_table(o["guarded"], o["crb"], rev).equals(chc.method_table(o["guarded"], o["crb"], o["plain"]))
    assert chc.guard_usability(o["guarded"], rev, o["sc"]) == chc.guard_usability(o["guarded"], o["plain"], o["sc"])
    plt.close(chc.consistency_figure(o["guarded"], rev, o["sc"]))


@pytest.mark.parametrize("how", ["copies", "one twice"])
def test_pr_a_run_twice_is_refused(how: str) -> None:
    from fusion.book.chapters import chernoff as chc

    o = _o()
    g = o["guarded"]
    runs = [g[0]] * 3 if how == "copies" else [g[0], g[0], g[1]]
    with pytest.raises(ValueError, match=r"^runs\[1\] repeats runs\[0\]"):
        chc.gain_values(runs)
    with pytest.raises(ValueError, match=r"^runs\[1\] repeats runs\[0\]"):
        chc.method_table(runs, o["crb"], o["plain"])
    with pytest.raises(ValueError, match=r"^plain\[1\] repeats plain\[0\]"):
        chc.method_table(g, o["crb"], [o["plain"][0], o["plain"][0], o["plain"][1]])
    # a copy of a run (an equal truth in another object) is the same run
    copy = dataclasses.replace(g[0])
    with pytest.raises(ValueError, match=r"^runs\[1\] repeats runs\[0\]"):
        chc.gain_values([g[0], copy, g[1]])


def test_pr_per_run_values_give_a_repeated_run_twice() -> None:
    """Documented: the per-run functions give one entry per run given, so a run given twice gives its entry twice."""
    from fusion.book.chapters import chernoff as chc

    g = _o()["guarded"]
    v = chc.per_run_mse([g[0], g[0], g[1]], "chernoff_pso")
    assert v[0] == v[1] and v[2] == chc.per_run_mse([g[1]], "chernoff_pso")[0]


# ---- LB: one label for two networks --------------------------------------------------------------------------


@pytest.mark.parametrize("fn", ["baseline_table", "criteria_table", "criteria_values"])
def test_lb_two_networks_with_one_label_are_refused(fn: str) -> None:
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters import chernoff_criteria as ccr
    from fusion.scenarios.fusion_networks import Network

    lab = dict(chc.PREMISE_LABELS)
    nets = _o()["nets"]
    dup = {**lab, Network.NON_GAUSSIAN: lab[Network.UNEQUAL]}
    with pytest.raises(ValueError, match=r"^labels must not repeat a label: labels\[.*unequal.*\] and "
                                         r"labels\[.*non_gaussian.*\]"):
        getattr(ccr, fn)(nets, dup, "small test study")
    with pytest.raises(ValueError, match=r"^labels\[.*chain.*\] is empty"):
        getattr(ccr, fn)(nets, {**lab, Network.CHAIN: ""}, "small test study")


def test_lb_labels_of_networks_not_read_may_repeat() -> None:
    """Only the networks read head columns: labels of other networks (the premise's feedback network) are free."""
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters import chernoff_criteria as ccr
    from fusion.scenarios.fusion_networks import Network

    lab = dict(chc.PREMISE_LABELS)
    assert Network.FEEDBACK not in ccr.CRITERIA_NETWORKS
    table, _ = ccr.baseline_table(_o()["nets"], {**lab, Network.FEEDBACK: lab[Network.UNEQUAL]}, "small test study")
    assert list(table.columns) == [lab[k] for k in ccr.CRITERIA_NETWORKS]
