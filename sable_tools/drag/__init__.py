"""drag scripts."""
