"""What each built-in clip's body does, as WordNet verb synsets (``actions.json`` beside this file).

The synsets become the clip's ``actions`` (:class:`motiondb.types.ClipDescription`): a clip
stands in for a verb it does not list only when one of the verb's senses is one of them or
directly a kind of one (``api/fallback.py``). A captured variant (``walk_02_01``) takes its
base name's entry; a clip without one stands in for nothing.
"""
from __future__ import annotations

import json
import re
from dataclasses import replace
from pathlib import Path

from text2anim.motiondb.types import ClipRecord

from .keyframes import ClipDataError

ACTIONS_FILE = Path(__file__).with_name("actions.json")


def clip_actions(path: Path = ACTIONS_FILE) -> dict[str, tuple[str, ...]]:
    """``{clip name: synset offsets}`` from ``path`` (entries are ``offset:lemma``; the lemma is for people)."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)["clips"]
    out = {}
    for name, actions in data.items():
        offsets = tuple(str(a).split(":")[0] for a in actions)
        if not offsets or not all(re.fullmatch(r"[0-9]{8}", o) for o in offsets):
            raise ClipDataError(f"{path.name}: {name}: actions must be 'offset:lemma' WordNet verb synsets")
        out[name] = offsets
    return out


def with_actions(records: list[ClipRecord], actions: dict[str, tuple[str, ...]] | None = None) -> list[ClipRecord]:
    """``records`` with their actions from ``actions.json`` (a variant ``name_NN_NN`` by its base name).

    Raises :class:`ClipDataError` naming an entry no clip has (a renamed clip must not lose it)."""
    actions = clip_actions() if actions is None else actions
    bases = {r.name: re.sub(r"(_\d+)+$", "", r.name) for r in records}
    missing = sorted(set(actions) - set(bases) - set(bases.values()))
    if missing:
        raise ClipDataError(f"{ACTIONS_FILE.name} names clips the library lacks: {', '.join(missing)}")
    return [replace(r, actions=actions.get(r.name, actions.get(bases[r.name], ()))) for r in records]
