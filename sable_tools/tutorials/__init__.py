"""tutorials scripts."""
