"""Errors of the motion database.

Every class here is a ``ValueError`` and *user facing* (``user_facing = True``): the command line
prints its message as one line on stderr and exits with status 2, without a
traceback. Messages name the thing at fault (the file, the clip, the verb,
the database URL with its password hidden).
"""
from __future__ import annotations

from collections.abc import Callable, Sequence


class DBError(ValueError):
    """A database problem the user can fix: a bad URL, an unreachable server, bad input."""

    user_facing = True


class SchemaVersionError(DBError):
    """The database was written by another (newer) version of text2anim."""


class ClipValidationError(DBError):
    """A clip (or a file to import) that cannot be stored; nothing was changed."""


class ClipExistsError(ClipValidationError):
    """A clip of that name is already in the database."""


class UnknownClipError(DBError, LookupError):
    """No clip of that name; ``suggestions`` lists the nearest names."""

    def __init__(self, name: str, suggestions: list[str] | tuple[str, ...] = ()):
        self.name = name
        self.suggestions = tuple(suggestions)
        msg = f"no clip named {name!r} in the database"
        if self.suggestions:
            msg += "; nearest: " + ", ".join(self.suggestions)
        super().__init__(msg)

    def __str__(self) -> str:  # LookupError would quote the message like a KeyError
        return self.args[0]


class UnknownCharacterError(DBError, LookupError):
    """No character of that name; ``known`` lists the characters there are."""

    def __init__(self, name: str, known: list[str] | tuple[str, ...] = ()):
        self.name = name
        self.known = tuple(known)
        msg = f"no character named {name!r} in the database"
        msg += "; characters: " + ", ".join(self.known) if self.known else " (it has none yet)"
        super().__init__(msg)

    def __str__(self) -> str:
        return self.args[0]


class UnknownVerbError(DBError, LookupError):
    """No clip is retrieved by that verb (lemma, synonym or reading).

    Attributes:
        verb: the verb asked for.
        suggestions: ``(lemma, reading)`` pairs of the nearest verbs the database
            has, nearest first (compared by katakana reading).

    ``suggestions`` may be given as a function that finds them: they are then found when first read (the
    message reads them), not when the error is made. A plan asks the database for a verb, its phrase and its
    spellings, catches most of the errors and words its own message (:mod:`text2anim.fallback`): comparing
    each with every verb of the database was half the cost of a refused sentence.
    """

    def __init__(self, verb: str, suggestions: Sequence[tuple[str, str]] | Callable[[], Sequence[tuple[str, str]]] = (),
                 n_verbs: int | None = None):
        self.verb = verb
        self.n_verbs = n_verbs
        if callable(suggestions):
            self._find = suggestions
        else:
            self.suggestions = tuple(suggestions)
        super().__init__(verb)

    def __getattr__(self, name: str):
        if name == "suggestions" and "_find" in self.__dict__:  # found on first read
            self.suggestions = tuple(self.__dict__.pop("_find")())
            return self.suggestions
        raise AttributeError(name)

    def __reduce__(self):  # pickled with its suggestions found (a function is not sent)
        return UnknownVerbError, (self.verb, self.suggestions, self.n_verbs)

    def __str__(self) -> str:
        msg = f"no clip in the motion database for the verb {self.verb!r}"
        if self.suggestions:
            msg += "; nearest verbs: " + ", ".join(f"{lemma} ({reading})" for lemma, reading in self.suggestions)
        elif self.n_verbs == 0:
            msg += "; the database has no verbs yet (add clips with `text2anim db import`)"
        else:
            msg += "; see `text2anim db verbs` for the verbs it has"
        return msg


class SeedWarning(UserWarning):
    """Some built-in clips were not stored (their names or the ``default`` character were taken)."""
