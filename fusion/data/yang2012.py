"""Numbers published by Yang, Feng & Fan (2012), Journal of Software 23(S1).

Typed from the source text exactly as printed, including the values the chapter shows
to be inconsistent.
"""

from __future__ import annotations

from fusion._frozen import constant
from fusion.data._published import Published
from fusion.data._published import read_only as _ro

__all__ = [
    "YANG2012_TABLE1",
    "YANG2012_TABLE2",
    "YANG2012_TABLE3",
    "YANG2012_TOTALS",
    "YANG2012_TRUE_VALUE",
    "YANG2012_FAILURE",
]


# --- Yang, Feng & Fan (2012), Journal of Software 23(S1):134-140 -----------

#: Table 1: three thermocouples (rows) x six observations (columns) of a furnace set to
#: 900 °C. The readings come from the source's reference [11] (Sun & Jing 2005).
YANG2012_TABLE1 = Published(
    values=_ro(
        [
            [899.5, 905.3, 901.9, 900.6, 899.9, 899.4],
            [898.3, 875.9, 888.1, 886.2, 907.5, 904.4],
            [896.7, 906.8, 898.2, 904.0, 896.4, 891.6],
        ]
    ),
    source="yang2012optimal",
    where="Table 1 (p. 138)",
    unit="°C",
    note="rows: sensors 1-3; columns: observations 1-6; true value 900 °C",
)

# The optimal-set column and its errors, printed identically in Tables 2 and 3.
_OPTIMAL_SET = _ro([901.1500, 906.0500, 900.0500, 902.3000, 900.2000, 901.7000])
_OPTIMAL_SET_ERR = _ro([1.1500, 6.0500, 0.0500, 2.3000, 0.2000, 1.7000])

#: Table 2: optimal-set fusion vs the arithmetic mean, with absolute errors.
YANG2012_TABLE2 = Published(
    values=_OPTIMAL_SET,
    source="yang2012optimal",
    where="Table 2 (p. 138)",
    unit="°C",
    note="values: optimal-set fusion per observation 1-6",
    columns={
        "optimal_set": _OPTIMAL_SET,
        "optimal_set_abs_error": _OPTIMAL_SET_ERR,
        "mean": _ro([898.1667, 896.0000, 896.0667, 896.9333, 897.9333, 898.4667]),
        "mean_abs_error": _ro([1.8333, 4.0000, 3.9333, 3.0667, 2.0667, 1.5333]),
    },
)

#: Table 3: optimal-set fusion vs the support-degree ("reliability") fusion of ref. [11].
YANG2012_TABLE3 = Published(
    values=_ro([898.2414, 896.1270, 896.0571, 896.8645, 897.9197, 898.4814]),
    source="yang2012optimal",
    where="Table 3 (p. 138)",
    unit="°C",
    note="values: reliability fusion per observation 1-6 (optimal-set column as in Table 2)",
    columns={
        "optimal_set": _OPTIMAL_SET,
        "optimal_set_abs_error": _OPTIMAL_SET_ERR,
        "reliability": _ro([898.2414, 896.1270, 896.0571, 896.8645, 897.9197, 898.4814]),
        "reliability_abs_error": _ro([1.7586, 3.8730, 3.9429, 3.1355, 2.0803, 1.5186]),
    },
)

#: Total absolute errors over the six observations, printed in the text below Table 3.
YANG2012_TOTALS = Published(
    values=_ro([16.4333, 16.3089, 11.4500]),
    source="yang2012optimal",
    where="text after Table 3 (p. 138)",
    unit="°C",
    note="order: arithmetic mean, reliability (ref. [11]), optimal fusion set",
    columns={
        "mean": _ro([16.4333]),
        "reliability": _ro([16.3089]),
        "optimal_set": _ro([11.4500]),
    },
)

#: True furnace temperature of the Table 1 experiment and of the simulations (°C).
YANG2012_TRUE_VALUE = 900.0

#: Failure experiment of Figs. 3-4: sensors (1-based), first and last sample (1-based,
#: inclusive) and bias added to each failing sensor (°C).
YANG2012_FAILURE = constant({"sensors": (4, 10), "samples": (50, 80), "biases": (4.0, 8.0)})
