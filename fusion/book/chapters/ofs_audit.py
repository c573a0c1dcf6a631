r"""Joint audit of Tables 2-3 of Yang, Feng & Fan (2012), and the three-reading closed form.

The audit asks which hypotheses about the data and about the authors' program explain the
printed values of Table 2 and the totals *jointly*, not one column at a time. A hypothesis is a
triple:

* a **data correction**: Table 1 as printed, or one reading replaced (a one-digit slip, a swap of
  two adjacent digits, or any other value on the 0.1 °C grid within 20 °C of the printed one);
* a **set rule**: a reading of eqs. 3-5 (averages or the printed sums, ``<`` or ``<=``, and the
  denominators :math:`n`, :math:`n-1` or the pair count);
* a **program model**: how the printed values may have been computed from the set: correctly
  (a fresh set at every observation, eqs. 6-12 on its members), or with state carried from one
  observation to the next (a buffer of member readings that is not reset, whose stale entries are
  fused with the new members; a set that is not reset between observations), in the natural or
  in any other order of the observations, starting clean or from a previous pass over the table.

Each hypothesis is scored by how many of the 26 printed values of Table 2 and the totals it
reproduces to the printed precision (6 means, 6 mean errors, 6 optimal-set values, 6 optimal-set
errors, the two totals). The support-degree column of Table 3 depends on a method the source does
not give and is audited separately (the chapter's α search).

References
----------
* Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on
   optimal fusion set. *Journal of Software* 23(Suppl. 1), 134-140.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike, NDArray

from fusion._frozen import constant
from fusion import data
from fusion._counts import count
from fusion._entries import entries_array
from fusion._results import ResultSpec, instance, integer, table, text, trusted, validated_post_init
from fusion._shown import shown
from fusion._validation import FloatArray, as_array, entries_text, flag, given_entries, input_size, instance_of, one_of, scalar
from fusion.readings.fusion_set import TIE_RTOL, _set_weights
from fusion.book.glue import GlueValues
# the support-degree variants of Table 3's column (audited apart from Table 2) live in their own module
from fusion.book.chapters import ofs_support as _support
from fusion.book.chapters import _ofs_audit_budget as _budget
from fusion.book.chapters.ofs_support import _TOL, support_values, support_variants

# named by this module, as before the split (the API page, its back-links to the chapter, the registries)
for _f in (support_values, support_variants):
    _f.__module__ = __name__
del _f

#: Support kernels of the support-degree literature: name -> support of a distance d at sharpness α.
SUPPORT_KERNELS = _support.SUPPORT_KERNELS
#: How the support matrix becomes weights.
SUPPORT_AGGREGATIONS = _support.SUPPORT_AGGREGATIONS

__all__ = [
    "SET_RULES",
    "PROGRAMS",
    "Correction",
    "corrections",
    "set_members",
    "run_program",
    "published_values",
    "score",
    "AuditResult",
    "joint_audit",
    "summary",
    "explain",
    "full_explanation",
    "describe",
    "SUPPORT_KERNELS",
    "SUPPORT_AGGREGATIONS",
    "support_values",
    "support_variants",
    "three_reading_set",
    "explanation_numbers",
]

#: Readings of eqs. 3-5: name -> (distance denominator, threshold denominator, strict test).
#: ``d_i = S_i / a`` with :math:`S_i = \sum_j |s_i - s_j|`, ``d_bar = (sum_i S_i) / b``; the
#: denominators are written as functions of n; strict is ``d_i < d_bar``, else ``<=``.
SET_RULES: dict[str, tuple[str, str, bool]] = constant({
    "averages, d_i < d̄ (the text)": ("n", "n*n", True),
    "averages, d_i ≤ d̄": ("n", "n*n", False),
    "d_i over n-1 (others only), d̄ their mean": ("n-1", "n*(n-1)", True),
    "d_i over n, d̄ over the n(n-1) pairs": ("n", "n*(n-1)", True),
    "sums as printed, d_i < d̄": ("1", "1", True),
    "sums as printed, d_i ≤ d̄": ("1", "1", False),
})

#: Program models: name -> description.
PROGRAMS: dict[str, str] = constant({
    "correct": "a fresh set at every observation, eqs. 6-12 on its members",
    "buffer, clean start": "member readings written into a two-slot buffer that is never reset; both slots fused "
                           "(m = 2 in every denominator); the first observation starts with an empty buffer",
    "buffer, previous pass": "member readings written into a two-slot buffer that is never reset; both slots fused; "
                             "the buffer carried over from a previous pass over the table",
    "three-slot buffer": "member readings written into an n-slot buffer that is never reset, all n slots fused",
    "set not reset": "the members of the previous observation stay members (by sensor)",
})

_TRUTH = 900.0  # the true temperature of the audited experiment (°C): :func:`score`'s default
#: Keys of :func:`published` (and of the printed and reconstructed columns of the chapter's table of them), read
#: by name across this module and the chapter's records (issue 36: named once).
MEAN_ERROR = "mean error"
OPTIMAL_SET = "optimal set"
OPTIMAL_SET_ERROR = "optimal-set error"
MEAN_TOTAL = "mean total"
OPTIMAL_SET_TOTAL = "optimal-set total"
#: Column headers of the joint audit's tables, built by one function of this module and read by others.
SET_RULE = "set rule"
CORRECTION_CLASS = "correction class"
OBSERVATION_ORDER = "observation order"
BEST_HYPOTHESIS = "best hypothesis"
VALUES_EXPLAINED = "values explained (of 26)"
VALUES_MISSED = "values missed"
#: Kinds of a :class:`Correction`.
_CORRECTION_KINDS = ("none", "one-digit slip", "adjacent digits swapped", "other value")
_TOL_TOTAL = 1.5e-4  # totals: four printed decimals, sums of six rounded values


def _denom(expr: str, n: int) -> float:
    return float({"1": 1, "n": n, "n-1": n - 1, "n*n": n * n, "n*(n-1)": n * (n - 1)}[expr])


def set_members(s: ArrayLike, rule: str = "averages, d_i < d̄ (the text)") -> NDArray[np.bool_]:
    """Members of the optimal fusion set under one reading of eqs. 3-5, row by row.

    Parameters
    ----------
    s : array_like, shape (..., n)
        Readings; the last axis is the sensors.
    rule : str
        A key of :data:`SET_RULES`.

    Returns
    -------
    ndarray of bool, shape (..., n)
        As :func:`fusion.readings.fusion_set.optimal_set_members` when no reading passes the test
        (every reading is kept); ties are judged with the package's relative tolerance.
    """
    rule = one_of(rule, tuple(SET_RULES), "rule")
    arr = as_array(s, "s")
    if arr.ndim < 1 or arr.shape[-1] < 2:
        raise ValueError(f"s must have at least two readings on its last axis, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("s contains NaN or infinite values")
    a, b, strict = SET_RULES[rule]
    n = arr.shape[-1]
    S = np.abs(arr[..., :, None] - arr[..., None, :]).sum(axis=-1)
    d = S / _denom(a, n)
    d_bar = S.sum(axis=-1, keepdims=True) / _denom(b, n)
    members = d < d_bar * (1.0 - TIE_RTOL) if strict else d <= d_bar * (1.0 + TIE_RTOL)
    empty = ~members.any(axis=-1)
    return np.where(empty[..., None], True, members)


def _fuse(values: FloatArray, members: NDArray[np.bool_]) -> FloatArray:
    """Eqs. 6-12 (scale 2 °C, row of C with j = i) on the marked entries of each row.

    Rows with one or two marked entries take the plain mean of them, which is what eqs. 6-11
    give there (equal weights, see the chapter); the others go through the package's weights.
    """
    m = members.sum(axis=1)
    v = np.where(members, values, 0.0)
    out = v.sum(axis=1) / np.maximum(m, 1)
    big = m > 2
    if big.any():
        w = _set_weights(values[big], members[big], 2.0, True)
        out[big] = np.einsum("ij,ij->i", w, v[big])
    return out


def run_program(t1: ArrayLike, program: str = "correct", rule: str = "averages, d_i < d̄ (the text)",
                order: ArrayLike | None = None) -> FloatArray:
    """Optimal-set values of every observation under one program model, for many tables at once.

    Parameters
    ----------
    t1 : array_like, shape (H, n_obs, n) or (n_obs, n)
        Readings: H variants of Table 1, observations by sensors (°C).
    program : str
        A key of :data:`PROGRAMS`.
    rule : str
        A key of :data:`SET_RULES`.
    order : array_like of int, shape (n_obs,) or (H, n_obs), optional
        Order (0-based observation indices) in which the program visits the observations; the
        natural order by default. Irrelevant for ``"correct"``.

    Returns
    -------
    ndarray, shape (H, n_obs) or (n_obs,)
        Fused values in observation order (°C).

    Raises
    ------
    TypeError
        ``order`` not of integers (a float, even a whole one, is not an observation index).
    ValueError
        ``t1`` not of the shapes above, ``program`` or ``rule`` unknown, ``order`` not of the shapes above or not a
        permutation of the observations; ``t1`` beyond the work budget (``fusion._limits.MAX_WORK``: 10 units a pair
        of readings of an observation, and a stateful program's 20,000 units a step plus 80 a table and one a pair).
    """
    program = one_of(program, tuple(PROGRAMS), "program")
    arr = as_array(t1, "t1")
    single = arr.ndim == 2
    if single:
        arr = arr[None]
    if arr.ndim != 3:
        raise ValueError(f"t1 must have shape (H, n_obs, n) or (n_obs, n), got {arr.shape}")
    _budget.program_budget(arr.shape, _program_shape(program, arr.shape[2])[0], program != "correct")
    return _run(arr, set_members(arr, rule), program, None if order is None else _order(order, arr.shape[:2]), single)


def _order(order: object, shape: tuple[int, int], what: str = "the observations of t1 and its H variants"
           ) -> NDArray[np.intp]:
    """``order`` as integer observation indices of shape (n_obs,) or (H, n_obs) (``shape`` is (H, n_obs)), each row
    a permutation of the observations; TypeError/ValueError naming ``order`` (and ``what`` the shape is)."""
    H, n_obs = shape
    # a sequence's entries before it is read or converted (fuzz 39a E1); an array's shape is named below (no copy)
    n = None if isinstance(getattr(order, "shape", None), tuple) else given_entries(order, H * n_obs)
    if n is not None and n > H * n_obs:
        raise ValueError(f"order must have shape ({n_obs},) or ({H}, {n_obs}) ({what}), got {entries_text(n)} entries")
    input_size(order, "order")
    try:
        o = entries_array(order)   # an object array of ints is integers, as its list is (fuzz 36b D4)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"order must be an array of integers (0-based observation indices): {exc}") from None
    if o.dtype.kind not in "iu":
        raise TypeError(f"order must hold integers (0-based observation indices), got dtype {o.dtype}")
    if o.shape not in ((n_obs,), (1, n_obs), (H, n_obs)):
        raise ValueError(f"order must have shape ({n_obs},) or ({H}, {n_obs}) ({what}), got {o.shape}")
    o = np.broadcast_to(o.astype(np.intp), (H, n_obs))
    if not np.all(np.sort(o, axis=1) == np.arange(n_obs)):
        raise ValueError("order must be a permutation of the observations")
    return o


def _members_first(mem: NDArray[np.bool_]) -> NDArray[np.intp]:
    """``np.argsort(~mem, axis=1, kind="stable")``: each row's members' indices in order, then the others'.

    With few sensors (up to 12) the permutation of every possible row is tabulated once and each row looks its own
    up by its bit pattern: the same integers as the sort, without sorting every row.
    """
    n = mem.shape[1]
    if n > 12:
        return np.argsort(~mem, axis=1, kind="stable")
    patterns = (np.arange(2**n)[:, None] >> np.arange(n)) & 1 == 1      # row p: bit j of p is sensor j
    table = np.argsort(~patterns, axis=1, kind="stable")
    code = mem.astype(np.intp) @ (1 << np.arange(n, dtype=np.intp))
    return table[code]


def _step(program: str, s: FloatArray, mem: NDArray[np.bool_], res: FloatArray, buf: FloatArray,
          filled: NDArray[np.bool_], prev: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """One observation of a stateful program on every row: its fused values written into ``res``.

    ``s``, ``mem`` (rows, n): the observation's readings and set members; ``res`` (rows,): the correct values
    on entry, the program's on return. The state is updated in place (``buf``, ``filled``: the buffer slots and
    whether they were ever written); the members of this observation are returned (the next one's ``prev``).
    """
    n, k_slots = s.shape[1], buf.shape[1]
    m = mem.sum(axis=1)
    if program == "set not reset":
        use = mem | prev
        vals, slots, full = s, use, use.sum(axis=1) == m  # the union adds nobody: correct value
    else:
        # write the members, in sensor order, into slots 0, 1, ...; later slots keep their values
        # (the members' indices in sensor order: a stable sort puts them first)
        first = _members_first(mem)[:, :k_slots]
        has = np.arange(k_slots) < m[:, None]
        np.copyto(buf, np.take_along_axis(s, first, axis=1), where=has)
        filled |= has
        vals, slots, full = buf, filled, (m >= k_slots) & (m == n)  # every slot holds a current member
    rest = ~full
    res[rest] = _fuse(vals[rest], slots[rest])
    return mem


def _program_shape(program: str, n: int) -> tuple[int, int]:
    """(passes over the table, buffer slots) of a stateful program on ``n`` sensors."""
    return (2 if program == "buffer, previous pass" else 1), (n if program == "three-slot buffer" else 2)


def _run(arr: FloatArray, members: NDArray[np.bool_], program: str, order: ArrayLike | None,
         single: bool = False, correct: FloatArray | None = None) -> FloatArray:
    H, n_obs, n = arr.shape
    if order is None:
        ordr = np.broadcast_to(np.arange(n_obs), (H, n_obs))
    else:
        ordr = np.broadcast_to(np.asarray(order, dtype=int), (H, n_obs))
        if not np.all(np.sort(ordr, axis=1) == np.arange(n_obs)):
            raise ValueError("order must be a permutation of the observations")
    if correct is None:
        correct = _fuse(arr.reshape(-1, n), members.reshape(-1, n)).reshape(H, n_obs)
    if program == "correct":
        return correct[0] if single else correct
    out = np.empty((H, n_obs))
    rows = np.arange(H)
    passes, k_slots = _program_shape(program, n)
    buf = np.zeros((H, k_slots))
    filled = np.zeros((H, k_slots), dtype=bool)
    prev = np.zeros((H, n), dtype=bool)
    for _ in range(passes):
        for step in range(n_obs):
            k = ordr[:, step]
            res = correct[rows, k]   # a new array (advanced indexing copies)
            prev = _step(program, arr[rows, k], members[rows, k], res, buf, filled, prev)
            out[rows, k] = res
    return out[0] if single else out


def _run_every_order(arr: FloatArray, members: NDArray[np.bool_], program: str, correct: FloatArray,
                     orders: NDArray[np.intp]) -> FloatArray:
    """``_run`` of each of the H tables under each order of ``orders``: every permutation, in lexicographic order.

    Returns shape (H, len(orders), n_obs), the values of ``_run(arr[h], members[h], program, orders[o],
    correct=correct[h])`` bit for bit. A program's state after a step depends only on the observations visited so
    far: the orders sharing their first t + 1 observations (a block of (n_obs - t - 1)! consecutive orders) share
    it, so step t runs once per such prefix, not once per order (about half the rows of a single pass; a second
    pass starts from 720 different states and runs every order). The rows are independent: the same operations
    on fewer rows give the same values.
    """
    H, n_obs, n = arr.shape
    n_ord = len(orders)
    if n_ord != math.factorial(n_obs):
        raise ValueError(f"orders must hold every permutation of {n_obs} observations, got {n_ord}")
    passes, k_slots = _program_shape(program, n)
    out = np.empty((H, n_ord, n_obs))
    every = np.arange(n_ord)
    groups = 1
    buf = np.zeros((H, 1, k_slots))
    filled = np.zeros((H, 1, k_slots), dtype=bool)
    prev = np.zeros((H, 1, n), dtype=bool)
    for p in range(passes):
        for step in range(n_obs):
            block = math.factorial(n_obs - step - 1) if p == 0 else 1
            heads = every[::block]           # the first order of each group sharing the first step + 1 observations
            if heads.size != groups:          # each group splits into n_obs - step: the state is repeated to them
                grow = heads.size // groups
                buf, filled, prev = (np.repeat(a, grow, axis=1) for a in (buf, filled, prev))
                groups = heads.size
            k = orders[heads, step]
            res = correct[:, k].reshape(-1)
            mem = _step(program, arr[:, k].reshape(-1, n), members[:, k].reshape(-1, n), res,
                        buf.reshape(-1, k_slots), filled.reshape(-1, k_slots), prev.reshape(-1, n))
            prev = mem.reshape(H, groups, n)
            out[:, every, orders[:, step]] = np.repeat(res.reshape(H, groups), block, axis=1)
    return out


def published_values() -> dict[str, FloatArray]:
    """The 26 printed values scored by the audit: Table 2's four columns and two totals.

    Returns
    -------
    dict of str to ndarray
        "mean", "mean error", "optimal set", "optimal-set error" (shape (6,)) and "mean total",
        "optimal-set total" (shape (1,)), °C.
    """
    t2, tot = data.YANG2012_TABLE2.columns, data.YANG2012_TOTALS.columns
    return {"mean": np.asarray(t2["mean"]), MEAN_ERROR: np.asarray(t2["mean_abs_error"]),
            OPTIMAL_SET: np.asarray(t2["optimal_set"]), OPTIMAL_SET_ERROR: np.asarray(t2["optimal_set_abs_error"]),
            MEAN_TOTAL: np.asarray(tot["mean"]), OPTIMAL_SET_TOTAL: np.asarray(tot["optimal_set"])}


def score(mean: ArrayLike, ofs: ArrayLike, truth: float = _TRUTH) -> dict[str, NDArray[np.bool_]]:
    """Which printed values a hypothesis reproduces.

    Parameters
    ----------
    mean, ofs : array_like, shape (H, n_obs)
        Arithmetic means and optimal-set values of each hypothesis (°C); shape (n_obs,) is one hypothesis.
    truth : float
        True temperature (°C).

    Returns
    -------
    dict of str to ndarray of bool
        Same keys as :func:`published_values`; shape (H, n_obs) or (H, 1) for the totals.

    Raises
    ------
    ValueError
        ``mean`` or ``ofs`` not finite, not of six observations (n_obs = 6, the printed tables) or of different
        shapes; ``truth`` not finite.
    """
    m, o = np.atleast_2d(as_array(mean, "mean", ndim=(1, 2))), np.atleast_2d(as_array(ofs, "ofs", ndim=(1, 2)))
    n_obs = published_values()["mean"].size
    for name, v in (("mean", m), ("ofs", o)):
        if v.shape[1] != n_obs:
            raise ValueError(f"{name} must hold the {n_obs} observations of the printed tables per hypothesis, "
                             f"got shape {v.shape}")
    if m.shape != o.shape:
        raise ValueError(f"mean and ofs must have the same shape, got {m.shape} and {o.shape}")
    truth = scalar(truth, "truth")
    return _hits(_column_hits(m, "mean", truth), _column_hits(o, OPTIMAL_SET, truth))


#: The keys of :func:`score` by printed column: (the column, its errors, their total).
_SCORE_KEYS = {"mean": ("mean", MEAN_ERROR, MEAN_TOTAL),
               OPTIMAL_SET: (OPTIMAL_SET, OPTIMAL_SET_ERROR, OPTIMAL_SET_TOTAL)}


def _column_hits(values: FloatArray, column: str, truth: float) -> dict[str, NDArray[np.bool_]]:
    """:func:`score`'s entries of one printed column ("mean" or "optimal set"): its values, errors and total."""
    pub = published_values()
    key, err, tot = _SCORE_KEYS[column]
    e = np.round(np.abs(values - truth), 4)
    return {key: np.abs(values - pub[key]) < _TOL, err: np.abs(e - pub[err]) < _TOL,
            tot: np.abs(e.sum(axis=1, keepdims=True) - pub[tot]) < _TOL_TOTAL}


def _hits(mean: dict[str, NDArray[np.bool_]], ofs: dict[str, NDArray[np.bool_]]) -> dict[str, NDArray[np.bool_]]:
    """:func:`score` from the two columns' :func:`_column_hits`, in its key order."""
    both = mean | ofs
    return {k: both[k] for k in ("mean", MEAN_ERROR, OPTIMAL_SET, OPTIMAL_SET_ERROR, MEAN_TOTAL, OPTIMAL_SET_TOTAL)}


@dataclass(frozen=True)
class Correction:
    """One single-reading correction of Table 1.

    Attributes
    ----------
    sensor, obs : int
        1-based sensor and observation (0 for "no correction").
    value : float
        Corrected reading (°C): a real number as :func:`describe` and :func:`explain` read it (not a bool, its
        magnitude representable; a float or numpy scalar, not an array); NaN for "none".
    kind : str
        "none", "one-digit slip", "adjacent digits swapped" or "other value": a label, not checked against
        ``value`` (:func:`corrections` sets both; a replaced value keeps its label).
    """

    sensor: int
    obs: int
    value: float
    kind: str

    __result_spec__ = ResultSpec(
        {"sensor": integer(0), "obs": integer(0), "value": instance(float, int, np.floating, np.integer),
         "kind": text(*_CORRECTION_KINDS)},
        relations=(lambda v, cls: _correction_relation(v, cls),))
    __post_init__ = validated_post_init


def _correction_relation(values: dict, cls: str) -> None:
    """"no correction" is sensor 0, observation 0 and a NaN value; any other correction a 1-based sensor and
    observation and a finite reading."""
    none = values["kind"] == "none"
    for field in ("sensor", "obs"):
        if (values[field] == 0) != none:
            raise ValueError(f"{cls}.{field} must be {'0' if none else '>= 1'} for the kind {shown(values['kind'])}, "
                             f"got {shown(values[field])}")
    if not none:  # the consumers' own rule (_correction: scalar), so that a Correction they refuse is not built
        scalar(values["value"], f"{cls}.value")  # (fuzz 22b q1: True and 1e308 were accepted, then refused)
    v = float(values["value"])
    if none != np.isnan(v) or np.isinf(v):
        raise ValueError(f"{cls}.value must be {'NaN' if none else 'finite'} for the kind {shown(values['kind'])}, "
                         f"got {shown(v)}")


def _slips(v: float) -> tuple[list[float], list[float]]:
    txt = f"{v:.1f}".replace(".", "")
    one, swap = [], []
    for p in range(len(txt)):
        for dgt in "0123456789":
            if dgt != txt[p] and not (p == 0 and dgt == "0"):
                one.append(int(txt[:p] + dgt + txt[p + 1:]) / 10)
    for p in range(len(txt) - 1):
        if txt[p] != txt[p + 1] and not (p == 0 and txt[p + 1] == "0"):
            swap.append(int(txt[:p] + txt[p + 1] + txt[p] + txt[p + 2:]) / 10)
    return one, swap


#: Largest search window of :func:`corrections` (°C): 20,001 grid values per reading.
MAX_WINDOW = 1000.0


def _window(window: object) -> float:
    """The search window of :func:`corrections` (°C): finite, positive, at most :data:`MAX_WINDOW`."""
    return scalar(window, "window", lo=0.0, hi=MAX_WINDOW, lo_open=True)


def corrections(t1: ArrayLike | None = None, window: float = 20.0, slips_only: bool = False) -> list[Correction]:
    """Every single-reading correction searched: one-digit slips first, then swaps, then any value.

    Parameters
    ----------
    t1 : array_like, shape (n, n_obs), optional
        Table 1 (sensors by observations, °C); the published one by default.
    window : float
        Other values are searched on the 0.1 °C grid within this distance of the printed reading.
    slips_only : bool
        Only one-digit slips and adjacent swaps.

    Returns
    -------
    list of Correction
        Starting with "no correction".

    Raises
    ------
    ValueError
        ``window`` not in (0, 1000] (``MAX_WINDOW``); the corrections beyond the work budget
        (``fusion._limits.MAX_WORK``, 25,000 units a character of a reading of ``t1`` printed to 0.1 and 4,000 a value of its grid), naming
        ``t1 and window``.
    """
    window = _window(window)
    slips_only = flag(slips_only, "slips_only")
    t = data.YANG2012_TABLE1.values if t1 is None else as_array(t1, "t1", ndim=(2,))
    _budget.corrections_budget(t, window, slips_only)  # 25,000 units a printed character, 4,000 a grid value
    out = [Correction(0, 0, float("nan"), "none")]
    grid = np.round(np.arange(-round(window * 10), round(window * 10) + 1) / 10, 1)
    for i, k in itertools.product(range(t.shape[0]), range(t.shape[1])):
        v = float(t[i, k])
        one, swap = _slips(v)
        seen = {round(v, 1)}
        for kind, vals in (("one-digit slip", one), ("adjacent digits swapped", swap),
                           ("other value", [] if slips_only else list(np.round(v + grid, 1)))):
            for u in vals:
                if round(u, 1) not in seen:
                    seen.add(round(u, 1))
                    out.append(trusted(Correction, sensor=i + 1, obs=k + 1, value=float(u), kind=kind))
    return out


def _tables(cors: list[Correction]) -> FloatArray:
    """(H, n_obs, n) readings, one corrected Table 1 per correction."""
    t = np.array(data.YANG2012_TABLE1.values, dtype=float).T  # (n_obs, n)
    out = np.repeat(t[None], len(cors), axis=0)
    for h, c in enumerate(cors):
        if c.obs:
            out[h, c.obs - 1, c.sensor - 1] = c.value
    return out


#: Columns of :attr:`AuditResult.table` and :attr:`AuditResult.full` read by :func:`summary`,
#: :func:`full_explanation` and :func:`explanation_numbers`.
_TABLE_COLUMNS = ("program", CORRECTION_CLASS, VALUES_EXPLAINED, OBSERVATION_ORDER, BEST_HYPOTHESIS, SET_RULE,
                  VALUES_MISSED)
_FULL_COLUMNS = ("program", SET_RULE, OBSERVATION_ORDER, "sensor", "obs", "value", "kind", "correction")
#: The cells of :attr:`AuditResult.full` that :func:`full_explanation` reads into a :class:`Correction` (decision 33b).
_FULL_CELLS = {"sensor": (0.0, np.inf, True), "obs": (0.0, np.inf, True), "value": (-np.inf, np.inf, False)}


@dataclass(frozen=True)
class AuditResult:
    """Outcome of :func:`joint_audit`.

    Attributes
    ----------
    table : DataFrame
        One row per (program, set rule, correction class, order class): the best hypothesis of
        that group, the number of printed values it explains (of 26) and the values it misses.
    full : DataFrame
        Every hypothesis that explains all 26 values (with the correction's sensor, observation,
        value and kind as columns).
    n_hypotheses : int
        Number of hypotheses scored (a stateful program's natural order is counted again in its
        order search).
    same_sets : DataFrame
        Set rules that give exactly the sets of an earlier rule for every correction (so the same
        values under every program and order); they are not scored again.

    The tables are the result's own copies (also those given to ``dataclasses.replace``), and each read returns a
    copy: an in-place edit of one never reaches the result (fuzz 19).
    """

    table: pd.DataFrame
    full: pd.DataFrame
    n_hypotheses: int
    same_sets: pd.DataFrame

    # the counts joint_audit makes (fuzz 33b D3: an inf or 27 reached summary's table and the glue)
    __result_spec__ = ResultSpec({"table": table(*_TABLE_COLUMNS, cells={VALUES_EXPLAINED: (0.0, 26.0, True)}),
                                  "full": table(*_FULL_COLUMNS, cells=_FULL_CELLS),
                                  "n_hypotheses": integer(0), "same_sets": table()})
    __post_init__ = validated_post_init




def _audit_result(result: object, name: str, explained: bool = False) -> AuditResult:
    """``result`` when it is an :class:`AuditResult` (whose constructor checked that its tables hold the columns read
    here) and, with ``explained``, holds at least one full explanation; TypeError/ValueError naming ``name``."""
    instance_of(result, AuditResult, name)
    if explained and result.full.empty:
        raise ValueError(f"{name} holds no hypothesis that explains all 26 values (its full table is empty)")
    return result


def _missed(hit: dict[str, NDArray[np.bool_]], h: int) -> str:
    miss = []
    for key, arr in hit.items():
        bad = np.flatnonzero(~arr[h])
        if bad.size:
            miss.append(key if arr.shape[1] == 1 else f"{key} (obs. {', '.join(str(b + 1) for b in bad)})")
    return "; ".join(miss) or "none"




def _correction(c: object, name: str) -> Correction:
    """``c`` when it is a :class:`Correction` of Table 1: a known kind, a 1-based sensor and observation of the table
    (both 0 for "none") and a finite value (any for "none"); TypeError/ValueError naming ``name``."""
    instance_of(c, Correction, name)
    one_of(c.kind, _CORRECTION_KINDS, f"{name}.kind")
    n, n_obs = data.YANG2012_TABLE1.values.shape
    if c.kind == "none":
        if not (count(c.sensor, f"{name}.sensor", 0, None) == 0 == count(c.obs, f"{name}.obs", 0, None)):
            raise ValueError(f"{name} of kind 'none' must have sensor = obs = 0, got {c.sensor} and {c.obs}")
        return c
    count(c.sensor, f"{name}.sensor", 1, n)
    count(c.obs, f"{name}.obs", 1, n_obs)
    scalar(c.value, f"{name}.value")
    return c


def describe(c: Correction) -> str:
    """One-line description of a correction, e.g. "obs. 5, sensor 1: 899.9 → 889.9 (one-digit slip)".

    Parameters
    ----------
    c : Correction

    Returns
    -------
    str
        ``"Table 1 as printed"``, or the observation, sensor, printed and corrected value (°C, 1 decimal) and the kind.

    Raises
    ------
    TypeError
        ``c`` not a :class:`Correction`.
    ValueError
        Its kind unknown, or its sensor or observation not one of Table 1 (1-based; both 0 for "none").
    """
    _correction(c, "c")
    if c.kind == "none":
        return "Table 1 as printed"
    return (f"obs. {c.obs}, sensor {c.sensor}: {data.YANG2012_TABLE1.values[c.sensor - 1, c.obs - 1]:.1f} → "
            f"{c.value:.1f} ({c.kind})")


def joint_audit(window: float = 20.0, order_search: str = "mean-consistent") -> AuditResult:
    """Score every hypothesis (correction × set rule × program × order) against the printed values.

    All corrections are run in the natural order under every rule and program. Every one of the
    720 orders of the observations is run under every rule and stateful program with Table 1 as
    printed and with the corrections selected by ``order_search``.

    Parameters
    ----------
    window : float
        Search window of the "other value" corrections (°C).
    order_search : {"mean-consistent", "slips"}
        ``"mean-consistent"``: the corrections that reproduce the ten mean-column values (means,
        their errors and total), which depend on the data alone; a hypothesis explaining all 26
        values must be among them, so this finds every full explanation at a fraction of the cost.
        ``"slips"``: every one-digit slip and swap (about 500 000 hypotheses per rule and program).

    Returns
    -------
    AuditResult
        The best hypothesis of each (program, set rule, correction class, order class), the hypotheses that explain all
        26 printed values, the count scored.

    Raises
    ------
    ValueError
        ``window`` not in (0, 1000] (``MAX_WINDOW``) or beyond the work budget (``fusion._limits.MAX_WORK``,
        16,000 units a correction: a window up to about 160 °C, 65 °C with ``"slips"``).
    """
    order_search = one_of(order_search, ("mean-consistent", "slips"), "order_search")
    window = _window(window)
    _budget.joint_budget(int(np.size(data.YANG2012_TABLE1.values)), window, order_search)  # 16,000 units a correction
    cors = corrections(window=window)
    tabs = _tables(cors)
    mean = tabs.mean(axis=2)
    if order_search == "slips":
        slip_idx = np.array([h for h, c in enumerate(cors) if c.kind in ("none", "one-digit slip",
                                                                        "adjacent digits swapped")])
    else:
        hit = score(mean, mean)
        mean_ok = hit["mean"].all(axis=1) & hit[MEAN_ERROR].all(axis=1) & hit[MEAN_TOTAL].all(axis=1)
        slip_idx = np.flatnonzero(mean_ok | (np.arange(len(cors)) == 0))
    orders = np.array(list(itertools.permutations(range(tabs.shape[1]))))
    kinds = np.array([c.kind for c in cors])
    rows, full, same = [], [], []
    n_hyp = 0

    def record(prog: str, rule: str, order_class: str, idx: NDArray[np.int_], ordr: NDArray[np.int_] | None,
               hit: dict[str, NDArray[np.bool_]]) -> None:
        nonlocal n_hyp
        total = sum(a.sum(axis=1) for a in hit.values())
        n_hyp += total.size
        for cls in ("none", "one-digit slip", "adjacent digits swapped", "other value"):
            sel = np.flatnonzero(kinds[idx] == cls)
            if sel.size == 0:
                continue
            best = sel[np.argmax(total[sel])]  # first best: slips before swaps before others, sensors in order
            rows.append({"program": prog, SET_RULE: rule, CORRECTION_CLASS: cls, OBSERVATION_ORDER: order_class,
                         BEST_HYPOTHESIS: describe(cors[idx[best]])
                         + ("" if ordr is None else f"; order {'-'.join(str(o + 1) for o in ordr[best])}"),
                         VALUES_EXPLAINED: int(total[best]),
                         "hypotheses at that score": int(np.sum(total[sel] == total[best])),
                         VALUES_MISSED: _missed(hit, best)})
            for h in sel[total[sel] == 26]:
                c = cors[idx[h]]
                full.append({"program": prog, SET_RULE: rule, "correction": describe(c),
                             OBSERVATION_ORDER: "1-6" if ordr is None else "-".join(str(o + 1) for o in ordr[h]),
                             "sensor": c.sensor, "obs": c.obs, "value": c.value, "kind": c.kind})

    all_idx = np.arange(len(cors))
    order_class = ("any of the 720 (mean-consistent data)" if order_search == "mean-consistent"
                   else "any of the 720 (slips)")
    H = slip_idx.size
    rep = np.repeat(slip_idx, len(orders))
    o_rep = np.tile(orders, (H, 1))
    n_obs = tabs.shape[1]
    mean_hits = _column_hits(mean[rep], "mean", _TRUTH)  # the same under every rule, program and order
    seen: dict[bytes, str] = {}
    for rule in SET_RULES:
        members = set_members(tabs, rule)
        key = members.tobytes()
        if key in seen:  # the same sets for every correction: the same values under every program and order
            same.append({SET_RULE: rule, "gives the sets of": seen[key]})
            continue
        seen[key] = rule
        correct = _run(tabs, members, "correct", None)
        for prog in PROGRAMS:
            ofs = _run(tabs, members, prog, None, correct=correct)
            record(prog, rule, "1-6", all_idx, None, score(mean, ofs))
            if prog == "correct":
                continue
            # every order, with Table 1 as printed and every slip or swap
            ofs_o = _run_every_order(tabs[slip_idx], members[slip_idx], prog, correct[slip_idx],
                                     orders).reshape(-1, n_obs)
            record(prog, rule, order_class, rep, o_rep, _hits(mean_hits, _column_hits(ofs_o, OPTIMAL_SET, _TRUTH)))
    table = pd.DataFrame(rows).sort_values(VALUES_EXPLAINED, ascending=False, kind="stable")
    full_table = pd.DataFrame(full) if full else pd.DataFrame(columns=list(_FULL_COLUMNS))  # its columns even if empty
    return AuditResult(table=table.reset_index(drop=True), full=full_table, n_hypotheses=n_hyp,
                       same_sets=pd.DataFrame(same))



_CLASS_COLUMNS = {"none": "Table 1 as printed", "one-digit slip": "one-digit slip",
                  "adjacent digits swapped": "adjacent digits swapped", "other value": "other value (±20 °C)"}


def summary(result: AuditResult) -> pd.DataFrame:
    """Best number of printed values explained (of 26) per program and correction class.

    Parameters
    ----------
    result : AuditResult
        From :func:`joint_audit`.

    Returns
    -------
    DataFrame
        Rows: programs (with the observation orders searched); columns: correction classes, and
        the best hypothesis of the row with the values it misses. Maxima over the set rules.
    """
    _audit_result(result, "result")
    t = result.table.copy()
    t["stateful"] = t[OBSERVATION_ORDER].where(t["program"] != "correct", "")
    piv = t.pivot_table(index="program", columns=CORRECTION_CLASS, values=VALUES_EXPLAINED,
                        aggfunc="max", sort=False)
    piv = piv.reindex(index=list(PROGRAMS), columns=list(_CLASS_COLUMNS)).rename(columns=_CLASS_COLUMNS)
    best = t.sort_values(VALUES_EXPLAINED, ascending=False, kind="stable").groupby("program", sort=False).first()
    piv[BEST_HYPOTHESIS] = [f"{best.loc[p, BEST_HYPOTHESIS]} [{best.loc[p, SET_RULE]}]" for p in piv.index]
    piv["values it misses"] = [best.loc[p, VALUES_MISSED] for p in piv.index]
    return piv


def explain(correction: Correction, program: str, rule: str = "averages, d_i < d̄ (the text)",
            order: ArrayLike | None = None, truth: float = 900.0) -> pd.DataFrame:
    """Published beside reconstructed values of one hypothesis, value by value.

    Parameters
    ----------
    correction : Correction
        Data correction (``Correction(0, 0, nan, "none")`` for Table 1 as printed).
    program, rule : str
        Keys of :data:`PROGRAMS` and :data:`SET_RULES`.
    order : array_like of int, shape (6,) or (1, 6), optional
        0-based order of the observations (natural by default): one order, as a row or a single-row array.
    truth : float
        True temperature (°C).

    Returns
    -------
    DataFrame
        Rows: observations 1-6 and "total"; columns: printed and reconstructed mean, optimal set and
        their absolute errors (°C), 4 decimals.

    Raises
    ------
    TypeError
        ``correction`` not a :class:`Correction`, ``order`` not of integers.
    ValueError
        ``correction`` of an unknown kind or outside Table 1 (as in :func:`describe`), an unknown ``program`` or
        ``rule``, ``order`` not of shape (6,) or (1, 6) or not a permutation of the six observations, ``truth``
        not finite.
    """
    _correction(correction, "correction")
    truth = scalar(truth, "truth")
    tab = _tables([correction])
    mean = tab.mean(axis=2)[0]
    if order is not None:   # checked here, by the caller's shape (fuzz 38b D4: (1, 6) was refused as (1, 1, 6))
        order = _order(order, (1, tab.shape[1]), "one order of the six observations")
    ofs = run_program(tab, program, rule, order)[0]
    pub = published_values()
    em, eo = np.round(np.abs(mean - truth), 4), np.round(np.abs(ofs - truth), 4)
    df = pd.DataFrame({("mean", "printed"): pub["mean"], ("mean", "reconstructed"): mean,
                       (MEAN_ERROR, "printed"): pub[MEAN_ERROR], (MEAN_ERROR, "reconstructed"): em,
                       (OPTIMAL_SET, "printed"): pub[OPTIMAL_SET], (OPTIMAL_SET, "reconstructed"): ofs,
                       (OPTIMAL_SET_ERROR, "printed"): pub[OPTIMAL_SET_ERROR],
                       (OPTIMAL_SET_ERROR, "reconstructed"): eo},
                      index=pd.Index([str(k) for k in range(1, 7)], name="observation"))
    df.loc["total"] = [np.nan, np.nan, pub[MEAN_TOTAL][0], em.sum(), np.nan, np.nan, pub[OPTIMAL_SET_TOTAL][0],
                       eo.sum()]
    return df.round(4)


def full_explanation(result: AuditResult) -> tuple[Correction, str, str] | None:
    """The full explanation to show: natural order first, then the first found.

    Parameters
    ----------
    result : AuditResult

    Returns
    -------
    (Correction, program, rule) or None
        None when no hypothesis explains all 26 values.
    """
    _audit_result(result, "result")
    if result.full.empty:
        return None
    f = result.full.sort_values(OBSERVATION_ORDER, key=lambda o: o != "1-6", kind="stable").iloc[0]
    return Correction(int(f["sensor"]), int(f["obs"]), float(f["value"]), str(f["kind"])), str(f["program"]), \
        str(f[SET_RULE])

def three_reading_set(x: ArrayLike) -> NDArray[np.bool_]:
    r"""Closed form of the optimal fusion set for three readings (eqs. 3-5 read as averages).

    Sort the readings :math:`a \le b \le c` and let :math:`g_1 = b - a`, :math:`g_2 = c - b`.
    Then :math:`S_a = 2g_1 + g_2`, :math:`S_b = g_1 + g_2`, :math:`S_c = g_1 + 2g_2` and the
    threshold is :math:`\frac13(S_a + S_b + S_c) = \frac43(g_1 + g_2)`, so

    * :math:`b` is always a member (:math:`g_1 + g_2 < \frac43(g_1 + g_2)` unless both gaps are 0);
    * :math:`a` is a member iff :math:`g_2 > 2 g_1`; :math:`c` is a member iff :math:`g_1 > 2 g_2`;
    * hence the set is :math:`\{a, b\}`, :math:`\{b, c\}` or :math:`\{b\}`, never all three.

    Parameters
    ----------
    x : array_like, shape (..., 3)
        Three readings per row.

    Returns
    -------
    ndarray of bool, shape (..., 3)
        Members, in the readings' order; all ``True`` for three identical readings (the package's
        convention for an empty set). Ties (:math:`g_2 = 2g_1`) are excluded, as in eq. 5.
    """
    arr = as_array(x, "x")
    if arr.ndim < 1 or arr.shape[-1] != 3:
        raise ValueError(f"x must have three readings on its last axis, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("x contains NaN or infinite values")
    idx = np.argsort(arr, axis=-1, kind="stable")
    srt = np.take_along_axis(arr, idx, axis=-1)
    g1, g2 = srt[..., 1] - srt[..., 0], srt[..., 2] - srt[..., 1]
    tol = TIE_RTOL * (g1 + g2)
    mem_sorted = np.stack([g2 - 2 * g1 > 3 * tol, g1 + g2 > 0, g1 - 2 * g2 > 3 * tol], axis=-1)
    mem_sorted = np.where((g1 + g2 == 0)[..., None], True, mem_sorted)
    out = np.empty_like(mem_sorted)
    np.put_along_axis(out, idx, mem_sorted, axis=-1)
    return out



def explanation_numbers(joint: AuditResult) -> GlueValues:
    """The numbers chapter 01's prose quotes from the joint audit of Tables 2-3 (glue keys ``ofs_joint_*``,
    ``ofs_fix_*``, ``ofs_stale*``).

    Parameters
    ----------
    joint : AuditResult
        The result of :func:`joint_audit`.

    Returns
    -------
    GlueValues
        Glue key -> value: hypotheses searched and values explained, the slip that with a never-cleared
        two-slot buffer explains every printed value (sensor, printed and corrected reading), the stale
        buffer value, the support-degree α that would reproduce Table 3 after the correction, and the
        corrected table's total error (°C).

    References
    ----------
    * Yang G. N., Feng X. F., Fan L. J. (2012). Multi-sensor data fusion algorithm based on optimal fusion set.
    """
    from fusion import readings as rd
    from fusion.book import audit as _book_audit
    from fusion.book.tables import rounded

    _audit_result(joint, "joint", explained=True)
    T1 = data.YANG2012_TABLE1.values
    t2, t3 = data.YANG2012_TABLE2.columns, data.YANG2012_TABLE3.columns
    TRUE = data.YANG2012_TRUE_VALUE
    fe = full_explanation(joint)
    fix = fe[0]
    fixed_t1 = T1.copy()
    fixed_t1[fix.sensor - 1, fix.obs - 1] = fix.value
    clean = explain(fix, "buffer, clean start", fe[2])
    stale = {k: (2 * t2["optimal_set"][k - 1] - T1[:, k - 1][three_reading_set(fixed_t1[:, k - 1])]).round(4)
             for k in (1, 5, 6)}
    full_orders = joint.full[(joint.full["program"] == "buffer, clean start") & (joint.full[SET_RULE] == fe[2])]
    fix_roots = _book_audit.parameters_matching(fixed_t1[:, fix.obs - 1], t3["reliability"][fix.obs - 1], "support_degree",
                                          "alpha", 1e-6, 1e3)
    t = joint.table
    return {
        "ofs_joint_n_values": 26, "ofs_joint_n_hyp": f"{joint.n_hypotheses:,}",
        "ofs_joint_best_correct": int(t.loc[t["program"] == "correct", VALUES_EXPLAINED].max()),
        "ofs_joint_best_printed": int(t.loc[t[CORRECTION_CLASS] == "none", VALUES_EXPLAINED].max()),
        "ofs_joint_n_full": len(joint.full), "ofs_joint_n_full_corrections": joint.full["correction"].nunique(),
        "ofs_fix_value": fix.value, "ofs_fix_orig": float(T1[fix.sensor - 1, fix.obs - 1]),
        "ofs_stale": float(stale[1][0]), "ofs_stale_same": bool(all(np.allclose(v, stale[1]) for v in stale.values())),
        "ofs_joint_clean_score": int(26 - np.sum(np.abs(clean.iloc[:, [1, 3, 5, 7]].to_numpy() - clean.iloc[:, [0, 2, 4, 6]].to_numpy()) > 1.5e-4)),
        "ofs_joint_clean_orders": len(full_orders),
        "ofs_obs6_pub": float(t2["optimal_set"][5]),
        "ofs_fix_alpha": ", ".join(f"{a:.3g}" for a in fix_roots) or "none",
        "ofs_obs5_pub_rel": float(t3["reliability"][4]),
        "ofs_fix_total_ofs": rounded(np.abs(rd.fuse_epochs(fixed_t1.T, "optimal_fusion_set").values - TRUE).sum()),
    }
