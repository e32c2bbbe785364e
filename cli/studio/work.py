"""A text into what the studio shows: the viewer page, the time table and the messages.

One animation at a time (the synthesis is CPU-bound; a newer text makes the page abort the older
request). The same text with the same database gives the same bytes, so the last few results are
kept: going back to a text, or appending to it, costs nothing for what was already made.
"""
from __future__ import annotations

import threading
from collections import OrderedDict
from dataclasses import dataclass

#: Longest text the studio animates (characters); the API's own limits apply too.
MAX_TEXT = 2000
#: Results kept (text -> payload).
CACHE = 32
#: What the page may download: format -> file suffix (``Animation.outputs``' keywords).
FORMATS = {"bvh": "bvh", "glb": "glb", "vrma": "vrma", "report": "json"}


@dataclass
class Studio:
    """The studio's state: its database (a :class:`motiondb.MotionDB`) and recent results."""

    db: object
    lock: threading.Lock
    cache: "OrderedDict[str, dict]"

    @classmethod
    def open(cls, db_url: str | None) -> "Studio":
        from text2anim.motiondb import MotionDB

        return cls(MotionDB.open(db_url), threading.Lock(), OrderedDict())

    def animate(self, text: str, edits: tuple = ()) -> dict:
        """``{"ok": True, "html", "table", "blends", "duration", "warnings"}`` for ``text`` with the time-table
        ``edits`` (:class:`text2anim.edits.Edit`), or ``{"ok": False, "error"}`` with the message the command
        line would print (never a traceback). Each table row carries its edit key (verb, nth), or None for
        what the scheduler added (a stop, an idle, a posture bridge)."""
        text = text.strip()
        if not text:
            return {"ok": False, "error": "type a sentence, e.g. 太郎は走って、ボールを蹴る。"}
        if len(text) > MAX_TEXT:
            return {"ok": False, "error": f"the text is {len(text)} characters long; the studio takes at most {MAX_TEXT}"}
        key = text + "\0" + repr(edits)
        with self.lock:
            hit = self.cache.get(key)
            if hit is not None:
                self.cache.move_to_end(key)
                return hit
            payload = self._make(text, edits)
            self.cache[key] = payload
            while len(self.cache) > CACHE:
                self.cache.popitem(last=False)
            return payload

    def _make(self, text: str, edits: tuple) -> dict:
        import text2anim
        from text2anim.cli.terminal import message
        from text2anim.edits import occurrences
        from text2anim.output.viewer import render_html

        try:
            anim = text2anim.animate(text, db=self.db, edits=edits)
        except Exception as exc:  # the stages' user errors carry user_facing; anything else is a bug to show
            if not getattr(exc, "user_facing", False) and not isinstance(exc, ValueError):
                raise
            return {"ok": False, "error": message(str(exc)), "unknown": unknown_verbs(text, exc)}
        keys = {i: list(k) for k, i in occurrences(anim.planned.analysis).items()}
        rows = [{"id": e.id, "actor": e.actor or "default", "verb": e.verb, "clip": e.clip, "method": e.method,
                 "start": round(e.start, 3), "end": round(e.end, 3), "body_part": e.body_part,
                 "key": keys.get(e.id)} for e in anim.table.elements]
        blends = [{"actor": s.actor, "start": round(s.start, 3), "end": round(s.end, 3), "part": s.part,
                   "label": s.label} for s in anim.spans() if s.kind == "blend"]
        return {"ok": True, "text": text, "html": render_html(anim.tracks(), anim.spans(), title=text),
                "notes": list(anim.planned.analysis.notes),
                "table": rows, "blends": blends, "warnings": list(anim.warnings),
                "duration": round(max((m.duration for m in anim.motions.values()), default=0.0), 3),
                "_anim": anim}

    def export(self, text: str, edits: tuple = (), fmt: str = "bvh") -> tuple[str, bytes] | None:
        """``(file name, bytes)`` of ``text``'s animation as ``fmt`` (:data:`FORMATS`: one file per actor
        for BVH, GLB and VRMA, zipped when there are several); None when it cannot be animated."""
        import io
        import tempfile
        import zipfile
        from pathlib import Path

        payload = self.animate(text, edits)
        if not payload["ok"]:
            return None
        with tempfile.TemporaryDirectory() as tmp:  # names only: nothing is written there
            files = payload["_anim"].outputs(**{fmt: Path(tmp) / f"animation.{FORMATS[fmt]}"})
        if len(files) == 1:
            ((path, data),) = files.items()
            return path.name, bytes(data)
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
            for path, data in sorted(files.items()):
                z.writestr(path.name, bytes(data))
        return "animation.zip", buf.getvalue()


def unknown_verbs(text: str, exc: Exception) -> list[dict]:
    """For an error naming verbs no clip has (``fallback.UnknownVerbsError``): each one's place in ``text``
    (``span``, characters), the database verbs nearest in meaning, the stand-in ``--fallback nearest`` plays
    (or None) and why; empty for any other error."""
    missing = getattr(exc, "missing", None)
    if not missing:
        return []
    from text2anim.nlp import analyze

    spans: dict[str, list[int]] = {}
    for m in analyze(text).motions:
        spans.setdefault(m.written or m.verb, list(m.span))
    return [{"written": w, "span": spans.get(w), "nearest": [v for v, _ in near], "standin": standin, "why": why}
            for w, near, standin, why in missing]
