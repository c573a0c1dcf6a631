"""Per-chapter bookkeeping: table assembly, figure recipes and the claims of each chapter's source."""
