"""The error of descriptions that cannot be made, read or used, and the command that learns a
praxicon folder again, which its messages name.

Both stand below every other praxicon module, so that the scores (the lowest layer that can
find a description unusable) raise the error every layer above raises.
"""

from __future__ import annotations

from psgs.errors import PSGSError

__all__ = ["DescriptionError", "REBUILD", "DAMAGED"]

#: The command that rebuilds a praxicon folder (named by every "other version" error).
REBUILD = "psgs praxicon build DATASET... -o FOLDER"
#: How a line about one damaged record ends (a build into the folder learns that one again).
DAMAGED = f"the record is damaged ('{REBUILD}' into the folder learns the action again)"


class DescriptionError(PSGSError, ValueError):
    """Descriptions that cannot be made, read or used (one line, naming what to do)."""


# praxicon.description's error (it imports it from below, so that the checks and the scores
# can raise it without importing that module back): named there in tracebacks and pickles
DescriptionError.__module__ = "praxicon.description"
