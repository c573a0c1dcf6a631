"""Chapter 01 (the optimal fusion set): the source's Tables 1-3 recomputed and audited.

With the numbers the prose quotes from them.
"""

from __future__ import annotations

from dataclasses import dataclass
from fusion.book.study_cache import study_cache

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion import data
from fusion import readings as rd
from fusion._counts import sequence
from fusion._limits import work
from fusion._results import ResultSpec, array, table, validated_post_init
from fusion._validation import FloatArray, as_array, flag, instance_of, one_of, scalar
from fusion.book import audit
from fusion.book.chapters import ofs_audit
from fusion.book.style import METHOD_LABELS
from fusion.book.tables import rounded, side_by_side
from fusion.book.chapters.ofs.readings import ALPHAS
from fusion.book.glue import GlueValues
from fusion._docstrings import ParameterDocs
from fusion._shown import shown

__all__ = [
    "table_numbers",
    "observation_numbers",
    "TableReproduction",
    "reproduce_tables",
    "table1_by_scale",
    "tables",
    "joint",
    "support_table",
    "corrected_table1",
    "table1_totals",
]

#: The parameter of this module's glue functions, documented once.
_PARAMS = ParameterDocs({"tabs": "TableReproduction\n    The result of :func:`reproduce_tables`."})


_TOL = 5e-5  # half a unit of the 4th printed decimal


def _fuse_subset(v: FloatArray) -> float:
    """Eqs. 6-12 applied to a given set of readings (no selection step)."""
    return rd.fusion_set_weights(v).value


_ANY = (-np.inf, np.inf, False)


def _side_by_side_cells(*groups: str) -> dict[tuple[str, str], tuple[float, float, bool]]:
    """The cells of :func:`fusion.book.tables.side_by_side` tables concatenated under ``groups``: finite numbers."""
    return {(g, c): _ANY for g in groups for c in ("published", "reproduced", "difference")}


#: The numeric cells :func:`reproduce_tables` makes, all finite (decision 33b: a table edited between producer and
#: reader is refused by its field when the result is rebuilt): temperatures and their differences (°C), totals of
#: absolute errors (>= 0), the implied change of a sum.
_CELLS = {"table2": _side_by_side_cells(f"{METHOD_LABELS['optimal_fusion_set']} (°C)", f"{METHOD_LABELS['mean']} (°C)"),
          "table3": _side_by_side_cells("support degree (°C)"),
          "totals": dict.fromkeys(("published total", "sum of published errors", "recomputed from Table 1"),
                                  (0.0, np.inf, False))}
_AUDIT_CELLS = dict.fromkeys(("published optimal set", "sum change implied by the published mean"), _ANY)
_ALPHA_CELLS = dict.fromkeys(("published", "mean of readings", "ours (α = 0.25)"), _ANY)


@dataclass(frozen=True)
class TableReproduction:
    """Tables 2-3 of the source recomputed from its Table 1.

    Attributes
    ----------
    ofs, mean, sup : ndarray, shape (6,)
        Fused values (°C) of the optimal fusion set, the mean and the rebuilt support degree.
    table2, table3 : DataFrame
        Published beside recomputed values (:func:`fusion.book.tables.side_by_side`).
    totals : DataFrame
        Published totals, sums of the published error columns, totals recomputed from Table 1.
    audit : DataFrame
        Per observation: readings, whether the published optimal-set value is within them, the
        subsets reproducing it, and the change of the readings' sum implied by the published mean.
    alpha : DataFrame
        Per observation: the support-degree parameters α (°C⁻²) reproducing Table 3's value.

    The tables are the result's own copies, and each read returns a copy: an in-place edit of one never reaches
    the result (fuzz 19).
    """

    ofs: FloatArray
    mean: FloatArray
    sup: FloatArray
    table2: pd.DataFrame
    table3: pd.DataFrame
    totals: pd.DataFrame
    audit: pd.DataFrame
    alpha: pd.DataFrame

    __result_spec__ = ResultSpec({**{name: array("obs") for name in ("ofs", "mean", "sup")},
                                  **{name: table(*cells, cells=cells) for name, cells in _CELLS.items()},
                                  "audit": table(*_AUDIT_CELLS, rows="obs", cells=_AUDIT_CELLS),
                                  "alpha": table(*_ALPHA_CELLS, rows="obs", cells=_ALPHA_CELLS)},
                                 relations=(lambda v, cls: _one_per_observation(v["ofs"], f"{cls}.ofs"),))
    __post_init__ = validated_post_init


def _one_per_observation(values: FloatArray, label: str) -> None:
    """Fused values of Table 1's observations: one per observation."""
    n_obs = data.YANG2012_TABLE1.values.shape[1]
    if values.shape != (n_obs,):
        raise ValueError(f"{label} must hold one value per observation of Table 1 ({n_obs}), got shape {values.shape}")


def reproduce_tables(alpha_range: tuple[float, float] = (1e-6, 1e3)) -> TableReproduction:
    """Recompute Tables 2-3 of Yang, Feng & Fan (2012) from their Table 1 and audit them.

    Parameters
    ----------
    alpha_range : (float, float)
        Range (°C⁻²) searched for support-degree parameters reproducing Table 3.

    Returns
    -------
    TableReproduction
        Our fused values per observation (°C), Tables 2-3 published beside ours, the error totals, the audit of each
        optimal set and the α that reproduce Table 3.
    """
    lo, hi = sequence(alpha_range, "alpha_range", 2)
    alpha_range = (scalar(lo, "alpha_range[0]", lo=0.0, lo_open=True), scalar(hi, "alpha_range[1]", lo=0.0, lo_open=True))
    if not alpha_range[0] < alpha_range[1]:
        raise ValueError(f"alpha_range must be an increasing pair (low, high), got {shown(alpha_range)}")
    t1 = data.YANG2012_TABLE1.values  # (3 sensors, 6 observations), °C
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    totals = data.YANG2012_TOTALS.columns
    truth = data.YANG2012_TRUE_VALUE
    obs = np.arange(1, t1.shape[1] + 1)
    ofs = rd.fuse_epochs(t1.T, "optimal_fusion_set").values
    mean = rd.fuse_epochs(t1.T, "mean").values
    sup = rd.fuse_epochs(t1.T, "support_degree").values
    table2 = pd.concat({f"{METHOD_LABELS['optimal_fusion_set']} (°C)": side_by_side(t2["optimal_set"], ofs, obs),
                        f"{METHOD_LABELS['mean']} (°C)": side_by_side(t2["mean"], mean, obs)}, axis=1)
    table3 = pd.concat({"support degree (°C)": side_by_side(t3["reliability"], sup, obs)}, axis=1)
    tot = pd.DataFrame(
        {"published total": [totals["optimal_set"][0], totals["mean"][0], totals["reliability"][0]],
         "sum of published errors": [t2["optimal_set_abs_error"].sum(), t2["mean_abs_error"].sum(),
                                     t3["reliability_abs_error"].sum()],
         "recomputed from Table 1": [np.abs(v - truth).sum() for v in (ofs, mean, sup)]},
        index=pd.Index([METHOD_LABELS["optimal_fusion_set"], METHOD_LABELS["mean"], "support degree (rebuilt)"],
                       name="method"),
    ).round(4)
    audit_rows, alpha_rows = [], []
    for k in range(t1.shape[1]):
        x = t1[:, k]
        matches = audit.matching_subsets(x, t2["optimal_set"][k], _TOL, _fuse_subset)
        audit_rows.append({
            "readings (°C)": ", ".join(f"{v:.1f}" for v in x),
            "published optimal set": t2["optimal_set"][k],
            "within the readings?": audit.in_convex_hull(x, t2["optimal_set"][k]),
            "subsets reproducing it": "; ".join(str(tuple(i + 1 for i in m.members)) for m in matches) or "none",
            "sum change implied by the published mean": rounded(audit.implied_sum_change(x, t2["mean"][k]), 3),
        })
        roots = audit.parameters_matching(x, t3["reliability"][k], "support_degree", "alpha", *alpha_range)
        alpha_rows.append({
            "published": t3["reliability"][k],
            "mean of readings": rounded(x.mean()),
            "ours (α = 0.25)": rounded(sup[k]),
            "α reproducing it (°C⁻²)": ", ".join(f"{a:.4g}" for a in roots) or "none",
        })
    idx = pd.Index(obs, name="observation")
    return TableReproduction(ofs=ofs, mean=mean, sup=sup, table2=table2, table3=table3, totals=tot,
                             audit=pd.DataFrame(audit_rows, index=idx), alpha=pd.DataFrame(alpha_rows, index=idx))


def _reproduction(tabs: object, name: str = "tabs") -> TableReproduction:
    """``tabs`` when it is a :class:`TableReproduction` (whose constructor checked that its fused values are finite,
    one per observation of Table 1: what :func:`table_numbers` and :func:`observation_numbers` read); TypeError
    naming ``name`` otherwise."""
    instance_of(tabs, TableReproduction, name)
    return tabs


#: Units of one scale of :func:`table1_by_scale` (one ``fuse_epochs`` of Table 1's 3 x 6 readings): 69-89 us measured
#: at 200 and 1,000 scales (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the machine shared with other jobs),
#: weighed 100 us: at most 100,000 scales (7-9 CPU-s).
_SCALE_UNITS = 10_000


def table1_by_scale(scales: ArrayLike) -> FloatArray:
    """Optimal-set values of the source's Table 1 for each scale of eq. 6.

    Parameters
    ----------
    scales : array_like, shape (k,)
        Scales of eq. 6, °C (the source's factor 1/2 is scale 2); a scalar is one scale (k = 1).

    Returns
    -------
    ndarray, shape (k, 6)
        Fused values, °C.

    Raises
    ------
    ValueError
        ``scales`` empty, not positive, or more than the work budget's 100,000 scales (``fusion._limits.MAX_WORK``,
        100 us a scale measured), before the first.
    """
    scales = as_array(scales, "scales", ndim=(0, 1))
    if np.any(scales <= 0):
        raise ValueError(f"scales must be positive, got {shown(scales.tolist(), 80)}")
    # rule 17 before the first scale (the audit after fuzz 57a: the caller's scales were looped over without a budget)
    work((scales.size,), "scales", weight=_SCALE_UNITS)
    t1 = data.YANG2012_TABLE1.values
    return np.stack([rd.fuse_epochs(t1.T, "optimal_fusion_set", scale=float(s)).values
                     for s in scales.ravel()])


@study_cache(maxsize=1)
def tables() -> TableReproduction:
    """:func:`reproduce_tables`, computed once.

    Returns
    -------
    TableReproduction
        Tables 2-3 recomputed from Table 1 beside the published ones, with the totals and the audits (default α range).
    """
    return reproduce_tables()


@study_cache(maxsize=1)
def joint() -> ofs_audit.AuditResult:
    """:func:`fusion.book.chapters.ofs_audit.joint_audit`, computed once.

    Returns
    -------
    fusion.book.chapters.ofs_audit.AuditResult
        The best hypothesis of each (program, set rule, correction, order) group, those that explain all 26 values, and
        the count scored.
    """
    return ofs_audit.joint_audit()


@study_cache(maxsize=1)
def support_table() -> pd.DataFrame:
    """:func:`fusion.book.chapters.ofs_audit.support_variants`, computed once.

    Returns
    -------
    pandas.DataFrame
        Rows (kernel, aggregation): the Table 3 observations each support-degree variant reaches, on Table 1 as printed
        and corrected.
    """
    return ofs_audit.support_variants()


def corrected_table1() -> FloatArray:
    """Table 1 with the joint audit's one correction (sensor 1 of observation 5).

    Returns
    -------
    ndarray, shape (3, 6)
        Readings (°C), sensors by observations.

    Raises
    ------
    ValueError
        When the joint audit finds no full explanation.
    """
    fe = ofs_audit.full_explanation(joint())
    if fe is None:
        raise ValueError("the joint audit finds no full explanation")
    t1 = np.array(data.YANG2012_TABLE1.values, dtype=float)
    t1[fe[0].sensor - 1, fe[0].obs - 1] = fe[0].value
    return t1


def table1_totals(t1: ArrayLike, alpha: float = 0.25, guard: bool = False, rule: str = "averages") -> dict[str, float]:
    """Total absolute errors (°C) on a table of readings: optimal set, mean, rebuilt support degree, median.

    Parameters
    ----------
    t1 : array_like, shape (n_sensors, n_obs)
        Readings (°C), as Table 1.
    alpha : float
        Sharpness of the rebuilt support degree (°C⁻²).
    guard : bool
        If true, a one-member optimal set falls back to the mean of all readings.
    rule : {"averages", "sums"}
        Eqs. 3-4 read as averages (as the text names them) or as the sums they print.

    Returns
    -------
    dict
        Method key (``"optimal_fusion_set"``, ``"mean"``, ``"median"``, ``"support_degree"``) -> total absolute
        error against 900 °C (°C).
    """
    x = as_array(t1, "t1", ndim=2).T
    alpha = scalar(alpha, "alpha", lo=0.0, lo_open=True)
    guard = flag(guard, "guard")
    truth = data.YANG2012_TRUE_VALUE
    rule = one_of(rule, ("averages", "sums"), "rule")
    ofs = (rd.fuse_epochs(x, "optimal_fusion_set", threshold="sum") if rule == "sums"
           else rd.fuse_epochs(x, "optimal_fusion_set"))
    vals = {"optimal_fusion_set": ofs.values, "mean": x.mean(axis=1), "median": np.median(x, axis=1),
            "support_degree": rd.fuse_epochs(x, "support_degree", alpha=alpha).values}
    if guard:
        vals["optimal_fusion_set"] = np.where(ofs.members.sum(axis=1) == 1, vals["mean"], vals["optimal_fusion_set"])
    return {k: float(np.abs(v - truth).sum()) for k, v in vals.items()}


@_PARAMS("tabs")
def table_numbers(tabs: TableReproduction) -> GlueValues:
    """The numbers chapter 01's prose quotes from Tables 2-3 reproduced (glue keys ``ofs_our_total_*``, ...).

    Returns
    -------
    GlueValues
        Glue key -> value: our total absolute errors (°C), which observations are reproduced at the
        printed precision, the total under the one-member guard, the ranking margin, and the support
        degree's total at each α.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    _reproduction(tabs)
    T1 = data.YANG2012_TABLE1.values
    t2 = data.YANG2012_TABLE2.columns
    TRUE = data.YANG2012_TRUE_VALUE
    ours = {"ofs": tabs.ofs, "mean": tabs.mean, "sup": tabs.sup}
    ok = np.abs(tabs.ofs - t2["optimal_set"]) < 5e-5
    mean_ok = np.abs(tabs.mean - t2["mean"]) < 5e-5
    OBS = np.arange(1, 7)
    return {
        **{f"ofs_our_total_{k}": rounded(np.abs(v - TRUE).sum()) for k, v in ours.items() if k != "sup"},
        "ofs_n_reproduced": int(ok.sum()),
        "ofs_reproduced_obs": ", ".join(str(o) for o in OBS[ok]),
        "ofs_mean_bad_obs": ", ".join(str(o) for o in OBS[~mean_ok]),
        "ofs_guard_total": rounded(np.abs(np.where(rd.fuse_epochs(T1.T, "optimal_fusion_set").members.sum(axis=1) == 1,
                                                   tabs.mean, tabs.ofs) - TRUE).sum()),
        "ofs_sup_total_by_alpha": ", ".join(
            f"{np.abs(rd.fuse_epochs(T1.T, 'support_degree', alpha=a).values - TRUE).sum():.2f} °C at α = {a:g}"
            for a in sorted((*ALPHAS, 0.25))),
    }


@_PARAMS("tabs")
def observation_numbers(tabs: TableReproduction) -> GlueValues:
    """The numbers chapter 01's prose quotes about observations 1, 2, 5 and 6 of Table 2 (glue keys ``ofs_obs*``).

    Returns
    -------
    GlueValues
        Glue key -> value: published and reproduced fused values (°C), the change of observation 5's
        sum implied by the published mean, the corrected reading and the fused values after it.

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    _reproduction(tabs)
    T1 = data.YANG2012_TABLE1.values
    t2 = data.YANG2012_TABLE2.columns
    return {
        "ofs_obs1_pub": float(t2["optimal_set"][0]), "ofs_obs1_pub_err": float(t2["optimal_set_abs_error"][0]),
        "ofs_obs2_pub": float(t2["optimal_set"][1]), "ofs_obs1_max": float(T1[:, 0].max()),
        "ofs_obs5_sum_change": rounded(audit.implied_sum_change(T1[:, 4], t2["mean"][4]), 3),
        "ofs_obs5_pub": float(t2["optimal_set"][4]),
        "ofs_obs1_ours": rounded(tabs.ofs[0]),
        "ofs_obs6_pub_err": float(t2["optimal_set_abs_error"][5]), "ofs_obs6_pub_mean_err": float(t2["mean_abs_error"][5]),
    }
