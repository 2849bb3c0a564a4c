"""The repository whose decks, builds and stored results the scripts use."""
import os

_PARENT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The package lives at the repository's root; an installed copy takes SABLE_REPO, else the current folder.
REPO = os.environ.get('SABLE_REPO') or (_PARENT if os.path.isdir(os.path.join(_PARENT, 'input_scripts')) else os.getcwd())


def repo_path(*parts):
    """A path inside the repository."""
    return os.path.join(REPO, *parts)
