"""The repository whose decks, builds and stored results the scripts use."""
import os

# The package lives at the repository's root; an installed copy is pointed at a checkout by SABLE_REPO.
REPO = os.environ.get('SABLE_REPO') or os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def repo_path(*parts):
    """A path inside the repository."""
    return os.path.join(REPO, *parts)
