r"""Which method should I use? Recommendations tied to the claims ledger.

Each :class:`Recommendation` names a task, the method to use, what to avoid, and the ledger
records (:class:`Evidence`) it rests on, each with the statuses under which the recommendation
stands. The book renders them (``.. fusion-recommendations::`` on the "Which method should I use?"
page) with the records' current status and numbers, and :func:`check` (run by the build and by
``tests/test_recommend.py``) fails when a cited record is missing or its status has moved outside
the expected set: a recommendation cannot outlive its evidence. The wording holds no numbers; the
numbers shown beside it come from the ledger.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from fusion.book.ledger import STATUSES
from fusion._limits import MAX_WORK, work
from fusion._validation import iterable, one_of, text, text_fields, texts
from fusion._shown import shown

__all__ = ["Evidence", "Recommendation", "RECOMMENDATIONS", "check"]


@dataclass(frozen=True)
class Evidence:
    """A ledger record a recommendation rests on.

    A wrong type (a list for a tuple, a number for a string) is a :class:`TypeError`, a wrong value of the
    right type a :class:`ValueError`, both naming the field.

    Parameters
    ----------
    claim : str
        Ledger record id (e.g. ``"yang-fig4-vs-mean"``).
    expect : tuple of str
        Statuses (from :data:`fusion.book.ledger.STATUSES`) under which the recommendation stands.
    role : str
        What the record shows for the recommendation, in a few words (no numbers).
    """

    claim: str
    expect: tuple[str, ...]
    role: str

    def __post_init__(self) -> None:
        # a wrong type (a list for the tuple of a frozen record, a number for a string) is a TypeError; a wrong
        # value of the right type a ValueError (issue 35)
        if not isinstance(self.claim, str):
            raise TypeError(f"claim must be a ledger record id (a string), got {type(self.claim).__name__}")
        text_fields(self, "claim", "role")  # plain str copies (rule 19): kept, compared and printed as their text
        if not self.claim.strip():  # a blank id names no record, as a blank role says nothing
            raise ValueError("claim must be a ledger record id (a non-empty string)")
        if not self.role.strip():
            raise ValueError("role must be a non-empty string")
        if not isinstance(self.expect, tuple):
            raise TypeError(f"expect must be a tuple of ledger statuses, got {type(self.expect).__name__}")
        object.__setattr__(self, "expect", texts(self.expect, "expect"))
        bad = [s for s in self.expect if s not in STATUSES]
        if not self.expect or bad:
            raise ValueError(f"expect must be a non-empty tuple of ledger statuses, got {shown(self.expect)}")


@dataclass(frozen=True)
class Recommendation:
    """One task: what to use, what to avoid, and the evidence.

    Parameters
    ----------
    task : str
        The situation, as a reader would describe it.
    use : str
        The recommended method (and the information it needs).
    why : str
        Why, in words (the numbers come from the evidence).
    avoid : str
        What not to use.
    avoid_why : str
        Why not.
    evidence : tuple of Evidence
        Ledger records the recommendation rests on.
    chapters : tuple of str
        Docnames of the chapters that hold the studies.
    """

    task: str
    use: str
    why: str
    avoid: str
    avoid_why: str
    evidence: tuple[Evidence, ...]
    chapters: tuple[str, ...]

    def __post_init__(self) -> None:
        text_fields(self, "task", "use", "why", "avoid", "avoid_why")  # plain str copies (rule 19)
        for name in ("task", "use", "why", "avoid", "avoid_why"):
            value = getattr(self, name)
            if not value.strip():
                raise ValueError(f"{name} must be a non-empty string")
        if not isinstance(self.evidence, tuple) or not all(isinstance(e, Evidence) for e in self.evidence):
            raise TypeError(f"evidence must be a tuple of Evidence, got {type(self.evidence).__name__}")
        if not self.evidence:
            raise ValueError("evidence must be a non-empty tuple of Evidence")
        if not isinstance(self.chapters, tuple) or not all(isinstance(c, str) for c in self.chapters):
            raise TypeError(f"chapters must be a tuple of docnames (str), got {type(self.chapters).__name__}")
        object.__setattr__(self, "chapters", texts(self.chapters, "chapters"))


_R = ("reproduced", "reproduced under stated assumptions")
_NOT = ("contradicted", "not reproduced")

#: The recommendations, one per task, in book order.
RECOMMENDATIONS: tuple[Recommendation, ...] = (
    Recommendation(
        task="Simultaneous readings of one quantity, some of which may be faulty",
        use="Reject outliers, then average the rest: the optimal fusion set of Yang et al. (2012) or a "
            "standard robust rule (median ± 3 MAD rejection then the mean, Tukey's biweight); the plain "
            "median does as well or better without faults and on the source's own table. With "
            "known, unequal noise levels and no faults, the inverse-variance mean. The comparison with "
            "the robust rules comes from the chapter's fair study, which has no ledger record of its own.",
        why="With failed sensors the mean is pulled by the faults while rejection drops them; without "
            "faults the fusion set discards valid readings, and whether it beats the mean depends on "
            "how unequal the sensors are.",
        avoid="The plain mean when a sensor can fail, and the lecture's adaptive weights with its uncentred "
              "variance estimates (σ̂² = R_pp − R̄_p, from the same readings).",
        avoid_why="One faulty sensor moves the mean by its bias over n; the lecture's uncentred estimates can be "
                  "negative or near zero, which gives the fused value unbounded errors. Centred (covariance) "
                  "estimates are another matter: over a record of readings they track a fault that starts within "
                  "it, but a sensor offset from the first sample looks healthy to them, and there the agreement "
                  "methods win (chapter 2's benchmark); a single snapshot leaves no variance to estimate.",
        evidence=(
            Evidence("yang-fig4-vs-mean", _R, "optimal fusion set vs mean with two failed sensors"),
            Evidence("yang-fig4-robust", _R, "the failure costs the fusion set less than the mean"),
            Evidence("yang-def3-keeps-valid", _NOT, "the set keeps every valid reading"),
            Evidence("yang-median-total", _R, "the plain median beats the fusion set on source Table 1"),
            Evidence("yang-fig2-vs-mean", _R + ("not distinguishable", "contradicted"),
                     "no fault: fusion set vs mean (sign depends on the noise spread)"),
            Evidence("lec-awf-estimated", ("not distinguishable", "contradicted"),
                     "the lecture's estimated-variance weights vs the mean"),
        ),
        chapters=("notebooks/01_optimal_fusion_set", "notebooks/02_lecture_weighting"),
    ),
    Recommendation(
        task="Measurements with correlated noise and a known covariance",
        use="The generalised least-squares (Markov) estimate, computed by a Cholesky or LDLᵀ solve.",
        why="The decorrelated pseudo-measurements of the lecture give exactly the same estimate.",
        avoid="Ignoring the correlation (inverse-variance weights from the diagonal only), unless the covariance "
              "is estimated from only a few tens of calibration vectors.",
        avoid_why="The fused variance it reports is wrong, and when the sensors are coupled unequally to the "
                  "common noise its error is several times larger; with equal couplings it costs little, and with "
                  "a covariance estimated from 10-30 vectors ignoring the correlation can be the better choice.",
        evidence=(
            Evidence("lec-ldl-equals-gls", _R, "LDLᵀ pseudo-measurements equal GLS"),
            Evidence("lec-correlation-matters", _R + ("not distinguishable",),
                     "GLS vs ignoring the correlation: within the margin with equal couplings, up to an order of "
                     "magnitude otherwise, and overconfident always"),
        ),
        chapters=("notebooks/04_lecture_biased_correlated",),
    ),
    Recommendation(
        task="Two track estimates whose cross-correlation is unknown",
        use="Covariance intersection with the weight chosen by a bounded scalar minimiser (or split "
            "CI when part of each error is known to be independent). When the cross-covariance can be "
            "computed, as in Wang & Tang's own two-filter setting, use Bar-Shalom–Campo without feedback, "
            "or the lossless information fusion (the centralised filter) with feedback.",
        why="Both report a covariance that is not smaller than the true error's; the weight is a "
            "one-dimensional convex problem, solved to machine precision in microseconds. Split CI must not "
            "feed its own split back to the local filters: it then reports too small a covariance.",
        avoid="The printed fusion equations of Wang & Tang (2024) and a fruit-fly search for the weight.",
        avoid_why="The printed eqs. 11-12 report a covariance smaller than the error when the weight "
                  "exceeds 1/2 (NEES above the dimension), and the fruit fly spends thousands of evaluations on a "
                  "one-dimensional convex problem that a closed form or a bounded search solves exactly.",
        evidence=(
            Evidence("ci-eq11-12-consistent", _NOT, "the printed eqs. 11-12 are overconfident when ω > 1/2"),
            Evidence("ci-consistent", _R, "CI is consistent without the cross-covariance"),
            Evidence("ci-fig5-foa-optimum", ("not distinguishable", "contradicted"),
                     "FOA's published weight is no better than the grid's on the source's sensors (the objective "
                     "is flat there)"),
            Evidence("ci-eq2-state-update", _NOT, "the printed state update is wrong"),
        ),
        chapters=("notebooks/05_covariance_intersection",),
    ),
    Recommendation(
        task="Distributed fusion of particle-filter (non-Gaussian) posteriors with unknown common information",
        use="CI with uniform weights on moment-matched Gaussians, or Chernoff fusion with uniform "
            "exponents; both need only each node's particles. Where a node's posterior is far from "
            "Gaussian, fusing mixtures can pay.",
        why="Optimising the exponents by the patent's swarm costs far more and is not measurably "
            "more accurate on the scenarios we ran.",
        avoid="The naive product of the local posteriors.",
        avoid_why="Overconfident: it treats errors sharing process noise and prior as independent. Its estimate "
                  "is not what fails (in the chapter's tracking study it is more accurate than the patent's "
                  "method); its covariance is.",
        evidence=(
            Evidence("chf-gain-uniform", ("not distinguishable", "contradicted"),
                     "optimised vs uniform exponents"),
            Evidence("chf-gain-ci", ("not distinguishable", "contradicted"), "mixtures vs moment-matched CI"),
            Evidence("chf-gain-local", _R, "fusion beats a node's own filter"),
            Evidence("chf-double-count", _R, "the naive product is overconfident over the whole track"),
            Evidence("chf-premise-double-count", _R, "with feedback the naive product is overconfident"),
            Evidence("chf-premise-mixture", _R, "mixtures beat Gaussian summaries where a posterior is far from Gaussian"),
        ),
        chapters=("notebooks/06_chernoff_fusion",),
    ),
    Recommendation(
        task="Asynchronous sensors to be registered to common instants",
        use="Offline, or with a lag of one sample: a fixed-lag Kalman smoother, or a quadratic fitted by "
            "least squares to the last few samples and the next one; with the whole record, a Kalman (RTS) "
            "smoother. In real time, filter each sensor and predict its state to the common instant (Shi et al. "
            "2023, §3). Give every filter a driving noise that allows for the target's manoeuvres.",
        why="With the same samples the fixed-lag smoother and the local quadratic fit beat the look-ahead "
            "'improved' method, and under an unmodelled change of acceleration they lose the least of the "
            "methods run; filtering removes measurement noise that interpolation passes through.",
        avoid="A quadratic fitted to every past sample (a growing-memory fit), a filter tuned with too little "
              "driving noise, and a straight-line least-squares fit on an accelerating target.",
        avoid_why="Under an unmodelled change of acceleration the growing-memory quadratic fit and the filters "
                  "with the default tuning (the §3 prediction, the RTS smoother, the 'improved' method) do "
                  "worse than two-point interpolation, by up to two orders of magnitude; an unmodelled "
                  "time-stamp latency biases every method and should be compensated.",
        evidence=(
            Evidence("shi-kalman-s3", _R, "Kalman prediction vs two-point extrapolation (real time)"),
            Evidence("shi-improved-fair", _NOT, "the improved method vs a fixed-lag smoother with the same samples"),
            Evidence("shi-improved", _R, "the improved method vs two-point interpolation, on its model"),
            Evidence("shi-interp-vs-ls", _R, "interpolation vs a straight-line least-squares fit"),
        ),
        chapters=("notebooks/07_time_registration",),
    ),
)


#: Units of work (``fusion._limits.work``, about 10 ns each) of one record and of one evidence item of a recommendation
#: that :func:`check` reads: 1.6 us and 0.42 us measured (CPU time, minimum of 3, 100,000 of each, shared machine), so
#: the budget's edge (5e6 records, or 2e7 evidence items) checks in about 8 CPU-s; the book checks about 150 records.
CHECK_RECORD, CHECK_EVIDENCE = 200, 50


def check(records: Iterable[Mapping[str, object]],
          recommendations: Iterable[Recommendation] = RECOMMENDATIONS) -> list[str]:
    """Problems with the recommendations given the ledger (empty when every one stands).

    Parameters
    ----------
    records : iterable of mapping
        Ledger records (as in ``book/ledger/*.json``), each with ``id`` and ``status``.
    recommendations : iterable of Recommendation
        Defaults to :data:`RECOMMENDATIONS`.

    Returns
    -------
    list of str
        One message per cited record that is missing or whose status is outside ``expect``.

    Raises
    ------
    TypeError
        ``records`` or ``recommendations`` not an iterable (a str is not), a record whose ``id`` is not a string, or
        ``recommendations`` holding something other than :class:`Recommendation`.
    ValueError
        A record without ``id`` and ``status``, a status outside :data:`fusion.book.ledger.STATUSES`, or two
        records with one id (naming ``records``); more than 5e6 items in ``records`` (what the work budget checks)
        or ``10**7`` in ``recommendations`` (rule 9: an endless generator is refused, not read for ever), or more
        records and evidence items than the work budget checks in about 10 CPU-s (``CHECK_RECORD``,
        ``CHECK_EVIDENCE`` units each), naming them.
    """
    # an iterable's items read at most once past what the work budget checks (fuzz 40b C8: an endless generator was
    # read for ever; review 18: up to 1e7 + 1 records, 2 GB of the caller's dicts, were read before the refusal)
    records = iterable(records, "records", MAX_WORK // CHECK_RECORD,
                       f"the work budget checks at most {MAX_WORK // CHECK_RECORD:,} records, CHECK_RECORD units each")
    recommendations = iterable(recommendations, "recommendations")   # rule 9's ceiling
    if not all(isinstance(r, Recommendation) for r in recommendations):
        raise TypeError("recommendations must hold Recommendation objects")
    work((CHECK_RECORD * len(records) + CHECK_EVIDENCE * sum(len(r.evidence) for r in recommendations),),
         "records and recommendations (their records and evidence items)")   # before the records are checked
    if not all(isinstance(r, Mapping) and "id" in r and "status" in r for r in records):
        raise ValueError("records must be mappings with 'id' and 'status' (as in book/ledger/*.json)")
    odd_id = [r["id"] for r in records if not isinstance(r["id"], str)]
    if odd_id:  # a ledger id is text: str() would make 5 and '5' one record
        raise TypeError(f"records: every id must be a string (as in book/ledger/*.json), got {shown(odd_id[0])}")
    ids = [text(r["id"], f"records[{i}]['id']") for i, r in enumerate(records)]  # plain str copies (rule 19)
    repeated = sorted(i for i, n in Counter(ids).items() if n > 1)  # linear: a count per id was quadratic (fuzz 22a Q1)
    if repeated:  # one id, two statuses: the check would keep the last without a word
        raise ValueError(f"records must not repeat an id, got {shown(repeated)} more than once")
    odd = [r["status"] for r in records if not isinstance(r["status"], str)]
    if odd:
        raise ValueError(f"records: every status must be one of {STATUSES}, got {shown(odd[0])}")
    statuses = [one_of(r["status"], STATUSES, f"records[{i}]['status']") for i, r in enumerate(records)]
    status = dict(zip(ids, statuses))  # the plain texts (rule 19): an Enum's str() is its name
    problems: list[str] = []
    for rec in recommendations:
        for ev in rec.evidence:
            if ev.claim not in status:
                problems.append(f"{rec.task!r}: ledger record {ev.claim!r} does not exist")
            elif status[ev.claim] not in ev.expect:
                problems.append(f"{rec.task!r}: {ev.claim!r} is now {status[ev.claim]!r}, "
                                f"the recommendation needs one of {list(ev.expect)}")
    return problems
