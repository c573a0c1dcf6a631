"""Fuzz 24b (chapter 06), classes PR, LB, DR, OR, WN and debatables D1, D3, D4, D5, D7.

PR: a run list is identified by its runs' truths (a run and its unguarded twin share the seed, so the truth):
the chapter's one run-list check (``fusion.book.chapters.chernoff.settings._check_study``) refuses a run given twice
and, for the paired list ``plain``, runs of another seed (truths not those of ``runs``), naming the argument; the
same runs in another order are paired by truth. LB: the labels that head the criteria tables' columns are distinct
and non-empty. DR: result tables are read by key (``fusion._results.table(key=, index=)``): a repeated row, a
missing row that is read, or rows of other exponents are refused by the result's check, and any row order gives the
same glue. OR: ``scaling_study`` sorts its sizes; ``snis_bias_study`` refuses ``far_omega`` at ω*. WN: a study that does
not fit its key's network (several exchanges under an oracle network's key, several frames under a criteria
network's) is refused naming ``studies[key]``, not the inner function's argument. Debatables: D1 and D3 documented (the rulebook's
relative tie rule; glue keyed by position), D4 fixed in part (NetworkStudy's KL non-negative, exponents in [0, 1]),
D5 documented in ``fusion._results`` (relations are structural; derived fields are not recomputed), D7 fixed.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

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


# ---- DR: result tables read by key; OR: sizes in order, far_omega not ω* ---------------------------------------


def _snis() -> Any:
    from fusion.book.chapters import chernoff_steps as cst

    return cst.snis_bias_study(np.random.default_rng(0), (5, 10), 2000)


def _chosen() -> Any:
    from fusion.book.chapters import chernoff_steps as cst

    return cst.chosen_bias_study(np.random.default_rng(0), (5, 10, 20), 2000)


_SNIS, _CHOSEN = [], []


def _cached(store: list, make: Any) -> Any:
    if not store:
        store.append(make())
    return store[0]


@settings(max_examples=15, deadline=None)
@given(st.data())
def test_dr_rows_in_any_order_give_the_same_glue(data: st.DataObject) -> None:
    """The glue reads rows by key: any permutation of the rows gives the same values (it read them by position)."""
    for s in (_cached(_SNIS, _snis), _cached(_CHOSEN, _chosen)):
        order = data.draw(st.permutations(range(len(s.table))))
        assert dataclasses.replace(s, table=s.table.iloc[list(order)]).glue() == s.glue()


@settings(max_examples=15, deadline=None)
@given(st.data())
def test_dr_a_repeated_row_is_refused(data: st.DataObject) -> None:
    import pandas as pd

    for s in (_cached(_SNIS, _snis), _cached(_CHOSEN, _chosen)):
        i = data.draw(st.integers(0, len(s.table) - 1))
        with pytest.raises(ValueError, match=rf"^{type(s).__name__}\.table repeats a row"):
            dataclasses.replace(s, table=pd.concat([s.table, s.table.iloc[[i]]]))


def test_dr_rows_of_other_exponents_or_sizes_are_refused() -> None:
    s = _cached(_SNIS, _snis)
    star = s.table["ω"].iloc[0]
    with pytest.raises(ValueError, match=r"^SnisBiasStudy\.table repeats a row"):  # the fuzz's case: every ω 0.3
        dataclasses.replace(s, table=s.table.assign(**{"ω": 0.3}))
    for bad in (s.table.assign(**{"ω": s.table["ω"].where(s.table["ω"] != star, 0.3)}),
                s.table.assign(**{"ω": -s.table["ω"]}), s.table[s.table["ω"] != star]):
        with pytest.raises(ValueError, match=r"^SnisBiasStudy\.table( must hold the rows of the exponents|\['ω'\] must hold)"):
            dataclasses.replace(s, table=bad)
    t = s.table.copy()
    t.loc[t.index[-1], "R"] = 20
    with pytest.raises(ValueError, match=r"^SnisBiasStudy\.table must hold every exponent at the same sizes R"):
        dataclasses.replace(s, table=t)
    with pytest.raises(ValueError, match=r"^ChosenBiasStudy\.table: the columns \['R'\] identify a row"):
        dataclasses.replace(_cached(_CHOSEN, _chosen), table=_cached(_CHOSEN, _chosen).table.assign(R=np.nan))


def test_dr_sigma_study_refuses_a_problem_twice() -> None:
    import pandas as pd

    from fusion.book.chapters import chernoff_first_order as cfo

    s = cfo.sigma_first_order_study(np.random.default_rng(0), 2)
    with pytest.raises(ValueError, match=r"^SigmaFirstOrderStudy\.runs repeats a row"):
        dataclasses.replace(s, runs=pd.concat([s.runs, s.runs.iloc[[0]]]))
    assert dataclasses.replace(s, runs=s.runs.iloc[::-1]).table().equals(s.table())


def test_dr_is_variance_table_rows_read_by_index() -> None:
    import pandas as pd

    from fusion.book.chapters import chernoff as chc

    s = chc.is_variance_study(np.random.default_rng(0), 20, 50)
    t = s.table
    with pytest.raises(ValueError, match=r"^IsVarianceStudy\.table must hold the rows .* misses \[0\.8\]"):
        dataclasses.replace(s, table=t.drop(index=0.8))
    with pytest.raises(ValueError, match=r"^IsVarianceStudy\.table repeats a row: the index label 0\.0"):
        dataclasses.replace(s, table=pd.concat([t.iloc[:1], t]))
    assert dataclasses.replace(s, table=t.iloc[::-1]).glue() == s.glue()


def test_or_scaling_study_sizes_in_any_order() -> None:
    from fusion.book.chapters import chernoff_scaling as csc

    a, b = csc.scaling_study(1, (40, 20), 2, 2), csc.scaling_study(1, (20, 40), 2, 2)
    assert a.rs == (20, 40) and a.glue() == b.glue()
    assert a.glue()["chf_scale_r_lo"] == 20
    with pytest.raises(ValueError, match=r"^ScalingStudy\.rs must be increasing"):
        dataclasses.replace(a, rs=(40, 20))


def test_or_far_omega_at_omega_star_is_refused() -> None:
    from fusion.book.chapters import chernoff_steps as cst

    star = float(cst.toy_reference().omega_star)
    for w in (star, round(star, 4), star + 4e-5):
        with pytest.raises(ValueError, match=r"^far_omega must differ from the exact ω\*"):
            cst.snis_bias_study(np.random.default_rng(0), (5, 10), 2000, w)
    cst.snis_bias_study(np.random.default_rng(0), (5, 10), 2000, star + 1e-3)  # another exponent: valid


# ---- WN: networks under each other's key -----------------------------------------------------------------------


@pytest.mark.parametrize("fn", ["premise_values", "premise_table", "criteria_values", "baseline_table"])
def test_wn_studies_under_each_others_key_name_studies(fn: str) -> None:
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters import chernoff_criteria as ccr
    from fusion.scenarios.fusion_networks import Network

    nets = _o()["nets"]
    swapped = {**nets, Network.UNEQUAL: nets[Network.FEEDBACK], Network.FEEDBACK: nets[Network.UNEQUAL]}
    args = (swapped, dict(chc.PREMISE_LABELS)) if fn in ("criteria_values", "baseline_table") else (swapped,)
    with pytest.raises(ValueError, match=r"^studies\[.*'unequal'.*\] must be a network with one exchange .* got the "
                                         r"study of 'feedback over three frames'"):
        getattr(ccr if len(args) == 2 else chc, fn)(*args, "small test study")
    if len(args) == 2:  # a multi-frame study under the chain's key (not an oracle network): named by its key
        with pytest.raises(ValueError, match=r"^studies\[.*'chain'.*\] must be of a network with one frame"):
            ccr.baseline_table({**nets, Network.CHAIN: nets[Network.FEEDBACK]}, dict(chc.PREMISE_LABELS), "r")


def test_wn_one_exchange_study_under_another_key_stays_valid() -> None:
    """The keys are the caller's: a one-exchange study under another one-exchange network's key is accepted (the
    criteria tests run one study under several keys)."""
    from fusion.book.chapters import chernoff as chc
    from fusion.book.chapters import chernoff_criteria as ccr
    from fusion.scenarios.fusion_networks import Network

    nets = _o()["nets"]
    ccr.baseline_table({**nets, Network.NON_GAUSSIAN: nets[Network.UNEQUAL]}, dict(chc.PREMISE_LABELS), "r")


# ---- debatables --------------------------------------------------------------------------------------------------


def test_d7_premise_mixture_scaled_too_few_runs_names_its_arguments() -> None:
    """D7 (decided: fixed): the comparison takes no reason, so fewer than MIN_RUNS runs are refused up front, naming
    runs and factor (the rulebook's message asked for a ``reason`` the function does not have)."""
    from fusion.book.chapters import chernoff as chc

    with pytest.raises(ValueError, match=r"^runs \* factor must be at least 100") as info:
        chc.premise_mixture_scaled(3, 2, 1)
    assert "reason (" not in str(info.value)


def test_d1_paired_numbers_offset_far_beyond_the_differences_is_a_tie() -> None:
    """D1 (decided: documented): the rulebook's one relative tie rule makes the deciding statistic a tie at an offset
    of 1e12 against differences of 0.3, while the median and the share won are of the raw differences."""
    from fusion.book.chapters import chernoff_steps as cst

    a = np.array([1.0, 2.0, 1.5, 0.5, 1.2])
    v = cst.paired_numbers(a + 1e12, a + 0.3 + 1e12, "chf_x", 4)
    assert v["chf_x_d"] == v["chf_x_lo"] == v["chf_x_hi"] == 0.0
    assert v["chf_x_med"] == pytest.approx(-0.3, abs=1e-3) and v["chf_x_won"] == 1.0
    w = cst.paired_numbers(a, a + 0.3, "chf_x", 4)  # without the offset: the difference
    assert w["chf_x_d"] == pytest.approx(-0.3) and w["chf_x_hi"] < 0
    assert "1e12" in cst.paired_numbers.__doc__


def test_d3_repeated_thresholds_and_tolerances_repeat_their_values() -> None:
    """D3 (decided: documented): the glue is keyed by position, so a repeat gives the same values twice; a
    tolerance of 1 or more stops the swarm at once, as 1 does."""
    from fusion.book.chapters import chernoff as chc

    o = _o()
    g = chc.guard_usability(o["guarded"], o["plain"], o["sc"], (0.01, 0.01))
    assert all(g[f"chf_gu_thr0{s}"] == g[f"chf_gu_thr1{s}"] for s in ("", "_runs", "_updates"))
    v = chc.stopping_values(o["guarded"], o["sc"], (1.0, 10.0))
    assert all(v[f"chf_stop_{k}_0"] == v[f"chf_stop_{k}_1"] for k in ("atlimit", "evals", "gap"))


@pytest.mark.parametrize("field,bad", [("kl_local", -1.0), ("eps", -0.33), ("eps", 1.5)])
def test_d4_network_study_keeps_its_ranges(field: str, bad: float) -> None:
    """D4 (decided: fixed in part): a KL divergence is non-negative and an exponent in [0, 1] (the sum over a node's
    row is not checked: tests build studies with placeholder exponents)."""
    st = next(iter(_o()["nets"].values()))
    arr = np.array(getattr(st, field))
    arr.flat[0] = bad
    with pytest.raises(ValueError, match=rf"^NetworkStudy\.{field} must lie in \[0"):
        dataclasses.replace(st, **{field: arr})
