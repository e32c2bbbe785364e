"""A studio project file (``.t2a.json``): the text and what the studio's user chose for it, read back.

The studio saves the page's work as one JSON object (docs/project.md)::

    {"format": "text2anim-project", "version": 1, "text": "太郎は走って、ボールを蹴る。",
     "edits": [{"verb": "蹴る", "nth": 0, "shift": 0.4}], "fallback": "strict"}

``text2anim project.t2a.json -o out.bvh`` animates it as the studio did (the same bytes as the page's BVH
export, on the same database). A file of another version, or no project at all, is refused with one line.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

#: The ``format`` field every project carries.
FORMAT = "text2anim-project"
#: The one version this text2anim reads (and the studio writes).
VERSION = 1
#: A project file's suffix (what makes ``text2anim FILE`` read a project rather than a text).
SUFFIX = ".t2a.json"
class ProjectError(ValueError):
    """A file that is no project this text2anim reads; the message says which and why, in one line."""

    user_facing = True


@dataclass(frozen=True)
class Project:
    """What a project asks for: ``text``, time-table ``edits`` (:class:`text2anim.edits.Edit`) and ``fallback``
    (``strict`` or ``nearest``)."""

    text: str
    edits: tuple
    fallback: str = "strict"


def is_project(arg: str) -> bool:
    """``arg`` names a project file (by its suffix) rather than being the text itself."""
    return arg.lower().endswith(SUFFIX) and "\n" not in arg


def read_project(path: str | Path) -> Project:
    """The project in ``path``; :class:`ProjectError` for anything else (not JSON, another format or version,
    a field of the wrong kind)."""
    from text2anim.core.inputs import read_input
    from text2anim.edits import Edit, EditError

    path = Path(path)
    # a regular file of at most 1 MB (a text of 2,000 characters and 200 edits fit many times over): a FIFO
    # named *.t2a.json is refused at once instead of hanging the command
    raw = read_input(path, "project", ProjectError)
    try:
        data = json.loads(raw.decode("utf-8"))
    except (ValueError, RecursionError):
        raise ProjectError(f"{path.name}: not a text2anim project (not JSON)") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ProjectError(f"{path.name}: not a text2anim project (no \"format\": \"{FORMAT}\")")
    if data.get("version") != VERSION:
        raise ProjectError(f"{path.name}: project version {str(data.get('version'))[:20]} is not one this text2anim "
                           f"reads (version {VERSION}); a newer text2anim may read it")
    text, edits, fallback = data.get("text"), data.get("edits", []), data.get("fallback", "strict")
    if not isinstance(text, str) or not isinstance(edits, list) or not all(isinstance(e, dict) for e in edits):
        raise ProjectError(f"{path.name}: \"text\" must be a string and \"edits\" a list of objects")
    if fallback not in ("strict", "nearest"):
        raise ProjectError(f"{path.name}: \"fallback\" must be strict or nearest")
    try:
        return Project(text, tuple(Edit.from_dict(e) for e in edits), fallback)
    except EditError as exc:
        raise ProjectError(f"{path.name}: {exc}") from None
