"""The studio's web application (Starlette): the page, its assets, and three JSON/file endpoints.

- ``GET /`` the page (``/?text=…`` opens it with that text animated: a link to share);
- ``GET /static/NAME`` one of the page's own files, ``GET /static/vendor/...`` the vendored three.js files
  (fixed lists: no path comes from the client);
- ``POST /api/animate`` ``{"text", "edits", "fallback", "draft", "page"}`` -> the viewer's data and the time
  table (:mod:`.work`); ``edits`` are the timeline's (:class:`text2anim.edits.Edit` as JSON: verb, nth, shift,
  duration, method); ``draft: true`` lets a new text be answered with a draft first (:mod:`.work`), ``page:
  true`` adds the viewer page itself (``html``: the page has none yet to load the data into);
- ``POST /api/export`` ``{"text", "edits", "format"}`` -> the animation as ``bvh`` (default), ``glb``, ``vrma``
  or the ``report`` (a zip of one file per actor when there are several);
- ``GET /api/verbs?q=`` the library's verbs holding ``q``; ``POST /api/import`` a dropped BVH (its bytes,
  ``X-Verb`` the verb it shows) read as ``db import`` reads it, for this session only; ``POST /api/rig`` a
  dropped ``.glb``/``.vrm`` character the animation is shown and exported on, as ``--rig`` does;
- the user's own clips: ``GET /api/library`` lists them, ``POST /api/library/keep`` ``{"clip"}`` adds a clip
  dropped in this session, ``/rename`` ``{"clip", "name"}`` and ``/remove`` ``{"clip"}`` change them, ``POST
  /api/clip`` ``{"clip"}`` is one's viewer page (a preview);
- ``GET /static/font/jp.woff`` the Japanese font for what the user types (:mod:`.page`).

Requests are bounded: a body of at most :data:`MAX_BODY` bytes (a dropped file :data:`MAX_UPLOAD`, at most
:data:`MAX_UPLOADS` at once) received within :data:`BODY_TIMEOUT` seconds, a text of at most
``work.MAX_TEXT`` characters, the API's own limits on what a text may ask for, and :data:`TIMEOUT` seconds
of work. Every malformed request is a 4xx with one line (``{"ok": false, "error"}``), never a 500.
:class:`.guard.SameOrigin` refuses other hosts and origins, state-changing requests without the session's
token, and framing by other pages.
"""
from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from importlib import resources

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from .guard import SameOrigin, new_token, own_hosts
from .page import FONT_URL, full_font
from .page import html as served_page
from .work import FORMATS, Studio, viewer_page

#: Largest request body (bytes).
MAX_BODY = 64 * 1024
#: Seconds a request may work before the page is told to try a shorter text.
TIMEOUT = 60.0
#: Seconds a request's body may take to arrive (a client that sends it a byte at a time is cut off).
BODY_TIMEOUT = 30.0
#: Dropped files received at once (each up to :data:`MAX_UPLOAD` bytes held in memory).
MAX_UPLOADS = 2
#: Texts waiting for or in the one animation at a time; more are told the studio is busy (429) rather than
#: queued for minutes (the page itself has one request in flight: a newer text aborts the older one).
MAX_PENDING = 4
#: Seconds between two looks at whether a request's client is still there (its work stops when it is not).
CANCEL_POLL = 0.02
#: The page's own files: name -> content type.
ASSETS = {"studio.js": "text/javascript; charset=utf-8", "studio3d.js": "text/javascript; charset=utf-8",
          "topview.js": "text/javascript; charset=utf-8", "viewer_link.js": "text/javascript; charset=utf-8",
          "studio.css": "text/css; charset=utf-8"}


def _vendored() -> dict[str, Path]:
    """``{relative path: file}`` of the vendored libraries' JavaScript (``static/vendor/``)."""
    root = Path(str(resources.files(__package__).joinpath("static").joinpath("vendor")))
    return {p.relative_to(root).as_posix(): p for p in root.rglob("*.js")}


def _asset(name: str) -> str:
    return resources.files(__package__).joinpath("static").joinpath(name).read_text(encoding="utf-8")


#: Largest file dropped on the page (bytes): a BVH to import, a GLB/VRM character.
MAX_UPLOAD = 30 * 1024 * 1024
#: Most time-table edits a request may carry.
MAX_EDITS = 200


def _refused(status: int, error: str, notice: dict | None = None) -> JSONResponse:
    """``{"ok": false, "error"}``, with the ``notice`` (:class:`core.notice.Notice` as JSON) the page words when
    there is one."""
    return JSONResponse({"ok": False, "error": error, **({"notice": notice} if notice else {})}, status_code=status)


async def _body(request: Request, limit: int, what: str) -> bytes | Response:
    """The request's body, at most ``limit`` bytes within :data:`BODY_TIMEOUT` seconds, or the refusal."""
    async def read() -> bytes | Response:
        parts, size = [], 0
        async for chunk in request.stream():
            size += len(chunk)
            if size > limit:
                return _refused(413, f"{what} is over {limit // 1024 if limit < 2**20 else limit // 2**20} "
                                     f"{'KB' if limit < 2**20 else 'MB'}")
            parts.append(chunk)
        return b"".join(parts)
    try:
        return await asyncio.wait_for(read(), BODY_TIMEOUT)
    except asyncio.TimeoutError:
        return _refused(408, f"{what} did not arrive within {BODY_TIMEOUT:g} s")


@dataclass(frozen=True)
class Asked:
    """What a request for a text asks: the text, the time-table edits, the format of an export, the fallback
    (``strict`` or ``nearest``), whether a draft may answer first and whether the viewer page is wanted too."""

    text: str
    edits: tuple
    format: str = "bvh"
    fallback: str = "strict"
    draft: bool = False
    page: bool = False


async def _text_of(request: Request) -> Asked | Response:
    """What a JSON request body ``{"text", "edits": [...], "format", "fallback", "draft", "page"}`` asks, or the
    response refusing it (every malformed body a 4xx: a list for a format, 20,000 nested brackets)."""
    from text2anim.edits import Edit

    data = await _json_of(request, '{"text": "..."}')
    if isinstance(data, Response):
        return data
    text, raw, fmt = data.get("text", ""), data.get("edits") or [], data.get("format", "bvh")
    if not isinstance(fmt, str) or fmt not in FORMATS:
        return _refused(400, f"format must be one of {', '.join(FORMATS)}")
    fallback = data.get("fallback", "strict")
    if fallback not in ("strict", "nearest"):
        return _refused(400, "fallback must be strict or nearest")
    draft, page = data.get("draft", False), data.get("page", False)
    if not isinstance(draft, bool) or not isinstance(page, bool):
        return _refused(400, "draft and page must be true or false")
    if not isinstance(text, str) or not isinstance(raw, list) or len(raw) > MAX_EDITS \
            or not all(isinstance(e, dict) for e in raw):
        return _refused(400, f"text must be a string and edits a list of at most {MAX_EDITS} objects")
    try:
        edits = tuple(Edit.from_dict(e) for e in raw)
    except (ValueError, TypeError, KeyError, AttributeError) as exc:  # EditError is a ValueError
        notice = getattr(exc, "notice", None)
        return _refused(400, f"edits: {_short(exc)}", notice.to_dict() if notice is not None else None)
    return Asked(text, edits, fmt, fallback, draft, page)


async def _json_of(request: Request, example: str) -> dict | Response:
    """The JSON object a request sends (as ``application/json``, within :data:`MAX_BODY`), or the refusal."""
    if request.headers.get("content-type", "").split(";")[0].strip().lower() != "application/json":
        return _refused(415, "the request must be sent as application/json")
    body = await _body(request, MAX_BODY, "the request")
    if isinstance(body, Response):
        return body
    try:
        data = json.loads(body or b"{}")
    except (ValueError, RecursionError):  # RecursionError: nesting deeper than the parser's stack
        return _refused(400, f"the request must be JSON: {example}")
    if not isinstance(data, dict):
        return _refused(400, f"the request must be a JSON object: {example}")
    return data


async def _clip_of(request: Request) -> tuple[str, str] | Response:
    """``(clip, name)`` of a library request ``{"clip", "name"}`` (``name`` only for a rename), or the refusal."""
    data = await _json_of(request, '{"clip": "..."}')
    if isinstance(data, Response):
        return data
    clip, name = data.get("clip"), data.get("name", "")
    if not isinstance(clip, str) or not clip or len(clip) > 200 or not isinstance(name, str) or len(name) > 200:
        return _refused(400, "clip (and name) must be strings of at most 200 characters")
    return clip, name


def _short(exc: BaseException) -> str:
    from text2anim.cli.terminal import message

    return message(str(exc).splitlines()[0] if str(exc) else type(exc).__name__, 200)


def create_app(db_url: str | None, host: str = "127.0.0.1", port: int = 8000) -> Starlette:
    """The studio answering on ``host``:``port`` (the ``Host`` its requests must carry) over ``db_url``."""
    studio = Studio.open(db_url)
    token = new_token()
    uploading = [0]  # dropped files being received now

    async def page(request: Request) -> Response:
        return HTMLResponse(await run_in_threadpool(served_page, token), headers={"Cache-Control": "no-store"})

    async def font(request: Request) -> Response:
        return Response(await run_in_threadpool(full_font), media_type="font/woff",
                        headers={"Cache-Control": "max-age=86400"})

    async def upload(request: Request) -> bytes | Response:
        """A dropped file's bytes (at most :data:`MAX_UPLOAD`, :data:`MAX_UPLOADS` at once), or the refusal."""
        if uploading[0] >= MAX_UPLOADS:
            return _refused(429, f"{MAX_UPLOADS} files are being received; drop this one again in a moment")
        uploading[0] += 1
        try:
            data = await _body(request, MAX_UPLOAD, "the file")
        finally:
            uploading[0] -= 1
        if isinstance(data, bytes) and not data:
            return _refused(400, "the file is empty")
        return data

    async def asset(request: Request) -> Response:
        name = request.path_params["name"]
        if name not in ASSETS:
            return Response("not found", status_code=404)
        return Response(_asset(name), media_type=ASSETS[name])

    vendored = _vendored()

    async def vendor(request: Request) -> Response:
        path = vendored.get(request.path_params["path"])  # the client's path only picks from our own list
        if path is None:
            return Response("not found", status_code=404)
        return Response(path.read_bytes(), media_type="text/javascript; charset=utf-8",
                        headers={"Cache-Control": "max-age=86400"})

    pending = [0]  # texts waiting for or in the animation

    async def work(request: Request, fn: Callable[[Asked, Callable[[], bool]], Response]) -> Response:
        """``fn(asked, cancelled)`` in a worker thread; ``cancelled()`` is true once the client went away (the
        page aborted the request for a newer text), so that the work stops there."""
        got = await _text_of(request)
        if isinstance(got, Response):
            return got
        if pending[0] >= MAX_PENDING:
            return _refused(429, f"the studio is busy with {MAX_PENDING} texts; try again in a moment")
        pending[0] += 1
        gone = threading.Event()

        async def watch() -> None:
            while not gone.is_set():
                if await request.is_disconnected():
                    gone.set()
                await asyncio.sleep(CANCEL_POLL)
        watcher = asyncio.create_task(watch())
        try:
            return await asyncio.wait_for(run_in_threadpool(fn, got, gone.is_set), TIMEOUT)
        except asyncio.TimeoutError:
            return JSONResponse({"ok": False, "code": "slow",
                                 "error": f"this text took over {TIMEOUT:g} s; try a shorter one"}, status_code=503)
        finally:
            pending[0] -= 1
            gone.set()
            watcher.cancel()

    async def animate(request: Request) -> Response:
        def run(asked: Asked, cancelled: Callable[[], bool]) -> Response:
            payload = studio.animate(asked.text, asked.edits, asked.fallback, cancelled, draft=asked.draft)
            answer = {k: v for k, v in payload.items() if not k.startswith("_")}
            if asked.page and payload["ok"]:
                answer["html"] = viewer_page(payload)
            return JSONResponse(answer, status_code=200 if payload["ok"] else 422)
        return await work(request, run)

    async def export(request: Request) -> Response:
        def run(asked: Asked, cancelled: Callable[[], bool]) -> Response:
            made = studio.export(asked.text, asked.edits, asked.format, asked.fallback)
            if made is None:
                failed = studio.animate(asked.text, asked.edits, asked.fallback)
                return JSONResponse({"ok": False, "error": failed["error"], "code": failed["code"]}, status_code=422)
            name, data = made
            kind = {"zip": "application/zip", "bvh": "text/plain; charset=utf-8", "json": "application/json",
                    "glb": "model/gltf-binary", "vrma": "model/gltf-binary"}[name.rsplit(".", 1)[1]]
            return Response(data, media_type=kind, headers={"Content-Disposition": f'attachment; filename="{name}"'})
        return await work(request, run)

    async def verbs(request: Request) -> Response:
        q = request.query_params.get("q", "")[:100]
        return JSONResponse({"ok": True, "verbs": await run_in_threadpool(studio.verbs, q)})

    async def import_bvh(request: Request) -> Response:
        from urllib.parse import unquote

        verb = unquote(request.headers.get("x-verb", "")).strip()[:100]
        name = unquote(request.headers.get("x-filename", "dropped.bvh"))[:200]
        if not verb:
            return JSONResponse({"ok": False, "error": "name the verb the clip shows (X-Verb)"}, status_code=400)
        data = await upload(request)
        if isinstance(data, Response):
            return data
        cyclic = request.headers.get("x-cyclic", "") == "1"
        done = await run_in_threadpool(studio.import_bvh, data, name, verb, cyclic)
        return JSONResponse(done, status_code=200 if done["ok"] else 422)

    async def rig(request: Request) -> Response:
        from urllib.parse import unquote

        if request.method == "DELETE":
            await run_in_threadpool(studio.clear_rig)
            return JSONResponse({"ok": True})
        suffix = Path(unquote(request.headers.get("x-filename", ""))).suffix.lower()
        if suffix not in (".glb", ".vrm"):
            return JSONResponse({"ok": False, "error": "drop a .glb or .vrm character"}, status_code=400)
        data = await upload(request)
        if isinstance(data, Response):
            return data
        done = await run_in_threadpool(studio.set_rig, data, suffix)
        return JSONResponse(done, status_code=200 if done["ok"] else 422)

    async def mine(request: Request) -> Response:
        return JSONResponse({"ok": True, "clips": await run_in_threadpool(studio.mine)})

    def on_clip(action: Callable[[str, str], dict]) -> Callable:
        async def endpoint(request: Request) -> Response:
            got = await _clip_of(request)
            if isinstance(got, Response):
                return got
            done = await run_in_threadpool(action, *got)
            return JSONResponse(done, status_code=200 if done["ok"] else 422)
        return endpoint

    async def favicon(request: Request) -> Response:
        return Response(status_code=204)

    app = Starlette(routes=[Route("/", page), Route(FONT_URL, font), Route("/static/vendor/{path:path}", vendor),
                            Route("/static/{name}", asset), Route("/favicon.ico", favicon),
                            Route("/api/animate", animate, methods=["POST"]),
                            Route("/api/export", export, methods=["POST"]), Route("/api/verbs", verbs),
                            Route("/api/import", import_bvh, methods=["POST"]), Route("/api/rig", rig, methods=["POST", "DELETE"]),
                            Route("/api/library", mine),
                            Route("/api/library/keep", on_clip(lambda c, n: studio.keep(c)), methods=["POST"]),
                            Route("/api/library/rename", on_clip(studio.rename), methods=["POST"]),
                            Route("/api/library/remove", on_clip(lambda c, n: studio.remove(c)), methods=["POST"]),
                            Route("/api/clip", on_clip(lambda c, n: studio.clip_page(c)), methods=["POST"])])
    app.add_middleware(SameOrigin, hosts=own_hosts(host, port), token=token)
    app.state.studio = studio
    return app
