r"""Helpers for the book only: figure style registry, published-vs-reproduced tables, audits of published values. Algorithms never import this package.

Modules:

style
    One figure style for the whole book.
tables
    Tables that set published numbers beside recomputed ones.
audit
    Checks of published numbers: can a printed value come out of the stated data at all?
ledger
    The claims ledger: one record per checkable claim, status derived by rule.
glue
    Glue many values at once.
figures
    The book's figure rules, checked on every published figure.
recommend
    "Which method should I use?": recommendations tied to ledger records.
benchmarks
    Stored benchmark results with their date (cells that show them are not compared by nbval).
"""

from fusion.book.glue import glue_all
from fusion.book.ledger import (
    Alternative,
    Claim,
    Comparison,
    Ledger,
    Proposition,
    PublishedValues,
    STATUSES,
    Unverifiable,
)
from fusion.book.style import (
    METHOD_COLORS,
    METHOD_LABELS,
    use_book_style,
    new_figure,
    color,
)
from fusion.book.tables import (
    side_by_side,
    rounded,
)
from fusion.book.audit import *  # noqa: F403
from fusion.book.audit import __all__ as _audit_all
from fusion.book.benchmarks import (
    BenchmarkResult,
    load_benchmark,
)

__all__ = [
    *_audit_all,
    "glue_all", "Alternative", "Claim", "Comparison", "Ledger", "Proposition", "PublishedValues", "STATUSES",
    "Unverifiable", "METHOD_COLORS", "METHOD_LABELS", "use_book_style", "new_figure", "color", "side_by_side",
    "rounded", "BenchmarkResult", "load_benchmark",
]
