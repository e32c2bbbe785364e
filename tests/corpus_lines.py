"""The corpora's JSON lines (tests/corpus/*.jsonl), read once per test module: their items, how many of each
class, and which texts are new against other corpora (a corpus written for an issue repeats none)."""
from __future__ import annotations

import json
from pathlib import Path

FOLDER = Path(__file__).resolve().parent / "corpus"


def items(name: str) -> list[dict]:
    """The JSON lines of ``tests/corpus/<name>`` (comments and blank lines left out)."""
    return [json.loads(x) for x in (FOLDER / name).read_text(encoding="utf-8").splitlines() if x.startswith("{")]


def short_classes(lines: list[dict], wanted: dict[str, int]) -> dict[str, int]:
    """The classes of ``wanted`` that have fewer lines than asked, with how many they have."""
    counts = {c: sum(it.get("category") == c for it in lines) for c in wanted}
    return {c: n for c, n in counts.items() if n < wanted[c]}


def repeated(lines: list[dict], *others: str) -> list[str]:
    """The texts of ``lines`` that one of the corpora ``others`` (file names) already has."""
    text = "".join((FOLDER / o).read_text(encoding="utf-8") for o in others)
    return [it["text"] for it in lines if f'"text": {json.dumps(it["text"], ensure_ascii=False)}' in text]
