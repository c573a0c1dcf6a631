"""Per-chapter helpers of the book: the studies, tables, figures and claims ledger of one chapter each (no algorithms)."""
