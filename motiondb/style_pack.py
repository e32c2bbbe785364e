"""Style packs: a motion dataset the user downloaded, imported with its styles mapped to ours.

One pack is known, ``bandai-namco``: the Bandai Namco Research Motion Dataset (1 and 2), BVH files named
``dataset-N_CONTENT_STYLE_NNN.bvh`` (``dataset-1_walk_sad_001.bvh``) anywhere under the folder given. Its
licence (CC BY-NC-ND 4.0) lets a user use it, not us ship it: nothing of it is in this package, and
:data:`NOTICE` is said on every import. ``bandai_namco.json`` maps its content labels to verbs and its
style labels to :data:`core.styles.STYLES`; a file whose content or style has no entry is left out and
counted, never guessed. Every group of files of one content and style is imported as
``db import --verb ... --style ...`` would, on the pack's own character (their skeleton is the dataset's;
the clips are retargeted onto it as any import is).
"""
from __future__ import annotations

import json
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from .errors import ClipValidationError

DATA = Path(__file__).with_name("bandai_namco.json")
PACKS = ("bandai-namco",)
#: Said on every import of the pack (its licence and attribution, README *Data and credits*).
NOTICE = ("Bandai Namco Research Motion Dataset, (c) 2022 Bandai Namco Research Inc., CC BY-NC-ND 4.0 "
          "(non-commercial use, attribution, no redistribution of adapted copies): imported into your database "
          "for your own use; text2anim ships none of it")
_NAME = re.compile(r"^dataset-(\d+)_(.+)_([a-z-]+)_(\d+)\.bvh$", re.IGNORECASE)


@dataclass(frozen=True)
class PackFile:
    """One file of a pack: its path, clip name, content and style labels, and what they map to."""

    path: Path
    name: str
    content: str
    label: str
    verbs: tuple[str, ...]
    cyclic: bool
    style: str | None


@dataclass(frozen=True)
class PackPlan:
    """The files of a pack folder to import, and those left out: ``(file, why)``."""

    files: tuple[PackFile, ...]
    left_out: tuple[tuple[Path, str], ...] = field(default=())

    def groups(self) -> dict[tuple[tuple[str, ...], bool, str | None], list[PackFile]]:
        """The files by (verbs, cyclic, style): each group is one import."""
        out: dict[tuple[tuple[str, ...], bool, str | None], list[PackFile]] = {}
        for f in self.files:
            out.setdefault((f.verbs, f.cyclic, f.style), []).append(f)
        return out


@lru_cache(maxsize=1)
def _tables() -> tuple[dict[str, tuple[tuple[str, ...], bool]], dict[str, str | None]]:
    data = json.loads(DATA.read_text(encoding="utf-8"))
    return ({k: (tuple(v[0]), bool(v[1])) for k, v in data["contents"].items()}, dict(data["styles"]))


def plan_pack(pack: str, folder: str | Path) -> PackPlan:
    """The files of ``pack`` under ``folder`` (recursively, sorted) with what each maps to; raises
    :class:`ClipValidationError` for an unknown pack, a missing folder or one with no file of the pack."""
    if pack not in PACKS:
        raise ClipValidationError(f"unknown style pack {pack!r}; known: {', '.join(PACKS)}")
    root = Path(folder)
    if not root.is_dir():
        raise ClipValidationError(f"{folder}: no such folder (the pack's files are read from a folder you downloaded)")
    contents, styles = _tables()
    files, left = [], []
    for path in sorted(root.rglob("*.bvh")):
        m = _NAME.match(path.name)
        if m is None:
            left.append((path, "not named dataset-N_CONTENT_STYLE_NNN.bvh"))
            continue
        n, content, label, number = m.group(1), m.group(2).lower(), m.group(3).lower(), m.group(4)
        if content not in contents:
            left.append((path, f"content {content} plays no verb of ours"))
        elif label not in styles:
            left.append((path, f"style {label} is none of ours"))
        else:
            verbs, cyclic = contents[content]
            files.append(PackFile(path, f"bn{n}_{content}_{label}_{number}", content, label, verbs, cyclic,
                                  styles[label]))
    if not files:
        raise ClipValidationError(f"{folder}: no file of the {pack} pack (dataset-N_CONTENT_STYLE_NNN.bvh) to import")
    return PackPlan(tuple(files), tuple(left))


def import_pack(db, pack: str, folder: str | Path, *, character: str = "bandai-namco", replace: bool = False,
                progress: Callable | None = None, notify: Callable | None = None) -> tuple[list, PackPlan]:
    """Import ``pack`` from ``folder`` into ``db`` (a :class:`motiondb.MotionDB`): ``(clips stored, plan)``.
    Each group of one content and style is one all-or-nothing import."""
    from .bvh_import import ImportOptions

    plan = plan_pack(pack, folder)
    stored = []
    for (verbs, cyclic, style), files in plan.groups().items():
        options = ImportOptions(verbs=verbs, character=character, cyclic=cyclic, style=style, replace=replace,
                                names=tuple(f.name for f in files))
        stored += db.import_bvh([f.path for f in files], options, progress=progress, notify=notify)
    return stored, plan
