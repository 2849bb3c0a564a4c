"""mohr scripts."""
