"""Chapter recipes: table assembly, figure recipes and claims ledgers of each chapter, one module per chapter."""
