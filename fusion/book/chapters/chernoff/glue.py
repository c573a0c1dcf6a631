"""The claims ledger and the glue values: the chapter's evidence, the ledger's values and the keys read.

Part of :mod:`fusion.book.chapters.chernoff` (chapter 06, patent CN107330468B), which re-exports its public names."""

from __future__ import annotations

import importlib
import inspect
from functools import lru_cache
from pathlib import Path
from collections.abc import Mapping
from typing import Any

from fusion._shown import shown
from fusion._validation import instance_of

from fusion.book.ledger import Comparison, Evidence, Ledger
from fusion.book.tables import rounded
from fusion.scenarios.fusion_networks import Network
from fusion.scenarios.range_bearing import RangeBearingScenario
from fusion.book.chapters.chernoff.settings import BIBKEY, STUDY_RUNS, _MSE, study_scenario
from fusion.book.chapters.chernoff.importance import _IS_OFFSET
from fusion.book.chapters.chernoff.premise import _PMSE, PREMISE_NETWORKS, _check_scenarios, oracle_exponents
from fusion.book.chapters.chernoff.evidence import _is_region_counts
from fusion.book.chapters.chernoff.compare import _word
from fusion.book.chapters.chernoff.tracking import any_collapsed
from fusion.book.chapters.chernoff.studies import premise_study, tracking_study
from fusion.book.chapters.chernoff.review import double_count_values
from fusion.book.chapters.chernoff.guard import _default_n_initial, guard_usability
from fusion.book.chapters.chernoff.mixture import toy
from fusion.book.glue import GlueValues
from fusion._counts import seed as check_seed
from fusion._validation import count
from fusion._paths import file_text, notebook_markdown

__all__ = ["ledger_values", "chapter_evidence", "claim_values", "SOURCE_CHAPTER", "referenced"]


def _study_args(runs: object, sc: object, scenarios: object, network_runs: object) -> tuple[int, int | None]:
    """The study arguments of :func:`chapter_evidence` and :func:`claim_values`, checked before any study runs
    (fuzz 26b CE: ``sc`` and ``network_runs`` were checked by the studies, after minutes of others, or named
    ``runs``): ``runs`` a count, ``sc`` None or a RangeBearingScenario, ``scenarios`` None or the designed networks,
    and the networks' count (``network_runs``, else ``runs``) at least the 2 a network study takes."""
    runs = count(runs, "runs")
    if sc is not None:
        instance_of(sc, RangeBearingScenario, "sc")
    if scenarios is not None:
        _check_scenarios(scenarios)
    if network_runs is None:
        if runs < 2:
            raise ValueError(f"runs must be at least 2 when network_runs is not given (the networks run runs times; "
                             f"a network study takes 2 or more), got {runs}")
        return runs, None
    return runs, count(network_runs, "network_runs", minimum=2)


def chapter_evidence(seed: int, runs: int = STUDY_RUNS, *, sc: RangeBearingScenario | None = None,
                     scenarios: dict[str, Any] | None = None, network_runs: int | None = None,
                     claims: Any = None) -> dict[str, dict[str, Evidence]]:
    """The evidence of every record of the chapter, reading by reading, from the claim file's settings.

    Parameters
    ----------
    seed, runs : int
        The chapter's root seed and run count.
    sc : RangeBearingScenario, optional
        The tracking scenario (default :func:`study_scenario`; tests pass small ones).
    scenarios : dict, optional
        The designed networks (tests).
    network_runs : int, optional
        Runs per network (2 or more), when not ``runs`` (tests run small tracking studies and 100-run networks);
        without it ``runs`` must be 2 or more.
    claims : fusion.book.claims.ClaimsFile, optional
        The claim file of this chapter's source (:data:`BIBKEY`); default ``book/claims/cn107330468b.yaml``.

    Returns
    -------
    dict
        Record id -> {reading key -> evidence}, for :func:`fusion.book.claims.build_ledger`.

    Raises
    ------
    TypeError
        ``seed``, ``runs`` or ``network_runs`` not an integer, ``sc`` not a RangeBearingScenario, ``scenarios`` not
        a mapping of NetworkScenario, ``claims`` not a ClaimsFile.
    ValueError
        ``seed`` negative, ``runs`` below 1, the networks' run count (``network_runs``, else ``runs``) below 2,
        ``scenarios`` without a network of the chapter, ``claims`` the claim file of another source (its records
        would give no evidence). All checked before any study runs.
    """
    # every study's derived seed (is_replicates' seed + 100 the largest), checked before any study (fuzz 55 D1)
    seed = check_seed(seed, span=_IS_OFFSET)
    runs, network_runs = _study_args(runs, sc, scenarios, network_runs)
    from fusion.book import claims as cl

    if claims is None:
        cf = cl.load(Path(__file__).resolve().parents[4] / "book" / "claims" / f"{BIBKEY}.yaml")
    else:
        instance_of(claims, cl.ClaimsFile, "claims")
        cf = claims
        if cf.source != BIBKEY:
            raise ValueError(f"claims is the claim file of {shown(cf.source)}, not of this chapter's source "
                             f"{shown(BIBKEY)}: its records give this chapter no evidence")
    out: dict[str, dict[str, Evidence]] = {}
    for spec in cf.records:
        if spec.chapter != SOURCE_CHAPTER:
            continue
        mod, name = spec.evidence.split(":")
        fn = getattr(importlib.import_module(mod), name)
        params = inspect.signature(fn).parameters
        extra = {k: v for k, v in (("sc", sc), ("scenarios", scenarios)) if k in params}
        n = runs if "scenarios" not in params or network_runs is None else network_runs
        keyed = {r.key: r.settings for r in spec.readings}
        keyed.setdefault("primary", {})
        out[spec.id] = {k: fn(dict(v), seed=seed, runs=n, **extra) for k, v in keyed.items()}
    return out


def claim_values(seed: int, runs: int = STUDY_RUNS, *, sc: RangeBearingScenario | None = None,
                 scenarios: dict[str, Any] | None = None, network_runs: int | None = None) -> GlueValues:
    """The computed values the claim file's texts name (``{name}`` fields), the same as the chapter's glue.

    Parameters
    ----------
    seed, runs : int
    sc : RangeBearingScenario, optional
    scenarios : dict, optional
    network_runs : int, optional
        As in :func:`chapter_evidence` (checked, with the others, before any study runs).

    Returns
    -------
    dict
        ``chf_runs``, ``chf_n_any_collapsed``, ``chf_r_toy``, ``chf_design_n0``, the linearised analysis
        (:func:`double_count_values`), the collapse thresholds (:func:`guard_usability`) and the networks' run counts
        (``chf_pr_runs``, ``chf_pr_non_gaussian_runs``).

    Raises
    ------
    TypeError, ValueError
        The arguments as :func:`chapter_evidence` refuses them.
    """
    # premise_study's seed + 10 + j, checked before the tracking study runs (fuzz 55 D1)
    seed = check_seed(seed, span=10 + len(PREMISE_NETWORKS) - 1)
    runs, network_runs = _study_args(runs, sc, scenarios, network_runs)
    sc_ = study_scenario() if sc is None else sc
    plain, rs = tracking_study(seed, runs, sc)
    nets = premise_study(seed, runs if network_runs is None else network_runs, scenarios)
    u = guard_usability(rs, plain, sc_)
    t = toy(seed)
    return ({"chf_runs": len(rs), "chf_r": sc_.n_samples, "chf_w_exact": t.w_exact,
             "chf_w_exact_off": abs(t.w_exact - 0.5), "chf_n_any_collapsed": int(any_collapsed(plain, sc_).sum()),
             "chf_r_toy": t.r, "chf_design_n0": _default_n_initial(sc_),
             "chf_pr_runs": nets[Network.UNEQUAL].runs, "chf_pr_non_gaussian_runs": nets[Network.NON_GAUSSIAN].runs,
             "chf_pr_relay_runs": nets[Network.RELAY].runs}
            | {f"chf_pr_{k}_oracle_eps": ", ".join(f"{x:.2f}" for x in oracle_exponents(nets[k])[0])
               for k in (Network.UNEQUAL, Network.OVERCONFIDENT)}
            | _is_region_counts(rs) | double_count_values(rs, sc_)
            | {k: v for k, v in u.items() if k.startswith("chf_gu_thr")})


#: Docname of the chapter.
SOURCE_CHAPTER = "notebooks/06_chernoff_fusion"


@lru_cache(maxsize=1)
def _referenced_keys() -> frozenset[str]:
    """Glue keys of the chapter that something reads: its markdown, the book's pages, the claim file's texts."""
    import re

    root = Path(__file__).resolve().parents[4]
    text = "".join(notebook_markdown(root / f"{SOURCE_CHAPTER}.ipynb", f"the chapter's {SOURCE_CHAPTER}.ipynb"))
    keys = set(re.findall(r"\{glue(?::\w+)?\}`([A-Za-z0-9_-]+)", text))
    pages = "".join(file_text(p, f"the book's {p.name}") for p in sorted((root / "book").glob("*.md")))
    appendix = root / f"{SOURCE_CHAPTER}_appendix.ipynb"  # the chapter's appendix reads its values across documents
    if appendix.is_file():
        pages += "".join(notebook_markdown(appendix, f"the chapter's {appendix.name}"))
    keys |= set(re.findall(r"06_chernoff_fusion\.ipynb::([A-Za-z0-9_-]+)", pages))
    keys |= set(re.findall(r"\{(chf_[A-Za-z0-9_]+)", file_text(root / "book" / "claims" / f"{BIBKEY}.yaml", "the chapter's claim file")))
    return frozenset(keys)


def referenced(values: GlueValues) -> GlueValues:
    """The glue values that something reads (``_referenced_keys``): the chapter glues no value nobody uses.

    Parameters
    ----------
    values : dict
        Glue key -> value.

    Returns
    -------
    dict
        The subset whose keys appear in a ``{glue}`` role of the chapter's markdown, in a ``{glue}`` role of a page of
        ``book/`` or of the chapter's appendix naming this notebook, or as a ``{name}`` field of the claim file.

    Raises
    ------
    TypeError
        ``values`` not a mapping.
    """
    instance_of(values, Mapping, "values")
    keys = _referenced_keys()
    return {k: v for k, v in values.items() if k in keys}


def ledger_values(led: Ledger) -> GlueValues:
    """Glue values of the ledger's records, as the rulebook judged them.

    Parameters
    ----------
    led : Ledger
        The chapter's ledger (:func:`fusion.book.claims.build_ledger` on :func:`chapter_evidence`).

    Returns
    -------
    dict
        For every record ``<id>`` (dashes as underscores) ``<id>_record_status`` (its status by the rulebook); for
        each whose evidence is a comparison: ``<id>_d`` (the deciding
        statistic of A − B: the mean paired difference, or the median for heavy-tailed differences), ``<id>_lo`` and
        ``<id>_hi`` (its 95 % interval; 4 decimals), ``<id>_status`` (the rulebook's status of that reading),
        ``<id>_runs`` (int) and ``<id>_margin`` (the practical margin, 4 decimals); for squared-error comparisons
        ``<id>_word`` (``_word``); the same keys ``<id>_alt<j>_*`` for its ``j``-th other reading (0-based, the
        claim file's order); ``<id>_alt_n`` and ``<id>_alt_holds`` (int) for a record with readings: the readings that
        count towards robustness (open choices with enough runs, R4-R5) and those of them under which the claim is
        reproduced; ``chf_source_n``, ``chf_implied_n``, ``chf_book_n`` (int: records by claimant, R8),
        ``chf_contradicted_n`` (int, records contradicted), ``chf_implied_contradicted`` (int, the book's readings
        of the patent's purpose that are contradicted), ``chf_source_contradicted`` (int, claims the patent prints
        that are contradicted), ``chf_source_unchecked`` (int, claims the patent prints that cannot be checked) and
        ``<id>_alt_nd`` (int, counted readings that are not distinguishable).

    Raises
    ------
    TypeError
        ``led`` not a Ledger.
    ValueError
        ``led`` the ledger of another source than the chapter's (:data:`BIBKEY`): its glue keys would be this
        chapter's.
    """
    instance_of(led, Ledger, "led")
    if led.source != BIBKEY:
        raise ValueError(f"led is the ledger of {shown(led.source)}, not of this chapter's source {shown(BIBKEY)}")
    v: dict[str, Any] = {}

    def put(prefix: str, ev: Any) -> None:
        if isinstance(ev, Comparison):
            d, lo, hi = ev.interval()
            v.update({f"{prefix}_d": rounded(d), f"{prefix}_lo": rounded(lo), f"{prefix}_hi": rounded(hi),
                      f"{prefix}_status": ev.status(), f"{prefix}_runs": ev.runs, f"{prefix}_margin": rounded(ev.margin)})
            if ev.metric.startswith(_MSE.split(" from ")[0]) or ev.metric == _PMSE:  # squared error: lower is better
                v[f"{prefix}_word"] = _word(ev)
    good = ("reproduced", "reproduced under stated assumptions")
    for c in led.claims:
        p = c.id.replace("-", "_")
        v[f"{p}_record_status"] = c.status
        put(p, c.evidence)
        for j, a in enumerate(c.alternatives):
            put(f"{p}_alt{j}", a.evidence)
        if c.alternatives:
            counted = [a for a in c.alternatives if a.counted(c.runs)[0]]
            v[f"{p}_alt_n"] = len(counted)
            v[f"{p}_alt_holds"] = sum(a.evidence.status() in good for a in counted)
            v[f"{p}_alt_nd"] = sum(a.evidence.status() == "not distinguishable" for a in counted)
    for who in ("source", "implied", "book"):
        v[f"chf_{who}_n"] = sum(c.claimant == who for c in led.claims)
    v["chf_contradicted_n"] = sum(c.status == "contradicted" for c in led.claims)
    v["chf_implied_contradicted"] = sum(c.status == "contradicted" and c.claimant == "implied" for c in led.claims)
    v["chf_source_contradicted"] = sum(c.status == "contradicted" and c.claimant == "source" for c in led.claims)
    v["chf_source_unchecked"] = sum(c.status == "cannot be checked" and c.claimant == "source" for c in led.claims)
    return v
