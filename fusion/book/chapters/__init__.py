"""Per-chapter bookkeeping for the book: table assembly, figure recipes, glue values and the claims of each source. Algorithms and scenarios never import this package."""
