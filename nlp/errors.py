"""Errors of the nlp stage."""
from __future__ import annotations


class NLPError(ValueError):
    """A problem with the input text that the user can fix.

    ``user_facing`` tells the CLI dispatcher to print the message as one line
    (exit code 2) instead of a traceback.
    """

    user_facing = True
