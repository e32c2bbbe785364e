"""``DIR/manifest.jsonl``: one record per corpus line, appended as results arrive.

The file is the batch's memory. Each record is flushed as soon as it is
written, so a crash, a killed worker or a Ctrl-C loses no finished line. When
a batch starts on a folder that has a manifest, the records still valid for
this corpus and these options (same line, same text hash, same options key,
not ``failed``) are kept and their lines skipped; the others (a changed text,
other options, a failure, a half-written last line) are dropped, so every
line is in the manifest exactly once.
"""
from __future__ import annotations

import json
import os

from text2anim.core.atomic import atomic_write_bytes

from .corpus import Item, text_hash

NAME = "manifest.jsonl"


def dumps(record: dict) -> str:
    return json.dumps(record, ensure_ascii=False, separators=(",", ":"))


class Manifest:
    """The manifest of one output folder, open for appending.

    Attributes:
        path: the file.
        kept: the records of an earlier run that still hold, in file order.
    """

    def __init__(self, path: str, kept: list[dict]):
        self.path = path
        self.kept = kept
        self._done = {r["line"] for r in kept}
        self._fh = open(path, "a", encoding="utf-8")

    @classmethod
    def open(cls, out_dir: str, items: list[Item], options_key: str) -> "Manifest":
        """Open (or start) ``out_dir/manifest.jsonl`` for ``items`` run with options ``options_key``."""
        path = os.path.join(out_dir, NAME)
        hashes = {it.line: text_hash(it.text) for it in items}
        kept, dropped = [], 0
        if os.path.exists(path):
            seen: set[int] = set()
            with open(path, encoding="utf-8") as fh:
                for raw in fh:
                    rec = _record(raw)
                    if rec is None or not _still_valid(rec, hashes, options_key) or rec["line"] in seen:
                        dropped += 1
                        continue
                    seen.add(rec["line"])
                    kept.append(rec)
            if dropped or not _ends_with_newline(path):  # rewrite without them, all at once
                atomic_write_bytes(path, "".join(dumps(r) + "\n" for r in kept).encode("utf-8"))
        return cls(path, kept)

    def done(self, item: Item) -> bool:
        """Whether an earlier run already finished ``item`` (its record was kept)."""
        return item.line in self._done

    def write(self, record: dict) -> None:
        self._fh.write(dumps(record) + "\n")
        self._fh.flush()

    def close(self) -> None:
        self._fh.close()

    def __enter__(self) -> "Manifest":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _record(raw: str) -> dict | None:
    try:
        rec = json.loads(raw)
    except json.JSONDecodeError:
        return None  # the half-written last line of a killed run
    return rec if isinstance(rec, dict) and isinstance(rec.get("line"), int) else None


def _ends_with_newline(path: str) -> bool:
    with open(path, "rb") as fh:
        fh.seek(0, os.SEEK_END)
        if fh.tell() == 0:
            return True
        fh.seek(-1, os.SEEK_END)
        return fh.read(1) == b"\n"


def _still_valid(rec: dict, hashes: dict[int, str], options_key: str) -> bool:
    return (hashes.get(rec["line"]) == rec.get("text_hash") and rec.get("options") == options_key
            and rec.get("status") != "failed")


def read(out_dir: str) -> list[dict]:
    """Every record of ``out_dir``'s manifest, in file order."""
    with open(os.path.join(out_dir, NAME), encoding="utf-8") as fh:
        return [json.loads(raw) for raw in fh]
