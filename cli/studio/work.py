"""A text into what the studio shows: the viewer page, the time table and the messages.

One animation at a time (the synthesis is CPU-bound; a newer text makes the page abort the older
request). The same text with the same database gives the same bytes, so recent results are kept, within
:data:`CACHE_BYTES` (what the page is sent: the viewer's data, the top view, the table): going back to a
text costs nothing. Only the latest :class:`Animation` itself is kept (for its export; a long text's
is ~40 MB); exporting another text animates it again.

**Draft first.** A new text is answered at once with a *draft*: the same analysis and clips joined by
crossfades (``blend="crossfade"``, ~15 ms of synthesis for two motions instead of the optimal blend's
110-180 ms), marked ``"draft": true``; the page shows it and asks for the finished animation (the optimal
blend, :data:`FINISHED`) straight after, which replaces it in place. The finished one goes on from the draft's
planned stages (the analysis, the time table, the clips: the same for both blends), so only its synthesis is
new work. Exports and the project always use the finished animation; a text whose finished animation is kept
is answered with it, never with a draft.
"""
from __future__ import annotations

import re
import tempfile
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

from text2anim.core.cancel import Cancelled, cancellable, checkpoint

if TYPE_CHECKING:
    from text2anim.export import ExportOptions
    from text2anim.pipeline import Work

#: Longest text the studio animates (characters); the API's own limits apply too.
MAX_TEXT = 2000
#: Results kept (text -> payload), at most this many ...
CACHE = 32
#: ... and at most this many bytes of them (200 requests of long texts took the studio to 1.65 GB).
CACHE_BYTES = 64 * 2**20
#: What the page may download: format -> file suffix (``Animation.outputs``' keywords).
FORMATS = {"bvh": "bvh", "glb": "glb", "vrma": "vrma", "report": "json"}
#: The blends of a draft and of the finished animation (``text2anim.animate(blend=...)``).
DRAFT, FINISHED = "crossfade", "optimal"
#: The last pipeline stage a draft and its finished animation share (the synthesis comes after it).
SHARED_STAGES = "manner"


@dataclass
class Studio:
    """The studio's state: the user's library (a :class:`motiondb.MotionDB`), the database the animations are
    made from (``db``: the library, or once a BVH was dropped a private copy of it holding the session's clips
    too), recent results, and the user's character when one was dropped (a ``.glb``/``.vrm``); the copy and the
    character are kept in ``folder``, a private temporary folder."""

    library: object
    lock: threading.Lock
    cache: "OrderedDict[str, dict]"
    folder: "tempfile.TemporaryDirectory[str]"
    rig: Path | None = None
    character: ExportOptions | None = None  # the rig's options: the file read, its joints placed and soles found once
    latest: tuple[str, object] | None = None  # (cache key, Animation) of the latest text animated
    planned: tuple[str, Work] | None = None  # (cache key, pipeline.Work up to SHARED_STAGES) of the latest draft
    session: object | None = None  # the library's copy with the dropped clips, once there are any
    dropped: set[str] = field(default_factory=set)  # the clips dropped in this session
    shelf: threading.Lock = field(default_factory=threading.Lock)  # the cache's own (``lock`` is the work's)

    @classmethod
    def open(cls, db_url: str | None) -> "Studio":
        from text2anim.motiondb import MotionDB

        return cls(MotionDB.open(db_url), threading.Lock(), OrderedDict(), tempfile.TemporaryDirectory(prefix="t2a-studio-"))

    @property
    def db(self):
        """The database animations are made from: the session's when a clip was dropped, else the library."""
        return self.session if self.session is not None else self.library

    def mine(self) -> list[dict]:
        """The user's own clips in the library (every clip not built in): name, verbs, seconds."""
        return [{"name": c.name, "verbs": list(c.verbs), "seconds": round(c.duration, 2)}
                for c in self.library.clips() if not c.source.startswith("builtin")]  # type: ignore[attr-defined]

    def keep(self, clip: str) -> dict:
        """Add the session's dropped ``clip`` to the user's library (the explicit step after a drop)."""
        with self.lock:
            if self.session is None or clip not in self.dropped:
                return {"ok": False, "error": f"no clip {clip[:60]!r} was dropped in this session"}
            if clip in {c.name for c in self.library.clips()}:  # type: ignore[attr-defined]
                return {"ok": False, "error": f"your library already has a clip named {clip[:60]!r}"}
            self.library.add([self.session.record(clip)])  # type: ignore[attr-defined]
        return {"ok": True, "clip": clip}

    def rename(self, clip: str, name: str) -> dict:
        """Give the user's ``clip`` another name (letters, digits, ``_`` and ``-``), in the library and the session."""
        from dataclasses import replace

        new = re.sub(r"[^\w-]+", "_", name)[:60].strip("_")
        if not new:
            return {"ok": False, "error": "a clip's name needs a letter or a digit"}
        with self.lock:
            if (refused := self._not_mine(clip)) is not None:
                return refused
            if new in {c.name for c in self.library.clips()}:  # type: ignore[attr-defined]
                return {"ok": False, "error": f"a clip is already named {new!r}"}
            for db in self._databases():
                if clip in {c.name for c in db.clips()}:
                    db.add([replace(db.record(clip), name=new)])
                    db.remove(clip)
            self._forget()
        return {"ok": True, "clip": new}

    def remove(self, clip: str) -> dict:
        """Remove the user's ``clip`` from the library (and the session): built-in clips cannot be removed."""
        with self.lock:
            if (refused := self._not_mine(clip)) is not None:
                return refused
            for db in self._databases():
                if clip in {c.name for c in db.clips()}:
                    db.remove(clip)
            self._forget()
        return {"ok": True}

    def clip_page(self, clip: str) -> dict:
        """The viewer page of one of the user's clips (a preview), or the refusal."""
        from text2anim.output.viewer import render_html

        with self.lock:
            if (refused := self._not_mine(clip)) is not None:
                return refused
            info, motion = self.library.info(clip), self.library.load(clip)  # type: ignore[attr-defined]
        return {"ok": True, "html": framed(render_html(motion, title=clip, props_code=True)), "verbs": list(info.verbs)}

    def _not_mine(self, clip: str) -> dict | None:
        """The refusal of a ``clip`` that is not one of the user's own (:meth:`mine`), else None."""
        if clip not in {c["name"] for c in self.mine()}:
            return {"ok": False, "error": f"{clip[:60]!r} is not one of your clips"}
        return None

    def _databases(self) -> list:
        return [self.library] + ([self.session] if self.session is not None else [])

    def _session_db(self):
        """The session's database, made on the first drop: a copy of the library (1.4 s for 151 clips)."""
        if self.session is None:
            from text2anim.motiondb import MotionDB

            records = [self.library.record(c.name) for c in self.library.clips()]  # type: ignore[attr-defined]
            self.session = MotionDB.open(Path(self.folder.name) / "session.sqlite", seed=lambda: records)
        return self.session

    def verbs(self, query: str, limit: int = 50) -> list[dict]:
        """The database's verbs whose spelling or reading holds ``query`` (all when empty), with their clip counts."""
        q = query.strip()
        return [{"verb": v.lemma, "reading": v.reading, "clips": v.clips} for v in self.db.verbs()
                if not q or q in v.lemma or q in v.reading][:limit]

    def import_bvh(self, data: bytes, filename: str, verb: str, cyclic: bool) -> dict:
        """Store a dropped BVH file as a clip of ``verb`` for this session (the user's library gets it only
        through :meth:`keep`), through ``db import``'s own reader and checks (the same limits); ``{"ok",
        "clip"}`` or ``{"ok": False, "error"}``. The name comes from ``filename``'s letters and digits only;
        nothing the client sends becomes a path."""
        from text2anim.cli.terminal import message
        from text2anim.motiondb import ImportOptions

        name = re.sub(r"[^0-9A-Za-z_-]+", "_", Path(filename).stem)[:60].strip("_") or "dropped"
        path = Path(self.folder.name) / "upload.bvh"
        with self.lock:
            path.write_bytes(data)
            try:
                session = self._session_db()
                taken = {c.name for c in session.clips()}
                name = next(n for n in (name if k == 1 else f"{name}_{k}" for k in range(1, len(taken) + 2))
                            if n not in taken)  # a dropped walk.bvh never replaces the built-in walk
                (info,) = session.import_bvh([path], ImportOptions((verb,), cyclic=cyclic, names=(name,)))
                self.dropped.add(info.name)
            except Exception as exc:
                if not getattr(exc, "user_facing", False) and not isinstance(exc, ValueError):
                    raise
                return {"ok": False, "error": message(str(exc).replace(str(path), filename))}
            finally:
                path.unlink(missing_ok=True)
            self._forget()  # the database changed: what was made may play other clips now
        return {"ok": True, "clip": info.name, "verbs": list(info.verbs), "frames": info.frames,
                "seconds": round(info.duration, 3)}

    def clear_rig(self) -> None:
        """Back to the built-in character."""
        with self.lock:
            if self.rig is not None:
                self.rig.unlink(missing_ok=True)
            self.rig = self.character = None
            self._forget()

    def set_rig(self, data: bytes, suffix: str) -> dict:
        """Keep a dropped ``.glb``/``.vrm`` character for what follows (read as ``--rig`` reads it: refused
        with the reader's message when it is no human rig); ``{"ok", "joints"}`` or ``{"ok": False, "error"}``."""
        from text2anim.cli.terminal import message
        from text2anim.export import ExportOptions

        path = Path(self.folder.name) / f"checking{suffix}"
        with self.lock:
            path.write_bytes(data)
            try:  # the whole --rig check (its joints placed as a human's), before it is kept
                checked = ExportOptions(rig=path).check(glb=True).skeleton
                joints = len(checked.names) if checked is not None else 0
            except Exception as exc:
                if not getattr(exc, "user_facing", False) and not isinstance(exc, ValueError):
                    raise
                path.unlink(missing_ok=True)
                return {"ok": False, "error": message(str(exc).replace(str(path), f"the dropped {suffix} file"))}
            kept = path.with_name(f"character{suffix}")
            if self.rig is not None:
                self.rig.unlink(missing_ok=True)
            self.rig = path.replace(kept)
            self.character = ExportOptions(rig=self.rig)
            self._forget()
        return {"ok": True, "joints": joints}

    def _forget(self) -> None:
        """Drop every result (the database or the character changed)."""
        with self.shelf:
            self.cache.clear()
        self.latest = self.planned = None

    def close(self) -> None:
        """Close the session's database and remove the private folder (it, a dropped character, an upload)."""
        if self.session is not None:
            self.session.close()  # type: ignore[attr-defined]
        self.folder.cleanup()

    def animate(self, text: str, edits: tuple = (), fallback: str = "strict",
                cancelled: Callable[[], bool] = lambda: False, draft: bool = False) -> dict:
        """``{"ok": True, "draft", "view", "top", "table", "blends", "duration", "warnings", "notices", "fallbacks"}`` for
        ``text`` with the time-table ``edits`` (:class:`text2anim.edits.Edit`) and ``fallback`` (``strict``, or ``nearest``: a
        verb no clip has played by its stand-in), or ``{"ok": False, "error", "code", "notice"}`` with the message
        the command line would print (never a traceback), its kind (:func:`error_code`) and, when the error has
        one, its :class:`core.notice.Notice`, which the page words in its own language (as ``notices``, the
        ``warnings``' own). ``cancelled()`` true (the page went away: a newer text) stops the work between the
        pipeline's stages, or before it starts once the animation before it is done: ``{"ok": False, "code":
        "cancelled"}``, nothing kept. Each table row carries its edit key (verb, nth), or None for
        what the scheduler added (a stop, an idle, a posture bridge). ``view`` is the viewer's document
        (:func:`output.viewer.viewer_data`, which the page's viewer loads in place; :func:`viewer_page` makes the
        page itself), ``top`` the scene seen from above (:meth:`output.topview.TopView.to_dict`), which the page
        draws beside the animation. ``draft``: answer a text whose finished animation is not kept with a draft
        (module docstring; never with a character dropped, whose view is the finished export)."""
        text = text.strip()
        if not text:
            return {"ok": False, "code": "empty", "error": "type a sentence, e.g. 太郎は走って、ボールを蹴る。"}
        if len(text) > MAX_TEXT:
            return {"ok": False, "code": "too_long", "max": MAX_TEXT,
                    "error": f"the text is {len(text)} characters long; the studio takes at most {MAX_TEXT}"}
        key = self._key(text, edits, fallback)
        draft = draft and self.character is None
        keys = (key, key + "\0draft") if draft else (key,)
        hit = self._cached(*keys)  # a text seen before is answered at once, even while another one is being made
        if hit is not None:
            return hit
        with self.lock:
            hit = self._cached(*keys)  # made while this request waited
            if hit is not None:
                return hit
            try:
                payload = self._make(text, edits, fallback, cancelled, key, draft)
            except Cancelled:
                return {"ok": False, "code": "cancelled", "error": "the page asked for another text"}
            anim = payload.pop("_anim", None)
            if anim is not None and not draft:
                self.latest = (key, anim)
            payload["_bytes"] = _size(payload)
            with self.shelf:
                self.cache[keys[-1]] = payload
                while len(self.cache) > 1 and (len(self.cache) > CACHE  # the newest is kept whatever its size
                                               or sum(p["_bytes"] for p in self.cache.values()) > CACHE_BYTES):
                    self.cache.popitem(last=False)
            return payload

    def _cached(self, *keys: str) -> dict | None:
        """The first of ``keys`` kept (the finished animation's before the draft's), or None."""
        with self.shelf:
            for key in keys:
                hit = self.cache.get(key)
                if hit is not None:
                    self.cache.move_to_end(key)
                    return hit
            return None

    def _key(self, text: str, edits: tuple, fallback: str = "strict") -> str:
        return text.strip() + "\0" + repr(edits) + "\0" + fallback + "\0" + str(self.rig)

    def animation(self, text: str, edits: tuple = (), fallback: str = "strict"):
        """The :class:`Animation` of ``text`` (the latest one kept, else made again), or None when it
        cannot be animated."""
        payload = self.animate(text, edits, fallback)
        if not payload["ok"]:
            return None
        key = self._key(text, edits, fallback)
        with self.lock:
            if self.latest is not None and self.latest[0] == key:
                return self.latest[1]
            with self.shelf:
                self.cache.pop(key, None)  # made again: the same bytes, and kept as the latest
        self.animate(text, edits, fallback)
        with self.lock:
            return self.latest[1] if self.latest is not None and self.latest[0] == key else None

    def _make(self, text: str, edits: tuple, fallback: str, cancelled: Callable[[], bool] = lambda: False,
              key: str = "", draft: bool = False) -> dict:
        from text2anim.cli.terminal import message
        from text2anim.edits import occurrences
        from text2anim.output.topview import top_view
        from text2anim.output.viewer import viewer_data

        try:
            anim = self._animation(text, edits, fallback, cancelled, key, draft)
            keys = {i: list(k) for k, i in occurrences(anim.planned.analysis).items()}
            tracks, props = anim.tracks(), anim.props()
            if self.character is not None:  # the user's character: its own skeleton and proportions
                rig = self.character
                tracks, props = anim.exported_motions(rig, units=False), anim.exported_props(rig)
        except Exception as exc:  # the stages' user errors carry user_facing; anything else is a bug to show
            if not getattr(exc, "user_facing", False) and not isinstance(exc, ValueError):
                raise
            notice = getattr(exc, "notice", None)  # a LimitError's, an EditError's: what the page words
            return {"ok": False, "error": message(str(exc)), "code": error_code(exc),
                    "unknown": unknown_verbs(text, exc), **({"notice": notice.to_dict()} if notice is not None else {})}
        rows = [{"id": e.id, "actor": e.actor or "default", "verb": e.verb, "clip": e.clip, "method": e.method,
                 "start": round(e.start, 3), "end": round(e.end, 3), "body_part": e.body_part,
                 "key": keys.get(e.id), "manner": e.manner.to_dict() if e.manner else None}
                for e in anim.table.elements]
        blends = [{"actor": s.actor, "start": round(s.start, 3), "end": round(s.end, 3), "part": s.part,
                   "label": s.label} for s in anim.spans() if s.kind == "blend"]
        return {"ok": True, "text": text, "draft": draft, "view": viewer_data(tracks, anim.spans(), title=text, props=props),
                "top": top_view(tracks, anim.spans(), props).to_dict(),
                "rig": self.rig is not None,
                "notes": list(anim.planned.analysis.notes),
                "table": rows, "blends": blends, "warnings": list(anim.warnings),
                "notices": [n.to_dict() for n in anim.notices],
                "fallbacks": [{"written": f.written, "used": f.used} for f in anim.planned.fallbacks],
                "duration": round(max((m.duration for m in anim.motions.values()), default=0.0), 3),
                "_anim": anim}

    def _animation(self, text: str, edits: tuple, fallback: str, cancelled: Callable[[], bool], key: str = "",
                   draft: bool = False):
        """``text2anim.animate(text, edits=edits, fallback=fallback, blend=DRAFT if draft else FINISHED)`` on the
        studio's database, stage by stage (:mod:`text2anim.pipeline`, as ``text2anim compare`` runs it), raising
        :class:`Cancelled` between two stages or two joins when ``cancelled()``: an abandoned text stops there
        instead of delaying the next one. The finished animation of the latest draft's ``key`` goes on from the
        draft's stages up to :data:`SHARED_STAGES`."""
        from dataclasses import replace

        from text2anim import limits
        from text2anim.pipeline import NAMES, Request, Work, animation, run

        limits.check_options(text, self.db, 30.0, limits.MAX_SECONDS, fallback=fallback)
        blend = DRAFT if draft else FINISHED
        work, done = Work(Request(text, fallback=fallback, edits=tuple(edits), blend=blend), self.db), None
        if not draft and self.planned is not None and self.planned[0] == key:
            work, done = replace(self.planned[1], request=work.request), SHARED_STAGES
        with cancellable(cancelled):  # and inside synthesis, between two joins (core.cancel)
            for name in NAMES[NAMES.index(done) + 1 if done else 0:]:
                checkpoint()
                work, done = run(work, after=done, until=name), name
                if draft and name == SHARED_STAGES:
                    self.planned = (key, work)
        return animation(work)

    def export(self, text: str, edits: tuple = (), fmt: str = "bvh", fallback: str = "strict") -> tuple[str, bytes] | None:
        """``(file name, bytes)`` of ``text``'s animation as ``fmt`` (:data:`FORMATS`: one file per actor
        for BVH, GLB and VRMA, zipped when there are several); None when it cannot be animated."""
        import io
        import zipfile

        anim = self.animation(text, edits, fallback)
        if anim is None:
            return None
        export = self.character if fmt in ("bvh", "glb", "vrma") else None
        with tempfile.TemporaryDirectory() as tmp:  # names only: nothing is written there
            files = anim.outputs(**{fmt: Path(tmp) / f"animation.{FORMATS[fmt]}"}, export=export)
        if len(files) == 1:
            ((path, data),) = files.items()
            return path.name, bytes(data)
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
            for path, data in sorted(files.items()):
                z.writestr(path.name, bytes(data))
        return "animation.zip", buf.getvalue()


#: What the studio changes in the viewer page it frames: the page draws the one (editable) time table itself,
#: and words the viewer's controls in its own language (studio.js), with the studio's font for their glyphs
#: and for the names of the animations loaded in place later (the viewer embeds only those of its own page):
#: the face ``t2a-studio``, which the page hands over by the bridge (the frame's opaque origin cannot fetch it:
#: the studio refuses the ``Origin: null`` such a fetch carries).
FRAMED_CSS = ("<style>#timeline-wrap { display: none; }\n"
              ':root, #help, #controls label { font-family: "t2a-jp", "t2a-studio", system-ui, sans-serif; }</style>')
#: The framed page's own policy, beside the one it inherits from the studio's page (``srcdoc``): its scripts
#: by their hashes only (an element that slipped into the page would not run), styles and fonts inline, and no
#: request of any kind (the viewer needs none: its data, fonts and icon are in the page or come by the bridge).
FRAMED_POLICY = ("default-src 'none'; script-src {scripts}; style-src 'unsafe-inline'; font-src data:; img-src data:; "
                 "base-uri 'none'; form-action 'none'")


def viewer_page(payload: dict) -> str:
    """The viewer page of an answer of :meth:`Studio.animate` as the studio frames it: the page loads it once,
    then hands the viewer every later answer's ``view`` in place (so it can show things whichever it had)."""
    from text2anim.output.viewer import viewer_page as page

    return framed(page(payload["view"], props_code=True))


def framed(page: str) -> str:
    """The viewer page as the studio frames it: :data:`FRAMED_CSS`, the bridge the page talks to it through
    (``static/viewer_bridge.js``: the frame is sandboxed without ``allow-same-origin``) and
    :data:`FRAMED_POLICY` as a ``<meta>``, first in its head."""
    page = page.replace("</head>", FRAMED_CSS + "</head>", 1)
    end = page.rfind("</body>")
    page = page[:end] + f"<script>\n{_bridge()}</script>\n" + page[end:]
    policy = FRAMED_POLICY.format(scripts=" ".join(_script_hashes(page)))
    return page.replace("<head>", f'<head>\n<meta http-equiv="Content-Security-Policy" content="{policy}">', 1)


@lru_cache(maxsize=1)
def _bridge() -> str:
    from importlib import resources

    text = resources.files(__package__).joinpath("static").joinpath("viewer_bridge.js").read_text(encoding="utf-8")
    if "</script" in text.lower():  # pragma: no cover - guards edits of the bridge
        raise RuntimeError("viewer_bridge.js must not contain '</script'")
    return text


def _script_hashes(page: str) -> list[str]:
    """The CSP sources (``'sha256-...'``) of the page's inline scripts (``<script>`` without attributes: the
    data's ``type="application/json"`` element is never run), hashed as the browser hashes them: its parser
    reads every line break as a line feed."""
    import base64
    import hashlib

    sources = []
    for body in re.findall(r"<script>(.*?)</script>", page, re.S):
        text = body.replace("\r\n", "\n").replace("\r", "\n")
        sources.append(f"'sha256-{base64.b64encode(hashlib.sha256(text.encode('utf-8')).digest()).decode('ascii')}'")
    return sources


def _size(payload: dict) -> int:
    """Bytes a result holds, about: its strings, the viewer's data (most of it) and 100 bytes a row."""
    import json

    return sum(len(v) for v in payload.values() if isinstance(v, str)) + len(json.dumps(payload.get("view", ""))) + 100 * (
        len(payload.get("table", ())) + len(payload.get("blends", ())) + len(str(payload.get("top", ""))) // 100)


def error_code(exc: Exception) -> str:
    """What kind of error ``exc`` is, for the page to say in its own words: ``unknown`` (a verb no clip has),
    ``no_motion`` (the analyser read no action), ``limit`` (a duration or count over the limits), ``edit`` (a
    time-table edit that cannot apply) or ``other``."""
    from text2anim.edits import EditError
    from text2anim.limits import LimitError
    from text2anim.nlp.errors import NLPError

    if getattr(exc, "missing", None):
        return "unknown"
    for kind, code in ((EditError, "edit"), (LimitError, "limit"), (NLPError, "no_motion")):
        if isinstance(exc, kind):
            return code
    return "other"


def unknown_verbs(text: str, exc: Exception) -> list[dict]:
    """For an error naming verbs no clip has (``fallback.UnknownVerbsError``): each one's place in ``text``
    (``span``, characters), the database verbs nearest in meaning, the stand-in ``--fallback nearest`` plays
    (or None) and why; empty for any other error."""
    missing = getattr(exc, "missing", None)
    if not missing:
        return []
    from text2anim.nlp import analyze
    from text2anim.phrase_sense import asked

    spans: dict[str, list[int]] = {}
    for m in analyze(text).motions:
        spans.setdefault(asked(m), list(m.span))  # as the error names it: 足を上げる, not 上げる
    return [{"written": w, "span": spans.get(w), "nearest": [v for v, _ in near], "standin": standin, "why": why}
            for w, near, standin, why in missing]
