"""campaign3 scripts."""
