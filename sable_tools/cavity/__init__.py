"""cavity scripts."""
