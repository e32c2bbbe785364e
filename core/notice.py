"""What a stage tells its user (a warning, a refusal) as it is made: a kind, its figures, and the English sentence.

The command line prints :attr:`Notice.text`; a front end in another language (the studio's page, in Japanese
first) words the notice itself from its ``kind`` and ``params`` (``cli/studio/static/messages.json``:
``n_<kind>`` with ``{param}`` slots), so it never shows the English sentence or a command-line flag. The
kinds are documented where they are made (``limits``, ``edits``, ``manners``); ``params`` hold plain values
(strings and numbers: seconds, counts, verbs as written).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["Notice"]


@dataclass(frozen=True)
class Notice:
    """One warning or refusal: ``kind`` (what happened, e.g. ``limit_duration``), ``params`` (name -> value,
    sorted by name) and ``text``, the sentence in English for the command line."""

    kind: str
    text: str
    params: tuple[tuple[str, Any], ...] = ()

    @classmethod
    def of(cls, kind: str, text: str, **params: Any) -> Notice:
        """The notice of ``kind`` said as ``text``, with ``params`` (plain strings and numbers)."""
        return cls(kind, text, tuple(sorted(params.items())))

    def __str__(self) -> str:
        return self.text

    def to_dict(self) -> dict[str, Any]:
        """``{"kind", "params": {...}, "text"}`` (JSON)."""
        return {"kind": self.kind, "params": dict(self.params), "text": self.text}
