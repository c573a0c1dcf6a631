"""Fuzz 42b (book layer): work budgets that count what a function loops over, at its entry, before any work (rule 17):
``table_james_stein``'s cells, counted by their measured cost before any ratio is checked (C1, C2);
``stability.tasks``' records and readings as iterating them yields them (C3, D3); ``check_grid``'s cells (C4);
``premise_study``'s networks, all at entry (C5); the loops of ``nested_values`` (C7), ``spread_check`` (C8),
``swarm_study`` and ``within_se_counts`` (C9), ``scaling_study`` (C10), ``chosen_bias_study`` and ``snis_bias_study``
(C11); the printing formatters name the float range, not rule 2's bound, for a value beyond it (D4)."""

from __future__ import annotations

import collections.abc as cabc
import time

import numpy as np
import pytest

from fusion._limits import MAX_WORK


def _refused_fast(f, match, limit=3.0):
    # a refusal before the work: the cases' own conversion costs up to 0.6 CPU-s on a quiet machine, and a loaded
    # CI doubled a 1-s bound's reading; the work refused would take 30 CPU-s and more
    t0 = time.process_time()
    with pytest.raises(ValueError, match=match):
        f()
    assert time.process_time() - t0 < limit


# --- C3, D3 ---------------------------------------------------------------------------------------------------------

class _Lying(cabc.Mapping):
    """A mapping whose ``__len__`` says 1 whatever it holds."""

    def __init__(self, d):
        self.d = d

    def __getitem__(self, k):
        return self.d[k]

    def __iter__(self):
        return iter(self.d)

    def __len__(self):
        return 1


def test_tasks_counts_the_readings_it_reads_not_their_len():
    """C3: a record whose Mapping says it holds 1 reading and holds 400,001 was counted 11,000 units, then 2,000,005
    tasks were built (36 CPU-s). The readings are counted by iterating them: refused at once naming readings."""
    from fusion.book import stability as S

    inner = {f"r{i}": ("primary", 100) for i in range(400_001)}
    _refused_fast(lambda: S.tasks({("src", "rec"): _Lying(inner)}, [1, 2, 3, 4, 5], 1),
                  r"^readings and seed_list \(at least [\d,]+ readings")
    outer = _Lying({("s", f"r{i}"): {"primary": ("primary", 100)} for i in range(400_000)})
    _refused_fast(lambda: S.tasks(outer, [1], 1),
                  r"^readings and seed_list \(at least [\d,]+ readings, .* in 400,000 records")
    # within the budget, a lying len() changes nothing: every reading is read and becomes a task
    small = {f"r{i}": ("primary", 100) for i in range(1000)}
    assert len(S.tasks({("src", "rec"): _Lying(small)}, [1], 1)) == 1000


def test_tasks_counts_records_without_readings():
    """D3: 5e6 records without readings were counted 0 units and checked for 6.4 CPU-s (0.95 us a record measured:
    100 units each). 10**7 records are the budget's edge; one more is refused by counting the keys alone."""
    from fusion._limits import work
    from fusion.book import stability as S

    assert work((10**7 * S.RECORD_WORK,), "readings") == MAX_WORK
    keys = [("s", f"r{i}") for i in range(10**7 + 1)]

    class Keys(cabc.Mapping):  # 10**7 + 1 records, each empty, without a dict of them
        def __getitem__(self, k):
            return {}

        def __iter__(self):
            return iter(keys)

        def __len__(self):
            return len(keys)

    _refused_fast(lambda: S.tasks(Keys(), [1], 1), r"^readings and seed_list \(0 readings.*at least 10,000,001 records")
    assert S.tasks({("s", "r"): {}}, [1], 1) == []


def test_tasks_refuses_readings_that_grow_while_read():
    """A mapping that yields more readings when checked than when counted is refused, not read past the count."""
    from fusion.book import stability as S

    class Growing(cabc.Mapping):
        def __init__(self):
            self.passes = 0

        def __getitem__(self, k):
            return {"primary": ("primary", 100)}

        def __iter__(self):
            self.passes += 1
            return iter([("s", f"r{i}") for i in range(3 if self.passes == 1 else 5)])

        def __len__(self):
            return 3

    with pytest.raises(ValueError, match="^readings yielded more than the 3 records counted"):
        S.tasks(Growing(), [1], 1)


class _Ran(Exception):
    """The call passed its entry checks and reached its work."""


def _ran(*args, **kwargs):
    raise _Ran


# --- C1, C2 ---------------------------------------------------------------------------------------------------------

def test_table_james_stein_weighs_a_cell_and_counts_the_ratios_first(monkeypatch):
    """C1: 530,000 ratios at d = 3 (counted 1.8e3 units a cell, measured about 86 us) ran 42.9 CPU-s; C2: 5e6 ratios
    were checked one by one for 12 CPU-s before the refusal. A cell weighs 9,000 units and the cells are counted
    before any ratio is checked: 100,000 ratios (7.6 CPU-s measured) are accepted, 110,000 refused, 5e6 at once."""
    from fusion.book.chapters.lecture_correlated import appendix as A

    _refused_fast(lambda: A.table_james_stein(ds=(3,), ratios=np.zeros(5_000_000), runs=100),
                  r"^ds, ratios and runs \(1 dimensions summing to 3 x 5,000,000 ratios")
    _refused_fast(lambda: A.table_james_stein(ds=(3,), ratios=[0.0] * 530_000, runs=100), r"^ds, ratios and runs")
    _refused_fast(lambda: A.table_james_stein(ds=(3,), ratios=[0.0] * 110_000, runs=100), r"^ds, ratios and runs")
    monkeypatch.setattr(A.np.random, "default_rng", _ran)
    with pytest.raises(_Ran):
        A.table_james_stein(ds=(3,), ratios=[0.0] * 100_000, runs=100)
    with pytest.raises(_Ran):  # the chapter's table
        A.table_james_stein()


# --- C4 -------------------------------------------------------------------------------------------------------------

def test_check_grid_weighs_a_cell(monkeypatch):
    """C4: 400 x 250 cells of 2 runs x 2 samples x 3 sensors were counted 6e7 units (6 % of the budget) and ran 36 CPU-s
    (347 us a cell measured, whatever its readings). A cell weighs 40,000 units, counted before any entry is
    checked: 24,000 such cells (12 CPU-s measured) are accepted, 100,000 and 10**6 factors refused at once."""
    from fusion.book.chapters.lecture_weighting.consistency import check_grid

    kw = dict(runs=2, samples=2, window=(0, 1), sigma=(0.5, 1.0, 1.5))
    names = r"^biases, eps_factors, runs, samples and sigma ask for"
    _refused_fast(lambda: check_grid(eps_factors=np.linspace(0.5, 2, 400), biases=np.linspace(5, 50, 250), **kw), names)
    _refused_fast(lambda: check_grid(eps_factors=np.linspace(0.5, 2, 10**6), biases=(5.0,), **kw), names)
    monkeypatch.setattr(np.random, "default_rng", _ran)
    with pytest.raises(_Ran):
        check_grid(eps_factors=np.linspace(0.5, 2, 200), biases=np.linspace(5, 50, 120), **kw)
    with pytest.raises(_Ran):  # the chapter's grid
        check_grid()


# --- C5 -------------------------------------------------------------------------------------------------------------

def test_premise_study_counts_every_network_at_entry(monkeypatch):
    """C5: premise_study(777, 1000) ran the first networks for 11 CPU-s, then the feedback network's own budget refused
    it (1.49e9 units). Every network is counted at entry, against the entry of STUDY_WORK for the reseeding sweep's 10x
    primaries (1,000 runs a network: 4.5e9 units, 56 CPU-s measured with the budget lifted): 1,000 runs reach the first
    draw; 2,100 runs, or a last network beyond the budget, are refused before the first network runs."""
    import dataclasses

    from fusion._limits import PREMISE_STUDY, STUDY_WORK
    from fusion.book.chapters.chernoff import premise as P
    from fusion.book.chapters.chernoff.studies import premise_study
    from fusion.scenarios import fusion_networks as fn

    scs = dict(fn.premise_scenarios() | fn.redundancy_scenarios())
    assert 2 * P._premise_work(scs, 1000) <= STUDY_WORK[PREMISE_STUDY] < 2 * P._premise_work(scs, 1000) + MAX_WORK
    monkeypatch.setattr(np.random, "default_rng", _ran)
    _refused_fast(lambda: premise_study(4321, 2100), r"^runs and scenarios \(6 networks of 2,100 runs")
    big = dataclasses.replace(scs[P.Network.OVERCONFIDENT], n_particles=200_000)  # the last network run
    _refused_fast(lambda: premise_study(4321, 100, scs | {P.Network.OVERCONFIDENT: big}), r"^runs and scenarios")
    _refused_fast(lambda: P.premise_studies(4321, 100, scs | {P.Network.OVERCONFIDENT: big}), r"^runs and scenarios")
    with pytest.raises(_Ran):  # the sweep's 10x
        premise_study(4321, 1000)


# --- C7 -------------------------------------------------------------------------------------------------------------

def test_nested_values_counts_its_ratios(monkeypatch):
    """C7: 25,000 ratios ran 32.5 CPU-s (a 2-D Chernoff weight search each, 2.2-2.9 ms measured); nothing counted them.
    A ratio weighs 250,000 units, counted before any entry is checked: 4,000 are accepted, 4,001 refused at once."""
    from fusion.book.chapters.chernoff import premise as P

    _refused_fast(lambda: P.nested_values(tuple(np.linspace(2, 100, 25_000))), r"^ks ask for")
    _refused_fast(lambda: P.nested_values(tuple(np.linspace(2, 100, 4_001))), r"^ks ask for")
    monkeypatch.setattr(P.ch, "gaussian_chernoff_weights", _ran)
    with pytest.raises(_Ran):
        P.nested_values(tuple(np.linspace(2, 100, 4_000)))
    with pytest.raises(_Ran):  # the chapter's
        P.nested_values()


# --- C8 -------------------------------------------------------------------------------------------------------------

def test_spread_check_counts_every_half_width(monkeypatch):
    """C8: 5 half-widths at 3.7e6 draws ran 46 CPU-s: each learned_limit_check passed its own budget (9.8e8 units, 10.4
    CPU-s), the loop over them was not counted. Every half-width's check is counted before any entry is checked
    (5 x 750,000 draws, 9.9e8 units, ran 6.7 CPU-s; 5 x 3.7e6 refused at once)."""
    from fusion.book.chapters.lecture_weighting import learning as LW
    from fusion.scenarios.lecture_weighting import learning as SL

    _refused_fast(lambda: LW.spread_check(log_ranges=(1.0, 2.0, 3.0, 4.0, 5.0), draws=3_700_000),
                  r"^log_ranges and draws ask for")
    _refused_fast(lambda: LW.spread_check(log_ranges=np.ones(10**6), draws=20), r"^log_ranges and draws ask for")
    monkeypatch.setattr(SL.np.random, "default_rng", _ran)
    with pytest.raises(_Ran):
        LW.spread_check(log_ranges=(1.0, 2.0, 3.0, 4.0, 5.0), draws=750_000)
    with pytest.raises(_Ran):  # the chapter's
        LW.spread_check()


# --- C9 -------------------------------------------------------------------------------------------------------------

def test_swarm_studies_count_every_n_and_variant_at_entry(monkeypatch):
    """C9: swarm_study(1, (2,), 4500, 1000) ran 35.7 CPU-s (only memory was counted); (2, 3, 40) at 3,000 runs ran n = 2
    and 3, then the n = 40 swarm refused naming swarm_options; within_se_counts ran n = 2 then refused naming r;
    swarm_within_se named swarm_options. Every N and variant is counted at entry (a problem weighs its measured cost),
    with the swarm's and SLSQP's own budgets of the largest N, naming the caller's arguments; 1,000 runs of n = 2 (the
    edge, 8.0 CPU-s measured) and the book's calls are accepted."""
    from fusion.book.chapters import chernoff_scaling as cs

    _refused_fast(lambda: cs.swarm_study(1, ns=(2,), runs=4500, r=1000), r"^ns, runs and r ask for")
    _refused_fast(lambda: cs.swarm_study(1, ns=(2, 3, 40), runs=3000, r=100), r"^ns, runs and r ask for")
    _refused_fast(lambda: cs.within_se_counts(1, ns=(2, 40), runs=3000), r"^runs, the 1,000 importance samples and ns")
    _refused_fast(lambda: cs.within_se_counts(1, ns=(2, 40), runs=600), r"^ns and runs ask for")
    _refused_fast(lambda: cs.swarm_within_se(1, 40, 3000, 100), r"^n, runs and r ask for")
    _refused_fast(lambda: cs.swarm_within_se(1, 2, 5000, 2), r"^n, runs and r ask for")  # the swarm's own loop
    _refused_fast(lambda: cs.swarm_within_se(1, 395, 2, 2), r"^n, runs and r ask for")  # SLSQP's own budget
    monkeypatch.setattr(cs.np.random, "default_rng", _ran)
    for call in (lambda: cs.swarm_study(1, ns=(2,), runs=1000, r=1000), lambda: cs.swarm_study(1),
                 lambda: cs.within_se_counts(1), lambda: cs.swarm_within_se(1, 10, 1000)):
        with pytest.raises(_Ran):
            call()


# --- C10 ------------------------------------------------------------------------------------------------------------

def test_scaling_study_has_a_work_budget(monkeypatch):
    """C10: 4,000 sample sizes of 2 runs ran 54.9 CPU-s, 20,000 runs of 2 sizes 27.3 (only memory was counted). The
    runs' exact exponents and each size's batch are weighed by their measured costs: both refused at once, 8,800 runs
    of 2 sizes (about 11 CPU-s) and the book's study accepted."""
    from fusion.book.chapters import chernoff_scaling as cs

    _refused_fast(lambda: cs.scaling_study(1, rs=tuple(range(2, 40000, 10)), runs=2), r"^rs, n and runs ask for")
    _refused_fast(lambda: cs.scaling_study(1, rs=(2, 3), runs=20000), r"^rs, n and runs ask for")
    _refused_fast(lambda: cs.scaling_study(1, rs=(2, 3), runs=9000), r"^rs, n and runs ask for")
    monkeypatch.setattr(cs.np.random, "default_rng", _ran)
    for call in (lambda: cs.scaling_study(1, rs=(2, 3), runs=8800), lambda: cs.scaling_study(1)):
        with pytest.raises(_Ran):
            call()


# --- C11 ------------------------------------------------------------------------------------------------------------

def _divisors(total, top):
    return tuple(r for r in range(2, top + 1) if total % r == 0)


@pytest.mark.parametrize("study, bad, edge", [
    # 54 sizes of a 2e6 pool ran 58.8 CPU-s; a size costs a 60-step bisection over the pool (60 units a sample)
    ("chosen_bias_study", dict(rs=_divisors(2_000_000, 1_000_000), total=2_000_000),
     dict(rs=(2, 4, 5, 8), total=1_400_000)),
    # 47 sizes of a 1e6 pool ran 2.4 CPU-s: lighter, but the pool size itself was not counted (1e7 x 62 sizes)
    ("snis_bias_study", dict(rs=_divisors(10_000_000, 5_000_000), total=10_000_000), dict(rs=(2, 4), total=9_000_000)),
])
def test_block_studies_count_the_pool_and_its_sizes(monkeypatch, study, bad, edge):
    """C11: the pool studies had no work budget on total x len(rs) (only divisibility and the count ceiling). The pool's
    samples and a pass over them per size are counted before the draw: the fuzz's requests are refused at once, a pool
    within the budget and the book's studies accepted."""
    from fusion.book.chapters import chernoff_snis as S

    _refused_fast(lambda: getattr(S, study)(np.random.default_rng(1), **bad), r"^rs and total ask for")
    monkeypatch.setattr(S.mx, "gm_sample", _ran)
    for kw in (edge, {}):
        with pytest.raises(_Ran):
            getattr(S, study)(np.random.default_rng(1), **kw)


# --- D4 -------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("value", ["decimal", "fraction", "longdouble"])
def test_printing_formatters_name_the_float_range(value):
    """D4: sci, fmt, rounded and roundoff refused a value beyond the float range stating rule 2's bound ("at most
    1e+150"), which these formatters do not apply (sci(1e300) prints). They name the float range; scalar keeps rule 2."""
    from decimal import Decimal
    from fractions import Fraction

    from fusion._validation import scalar
    from fusion.book.chapters.lecture import sci as lecture_sci
    from fusion.book.ledger import fmt
    from fusion.book.tables import rounded, roundoff, sci

    x = {"decimal": Decimal("1e400"), "fraction": Fraction(10**400, 3), "longdouble": np.longdouble("1e4000")}[value]
    if value == "longdouble" and np.isinf(x):
        pytest.skip("longdouble is float64 on this platform")
    for f, name in ((sci, "x"), (fmt, "x"), (rounded, "value"), (roundoff, "value"), (lecture_sci, "value")):
        with pytest.raises(ValueError, match=rf"^{name} must be a number of magnitude within the float range \(at most "
                                             r"1\.8e\+308\), got one beyond it$"):
            f(x)
    assert sci(1e300) == "10³⁰⁰"  # printed, no rule-2 bound
    with pytest.raises(ValueError, match=r"^x must be a number of magnitude at most 1e\+150"):
        scalar(x, "x")
