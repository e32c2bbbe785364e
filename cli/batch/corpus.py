"""Corpus files: one sentence a line, as plain text or as a JSON object.

A corpus line is either plain text or a JSON object::

    {"text": "...", "category": "te", "expect": {...}}

``expect`` is a subset of the parse JSON (docs/language.md §5, plus ``hold``,
``reading`` and ``cue``); a motion may also name the ``clip`` its time-table row
plays (``"clip": "stand_up"``, met by stand_up or a captured variant such as
stand_up_14_32; the line is then planned, ``lines.check``); ``{"error": "words"}``
expects the line to be refused with a message containing the words. Blank lines and lines starting
with ``#`` are skipped; an item keeps its line number in the file.
"""
from __future__ import annotations

import hashlib
import io
import json
from dataclasses import dataclass

from text2anim.core.inputs import read_input


class CorpusError(ValueError):
    """A corpus file that cannot be read as text lines or JSON lines."""

    user_facing = True


@dataclass(frozen=True, slots=True)
class Item:
    """One corpus line: its number in the file (1-based), the text, and what it should parse to."""

    line: int
    text: str
    category: str | None = None
    expect: dict | None = None


def text_hash(text: str) -> str:
    """The key a manifest record keeps of its text: 16 hex digits of SHA-256 of the UTF-8 bytes."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def load_corpus(path: str) -> list[Item]:
    """Every item of the corpus at ``path``, in file order; a malformed line raises :class:`CorpusError`."""
    try:
        text = read_input(path, "corpus", CorpusError).decode("utf-8")
    except UnicodeDecodeError:
        raise CorpusError(f"{path}: not UTF-8 text") from None
    items = []
    for n, raw in enumerate(io.StringIO(text, newline=None), 1):  # line numbers as a text file counts them
        line = raw.strip()
        if line and not line.startswith("#"):
            items.append(_parse_line(line, n, path))
    return items


def _parse_line(line: str, n: int, path: str) -> Item:
    if not line.startswith("{"):
        return Item(n, line)
    try:
        obj = json.loads(line)
    except json.JSONDecodeError as exc:
        raise CorpusError(f"{path}:{n}: not valid JSON: {exc.msg}") from None
    if not isinstance(obj, dict) or not isinstance(obj.get("text"), str):
        raise CorpusError(f'{path}:{n}: a JSON line needs a "text" string')
    expect = obj.get("expect")
    if expect is not None and not isinstance(expect, dict):
        raise CorpusError(f'{path}:{n}: "expect" must be an object')
    category = obj.get("category")
    return Item(n, obj["text"], None if category is None else str(category), expect)


def chunks(items: list[Item], size: int) -> list[list[Item]]:
    """``items`` cut into consecutive runs of at most ``size`` lines (the unit of work sent to a worker)."""
    return [items[i:i + size] for i in range(0, len(items), size)]
