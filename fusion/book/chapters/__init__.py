"""Per-chapter table assembly, figure recipes and claims (one module per chapter); notebooks call these."""
