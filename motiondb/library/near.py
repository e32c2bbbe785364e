"""Near-synonyms declared on built-in clips: verbs a clip already shows well enough, each with its reason.

``near.json`` (next to this file) maps a clip name (keyframed or captured, as
:func:`motiondb.library.builtin_clips` names them) to ``{verb: why}``: the verb
is added to that clip's synonyms, and ``why`` says why a native speaker would
accept the clip as that verb's animation (issue 14: grow coverage where a clip
already fits, each addition justified). Kept apart from the clips' own verb
lists so that the lists stay what each clip *is*, and the stretches stay
visible and argued.
"""
from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from text2anim.motiondb.types import ClipRecord

from .keyframes import ClipDataError

NEAR_FILE = Path(__file__).with_name("near.json")


def near_synonyms(path: Path = NEAR_FILE) -> dict[str, dict[str, str]]:
    """``{clip name: {verb: reason}}`` from ``path``; a verb without a reason is refused."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)["clips"]
    for name, verbs in data.items():
        for verb, why in verbs.items():
            if not verb or " " in verb or not str(why).strip():
                raise ClipDataError(f"{path.name}: {name}: near-synonym {verb!r} needs a verb and a reason")
    return data


def with_near_synonyms(records: list[ClipRecord], near: dict[str, dict[str, str]] | None = None) -> list[ClipRecord]:
    """``records`` with each named clip's near-synonyms appended to its verbs (after its own).

    Raises :class:`ClipDataError` naming a clip the file declares but ``records`` lacks (a
    renamed or removed clip must not silently drop its verbs)."""
    near = near_synonyms() if near is None else near
    names = {r.name for r in records}
    missing = sorted(set(near) - names)
    if missing:
        raise ClipDataError(f"{NEAR_FILE.name} names clips the library lacks: {', '.join(missing)}")
    out = []
    for r in records:
        extra = tuple(v for v in near.get(r.name, {}) if v not in r.verbs)
        out.append(replace(r, verbs=r.verbs + extra) if extra else r)
    return out
