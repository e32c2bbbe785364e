"""The studio's server (Starlette, through its test client): what it animates, what it exports, what it refuses.

The browser side is tests/studio/test_studio_browser.py; these check the HTTP contract a page relies on.
"""
from __future__ import annotations

import re

import pytest
from starlette.testclient import TestClient

from text2anim.cli.studio.app import MAX_BODY, create_app
from text2anim.cli.studio.work import Studio
from text2anim.core.bvh import parse_bvh

PORT = 8123
BASE = f"http://127.0.0.1:{PORT}"


def _token(client: TestClient) -> str:
    """The session's token, as the page gets it: from the HTML the studio serves."""
    return re.search(r'<meta name="t2a-token" content="([^"]+)">', client.get("/").text).group(1)


@pytest.fixture(scope="module")
def client(library_db):
    c = TestClient(create_app(library_db, "127.0.0.1", PORT), base_url=BASE)
    c.headers["X-Studio-Token"] = _token(c)
    return c


def test_the_page_and_its_own_files_are_served(client):
    page = client.get("/")
    assert page.status_code == 200 and "text2anim studio" in page.text and "/static/studio.js" in page.text
    assert client.get("/static/studio.js").status_code == 200
    assert client.get("/static/../app.py").status_code == 404  # no path comes from the client
    assert client.get("/static/viewer.js").status_code == 404
    for vendored in ("three/three.module.js", "three/three.core.js", "three/examples/jsm/loaders/GLTFLoader.js"):
        assert client.get(f"/static/vendor/{vendored}").status_code == 200, vendored  # shipped with the package
    assert client.get("/static/vendor/../app.py").status_code == 404


def test_a_text_becomes_the_viewers_data_and_its_time_table(client):
    r = client.post("/api/animate", json={"text": "太郎は走って、ボールを蹴る。", "page": True})
    data = r.json()
    assert r.status_code == 200 and data["ok"] and not data["draft"]
    assert [(e["verb"], e["method"]) for e in data["table"]] == [("走る", "initial"), ("蹴る", "transition")]
    assert data["view"]["actors"] and data["duration"] > 1.0 and data["blends"]
    assert "__t2a" in data["html"] and "Props = (function" in data["html"]  # the page, asked for: it can show things
    assert "html" not in client.post("/api/animate", json={"text": "太郎は走って、ボールを蹴る。"}).json()


def test_a_new_text_is_answered_with_a_draft_then_the_finished_animation(client, library_db):
    """A draft (crossfaded joins) first, marked; the finished animation when asked without ``draft``, which then
    answers the text even when a draft is asked; it has the same bytes as one made without a draft before it."""
    text = "花子は歩いて、座る。"
    draft = client.post("/api/animate", json={"text": text, "draft": True}).json()
    assert draft["ok"] and draft["draft"]
    finished = client.post("/api/animate", json={"text": text}).json()
    assert finished["ok"] and not finished["draft"]
    assert [e["verb"] for e in draft["table"]] == [e["verb"] for e in finished["table"]] == ["歩く", "座る"]
    assert draft["view"]["actors"][0]["rel"] != finished["view"]["actors"][0]["rel"]  # another blend, other frames
    assert client.post("/api/animate", json={"text": text, "draft": True}).json() == finished
    fresh = Studio.open(library_db)
    try:
        alone = fresh.animate(text)
        assert alone["view"] == finished["view"] and alone["table"] == finished["table"]
    finally:
        fresh.close()
    assert client.post("/api/animate", json={"text": text, "draft": "yes"}).status_code == 400


def test_a_manner_is_on_its_row_and_one_not_shown_is_a_warning(client):
    data = client.post("/api/animate", json={"text": "花子はしょんぼり歩いて、にこにこ座った。"}).json()
    assert data["ok"]
    assert [(e["verb"], (e["manner"] or {}).get("by")) for e in data["table"]] == [("歩く", "modifiers"),
                                                                                    ("座る", None)]
    assert any("にこにこ is not shown" in w for w in data["warnings"])
    assert data["notices"] == [{"kind": "manner_not_shown", "text": data["warnings"][0],  # for the page to word
                                "params": {"row": 2, "verb": "座る", "word": "にこにこ", "why": "no_style"}}]


def test_what_cannot_be_animated_says_why_in_the_users_terms(client):
    """Each error has its kind (``code``), which the page words in its own language."""
    r = client.post("/api/animate", json={"text": "太郎は泳ぐ。"})
    assert r.status_code == 422 and "泳ぐ" in r.json()["error"] and "Traceback" not in r.text
    assert r.json()["code"] == "unknown"
    r = client.post("/api/animate", json={"text": "雨が降る。"})
    assert r.status_code == 422 and "no motion" in r.json()["error"] and r.json()["code"] == "no_motion"
    assert client.post("/api/animate", json={"text": "  "}).json()["code"] == "empty"
    r = client.post("/api/animate", json={"text": "太郎は" + "九" * 30 + "秒歩く。"})
    assert r.status_code == 422 and r.json()["code"] == "limit"
    r = client.post("/api/animate", json={"text": "太郎は400秒走る。"})
    assert r.json()["code"] == "limit" and "--max-seconds" in r.json()["error"]  # the command line's sentence
    assert r.json()["notice"]["kind"] == "limit_duration"  # and what the page words instead
    assert r.json()["notice"]["params"] == {"verb": "走る", "s": "400", "max": 300.0}
    r = client.post("/api/animate", json={"text": "太郎は走る。", "edits": [{"verb": "走る", "duration": 90}]})
    assert r.status_code == 400 and r.json()["notice"]["kind"] == "edit_duration"
    assert r.json()["notice"]["params"] == {"verb": "走る", "s": 90.0, "min": 0.1, "max": 60.0}


def test_a_verb_no_clip_has_plays_its_stand_in_when_the_page_asks(client):
    """The page's stand-in button: the same text with ``fallback: nearest`` (what --fallback nearest does)."""
    assert client.post("/api/animate", json={"text": "太郎は公園をぶらつく。"}).status_code == 422
    r = client.post("/api/animate", json={"text": "太郎は公園をぶらつく。", "fallback": "nearest"})
    assert r.status_code == 200 and r.json()["fallbacks"] == [{"written": "ぶらつく", "used": "歩く"}]
    assert client.post("/api/animate", json={"text": "x", "fallback": "loose"}).status_code == 400


def test_the_page_carries_its_words_and_fonts(client):
    """The catalogue (Japanese and English for every key) and the two faces: the catalogue's embedded, the whole
    JIS X 0208 set served (under 2 MB) for what the user types."""
    import json

    from text2anim.cli.studio.page import messages

    page = client.get("/").text
    words = json.loads(re.search(r'<script type="application/json" id="t2a-messages">(.*?)</script>', page).group(1))
    assert words == messages() and all(set(m) == {"ja", "en"} and m["ja"] and m["en"] for m in words.values())
    assert not any("--" in m["ja"] + m["en"] for m in words.values())  # no command-line flag in the page's words
    assert 'font-family: "t2a-ui"' in page and "url(/static/font/jp.woff)" in page
    font = client.get("/static/font/jp.woff")
    assert font.status_code == 200 and font.content[:4] == b"wOFF" and 1_000_000 < len(font.content) < 2 * 2**20


def test_a_phrase_no_clip_does_is_marked_where_it_is_written(client):
    """足を上げる: the clips of 上げる raise a hand; the error names the phrase, and the page underlines
    its verb (issue 39)."""
    r = client.post("/api/animate", json={"text": "太郎は左足を上げた。"})
    (unknown,) = r.json()["unknown"]
    assert r.status_code == 422 and unknown["written"] == "左足を上げる" and unknown["span"] == [6, 8]


def test_the_bvh_export_reads_back(client):
    r = client.post("/api/export", json={"text": "太郎は歩く。"})
    assert r.status_code == 200 and 'filename="animation.bvh"' in r.headers["content-disposition"]
    motion = parse_bvh(r.text)
    assert motion.n_frames > 10 and motion.skeleton.n_joints > 20
    two = client.post("/api/export", json={"text": "太郎は歩く。花子は座る。"})
    assert two.status_code == 200 and two.headers["content-type"] == "application/zip"


@pytest.mark.parametrize("headers", [{"host": f"evil.example:{PORT}"}, {"host": "127.0.0.1:9"},
                                     {"origin": "http://evil.example"}, {"origin": f"http://127.0.0.1:{PORT + 1}"}])
def test_another_host_or_origin_is_refused(client, headers):
    """A page on another site (or a rebound DNS name) must not drive a local tool."""
    r = client.post("/api/animate", json={"text": "太郎は歩く。"}, headers=headers)
    assert r.status_code == 403 and "refused" in r.text
    assert client.get("/", headers=headers).status_code == 403


def test_requests_are_bounded(client):
    big = client.post("/api/animate", content=b'{"text": "' + b"a" * (MAX_BODY + 10) + b'"}',
                      headers={"content-type": "application/json"})
    assert big.status_code == 413
    long = client.post("/api/animate", json={"text": "歩く。" * 1000})
    assert long.status_code == 422 and "at most" in long.json()["error"]
    bad = client.post("/api/animate", content=b"not json", headers={"content-type": "application/json"})
    assert bad.status_code == 400


@pytest.mark.parametrize("fmt, name, magic", [("glb", "animation.glb", b"glTF"), ("vrma", "animation.vrma", b"glTF"),
                                              ("report", "animation.json", b"{")])
def test_the_other_downloads(client, fmt, name, magic):
    r = client.post("/api/export", json={"text": "太郎は歩く。", "format": fmt})
    assert r.status_code == 200 and f'filename="{name}"' in r.headers["content-disposition"]
    assert r.content[:len(magic)] == magic
    assert client.post("/api/export", json={"text": "太郎は歩く。", "format": "exe"}).status_code == 400


def test_the_library_is_searched_by_spelling_and_reading(client):
    verbs = client.get("/api/verbs", params={"q": "ジャンプ"}).json()["verbs"]
    assert any(v["verb"] == "ジャンプする" for v in verbs) and all("ジャンプ" in v["verb"] + v["reading"] for v in verbs)


def test_dropped_files_are_bounded_and_checked_before_anything_is_stored(client):
    from urllib.parse import quote

    from text2anim.cli.studio.app import MAX_UPLOAD

    assert client.post("/api/import", content=b"HIERARCHY", headers={"x-filename": "a.bvh"}).status_code == 400  # no verb
    broken = client.post("/api/import", content=b"HIERARCHY\nROOT x\n{", headers={"x-filename": "a.bvh", "x-verb": "x"})
    assert broken.status_code == 422 and "a.bvh" in broken.json()["error"] and "Traceback" not in broken.text
    assert client.post("/api/rig", content=b"glTF", headers={"x-filename": "a.fbx"}).status_code == 400
    bad_rig = client.post("/api/rig", content=b"glTF\x02\x00\x00\x00", headers={"x-filename": "a.glb"})
    assert bad_rig.status_code == 422 and bad_rig.json()["ok"] is False
    big = client.post("/api/import", content=b"x" * (MAX_UPLOAD + 1), headers={"x-filename": "a.bvh",
                                                                               "x-verb": quote("歩く")})
    assert big.status_code == 413 and "MB" in big.json()["error"]


# ------------------------------------------------------------------ issue 41: every request bounded
@pytest.mark.parametrize("body", [b'{"text": "\xe8\xb5\xb0\xe3\x82\x8b", "format": []}', b"[" * 20_000, b'["text"]',
                                  b'{"text": 7}', b'{"text": "x", "edits": [1, 2]}', b'{"text": "x", "edits": [{"nth": []}]}',
                                  b'{"text": "x", "format": {"a": 1}}', b'\xff\xfe', b'{"text": "x", "edits": {"a": 1}}'])
@pytest.mark.parametrize("endpoint", ["/api/animate", "/api/export"])
def test_a_malformed_request_is_one_line_and_a_4xx(client, endpoint, body):
    """A list for a format and 20,000 nested brackets were 500s with a traceback."""
    r = client.post(endpoint, content=body, headers={"content-type": "application/json"})
    assert 400 <= r.status_code < 500, (r.status_code, r.text[:200])
    error = r.json()["error"]
    assert "\n" not in error and len(error) < 300 and "Traceback" not in r.text


def test_json_only_as_json_and_only_with_the_sessions_token(client):
    """A cross-site "simple" request (a form posting text/plain) and a request without the token are refused:
    neither is served, whatever its Origin says (a browser may omit it)."""
    simple = client.post("/api/animate", content='{"text": "太郎は歩く。"}'.encode(), headers={"content-type": "text/plain"})
    assert simple.status_code == 415
    for token in ("", "wrong", client.headers["X-Studio-Token"][:-1]):
        r = client.post("/api/animate", json={"text": "太郎は歩く。"}, headers={"X-Studio-Token": token})
        assert r.status_code == 403 and "token" in r.text
        assert client.delete("/api/rig", headers={"X-Studio-Token": token}).status_code == 403
    assert client.get("/api/verbs").status_code == 200  # reading needs no token


def test_no_page_may_frame_the_studio_and_its_viewer_is_sandboxed(client):
    for r in (client.get("/"), client.get("/static/studio.js"), client.post("/api/animate", json={"text": "歩く。"}),
              client.get("/", headers={"host": "evil.example"})):
        assert r.headers["x-frame-options"] == "DENY"
        assert r.headers["content-security-policy"] == "frame-ancestors 'none'"
    assert re.search(r'<iframe id="view"[^>]* sandbox="allow-scripts">', client.get("/").text)


def test_the_framed_viewer_runs_its_own_scripts_only_and_asks_for_nothing(client, library_db):
    """The viewer page the studio frames carries its policy first in its head: its inline scripts by their
    hashes (the player and the bridge among them), no request of any kind; the page ``text2anim TEXT`` writes
    has neither the policy nor the bridge (it plays alone, from a file)."""
    import base64
    import hashlib

    import text2anim
    from text2anim.output.viewer import render_html

    page = client.post("/api/animate", json={"text": "太郎は歩く。", "page": True}).json()["html"]
    head = page[page.index("<head>"):page.index("</head>")]
    policy = re.match(r'<head>\s*<meta http-equiv="Content-Security-Policy" content="([^"]+)">', head)
    assert policy is not None
    rules = dict(r.strip().split(" ", 1) for r in policy.group(1).split(";"))
    scripts = re.findall(r"<script>(.*?)</script>", page, re.S)
    hashes = {f"'sha256-{base64.b64encode(hashlib.sha256(s.encode()).digest()).decode()}'" for s in scripts}
    assert len(scripts) == 3 and set(rules["script-src"].split()) == hashes  # errors, the player, the bridge
    assert any("window.parent" in s for s in scripts)
    assert rules["default-src"] == "'none'" and "unsafe" not in rules["script-src"] and "url(/" not in page
    alone = render_html(text2anim.animate("太郎は歩く。", db=library_db).motions["太郎"])
    assert "Content-Security-Policy" not in alone and "window.parent" not in alone


def test_a_rig_is_checked_whole_before_it_is_kept(client, tmp_path):
    """A GLB that reads but is no human (a chain of 40 nodes) was kept, and every later request was a 500."""
    import json
    import struct

    nodes = [{"name": f"j{i}", "children": [i + 1] if i < 39 else [], "translation": [0, 0.05, 0]} for i in range(40)]
    gl = json.dumps({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": list(range(40))}]}).encode()
    gl += b" " * (-len(gl) % 4)
    body = struct.pack("<II", len(gl), 0x4E4F534A) + gl
    chain = b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body
    r = client.post("/api/rig", content=chain, headers={"x-filename": "chain.glb"})
    assert r.status_code == 422 and "hips" in r.json()["error"]
    after = client.post("/api/animate", json={"text": "太郎は歩く。"})
    assert after.status_code == 200 and after.json()["rig"] is False


def test_a_text_the_page_went_away_from_stops_between_stages(library_db):
    """The work of a request whose page went away stops at the next stage, and nothing of it is kept."""
    import time

    from text2anim.cli.studio import work

    studio = work.Studio.open(library_db)
    looks: list[float] = []

    def gone() -> bool:
        looks.append(time.perf_counter())
        return len(looks) > 2  # the page goes away after the second stage

    text = "太郎は走って、ボールを蹴る。そして喜ぶ。"
    assert studio.animate(text, cancelled=gone) == {"ok": False, "code": "cancelled",
                                                    "error": "the page asked for another text"}
    assert len(looks) == 3 and not studio.cache
    assert studio.animate(text)["ok"]


def test_a_dropped_clip_is_the_sessions_until_kept_then_listed_renamed_and_removed(library_db, tmp_path):
    import text2anim
    from text2anim.cli.studio import work
    from text2anim.output.bvh_write import format_bvh

    (motion,) = text2anim.animate("太郎は手を振る。", db=library_db).motions.values()
    library = tmp_path / "mine.sqlite"
    studio = work.Studio.open(str(library))
    try:
        done = studio.import_bvh(format_bvh(motion).encode(), "walk.bvh", "逆立ちする", False)
        assert done["ok"] and done["clip"] == "walk_2"  # a dropped walk.bvh never replaces the built-in walk
        assert studio.animate("花子は逆立ちする。")["table"][0]["clip"] == "walk_2"
        assert studio.mine() == [] and studio.keep("walk") == {"ok": False, "error": "no clip 'walk' was dropped in "
                                                                                      "this session"}
        assert studio.keep("walk_2")["ok"] and [c["name"] for c in studio.mine()] == ["walk_2"]
        assert studio.rename("walk_2", "手招き")["ok"] and [c["name"] for c in studio.mine()] == ["手招き"]
        assert studio.animate("花子は逆立ちする。")["table"][0]["clip"] == "手招き"
        assert studio.remove("walk")["ok"] is False  # a built-in clip is not the user's to remove
        assert studio.remove("手招き")["ok"] and studio.mine() == []
        assert studio.animate("花子は逆立ちする。")["code"] == "unknown"
    finally:
        studio.close()


def test_the_result_cache_is_held_to_its_byte_budget(library_db, monkeypatch):
    """Results are kept within CACHE_BYTES (the page's payloads, not whole animations); a text whose result
    was let go is exported all the same (animated again: the same bytes)."""
    from text2anim.cli.studio import work

    studio = work.Studio.open(library_db)
    one = studio.animate("太郎は歩く。")
    monkeypatch.setattr(work, "CACHE_BYTES", one["_bytes"] + 10)
    before = studio.export("太郎は歩く。")
    studio.animate("太郎は走る。")
    assert list(studio.cache) == [studio._key("太郎は走る。", ())]
    assert all("_anim" not in p for p in studio.cache.values())
    assert studio.export("太郎は歩く。") == before
    studio.close()


def test_a_studio_on_every_interface_answers_to_the_names_that_reach_it():
    import socket

    from text2anim.cli.studio.guard import own_hosts

    hosts = own_hosts("0.0.0.0", 8000)
    assert {"localhost:8000", "127.0.0.1:8000", f"{socket.gethostname()}:8000"} <= hosts
    assert "0.0.0.0:8000" not in hosts and "[::1]:8000" in own_hosts("::1", 8000)
    assert own_hosts("192.0.2.7", 80) == {"192.0.2.7:80"}


def test_sigterm_removes_the_dropped_character(tmp_path, library_db):
    """The studio's private folder (a dropped character) was left behind when the studio was stopped by SIGTERM."""
    import os
    import signal
    import subprocess
    import sys
    import time
    import urllib.request

    from cli_run import REPO
    from rig_builders import vrm_file
    from text2anim.cli.cmd_studio import free_port

    port, tmp = free_port("127.0.0.1"), tmp_path / "tmp"
    tmp.mkdir()
    env = {**os.environ, "TMPDIR": str(tmp), "PYTHONPATH": str(REPO)}
    proc = subprocess.Popen([sys.executable, "-m", "text2anim.cli.main", "studio", "--no-browser", "--port", str(port),
                             "--db", library_db], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        base = f"http://127.0.0.1:{port}"
        deadline = time.monotonic() + 60
        while True:
            try:
                html = urllib.request.urlopen(base + "/", timeout=5).read().decode()
                break
            except OSError:
                assert time.monotonic() < deadline and proc.poll() is None, "the studio did not start"
                time.sleep(0.2)
        token = re.search(r'<meta name="t2a-token" content="([^"]+)">', html).group(1)
        rig = vrm_file(tmp_path / "a.vrm").read_bytes()
        request = urllib.request.Request(base + "/api/rig", data=rig, method="POST",
                                         headers={"X-Filename": "a.vrm", "X-Studio-Token": token})
        assert b'"ok":true' in urllib.request.urlopen(request, timeout=60).read()
        (folder,) = tmp.glob("t2a-studio-*")
        assert list(folder.glob("character.vrm"))
        proc.send_signal(signal.SIGTERM)
        assert proc.wait(30) == 128 + signal.SIGTERM
        assert not folder.exists()
    finally:
        proc.kill()
        proc.wait()


def test_a_request_the_page_abandoned_is_not_worked_on(library_db):
    """A text queued behind another whose page went away (a newer text aborted it) is dropped when its turn comes:
    the next text waits for the one in work only (issue 41: aborted requests ran on and delayed the next by 8.5 s)."""
    import json
    import socket
    import threading
    import time

    import uvicorn

    from text2anim.cli.cmd_studio import free_port

    port = free_port("127.0.0.1")
    app = create_app(library_db, "127.0.0.1", port)
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))
    threading.Thread(target=server.run, daemon=True).start()
    while not server.started:
        time.sleep(0.05)
    token = app.user_middleware[0].kwargs["token"]

    def post(text: str, leave_after: float | None = None) -> bytes:
        body = json.dumps({"text": text}).encode()
        with socket.create_connection(("127.0.0.1", port)) as s:
            s.sendall(f"POST /api/animate HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n"
                      f"X-Studio-Token: {token}\r\nContent-Length: {len(body)}\r\n\r\n".encode() + body)
            if leave_after is not None:
                time.sleep(leave_after)
                return b""
            return s.recv(100).split(b"\r\n")[0]

    try:
        first = threading.Thread(target=post, args=("太郎は走る。" + "3秒後に歩く。" * 3,))
        first.start()
        time.sleep(0.3)
        abandoned = "花子は" + "3秒後に走る。" * 3
        post(abandoned, leave_after=0.2)
        assert post("次郎は歩く。") == b"HTTP/1.1 200 OK"
        first.join()
        kept = [key.split("\0")[0] for key in app.state.studio.cache]
        assert abandoned not in kept and "次郎は歩く。" in kept
    finally:
        server.should_exit = True


def test_headers_sent_a_byte_at_a_time_are_cut_off(library_db, monkeypatch):
    """A client trickling its headers is disconnected HEADER_TIMEOUT after its first byte (every byte restarted
    uvicorn's keep-alive clock: it held the connection for ever); a request in time is answered as before."""
    import socket
    import threading
    import time

    import uvicorn

    from text2anim.cli.cmd_studio import free_port
    from text2anim.cli.studio import slow

    monkeypatch.setattr(slow, "HEADER_TIMEOUT", 1.0)
    monkeypatch.setattr(slow, "CHECK_EVERY", 0.2)
    port = free_port("127.0.0.1")
    server = uvicorn.Server(slow.server_config(create_app(library_db, "127.0.0.1", port), "127.0.0.1", port,
                                               log_level="warning"))
    threading.Thread(target=server.run, daemon=True).start()
    while not server.started:
        time.sleep(0.05)
    try:
        with socket.create_connection(("127.0.0.1", port)) as s:
            s.sendall(f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
            assert s.recv(100).startswith(b"HTTP/1.1 200")
        with socket.create_connection(("127.0.0.1", port)) as s:
            start, closed = time.monotonic(), False
            for byte in f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Slow: {'a' * 40}".encode():
                try:
                    s.sendall(bytes([byte]))
                except OSError:
                    closed = True
                    break
                time.sleep(0.1)
                if time.monotonic() - start > 4:
                    break
            s.settimeout(2)
            try:
                closed = closed or s.recv(100) == b""
            except OSError:
                closed = True
            assert closed and time.monotonic() - start < 4
    finally:
        server.should_exit = True
