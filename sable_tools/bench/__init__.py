"""bench scripts."""
