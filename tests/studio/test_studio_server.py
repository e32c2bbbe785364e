"""The studio's server (Starlette, through its test client): what it animates, what it exports, what it refuses.

The browser side is tests/studio/test_studio_browser.py; these check the HTTP contract a page relies on.
"""
from __future__ import annotations

import pytest
from starlette.testclient import TestClient

from text2anim.cli.studio.app import MAX_BODY, create_app
from text2anim.core.bvh import parse_bvh

PORT = 8123
BASE = f"http://127.0.0.1:{PORT}"


@pytest.fixture(scope="module")
def client(library_db):
    return TestClient(create_app(library_db, "127.0.0.1", PORT), base_url=BASE)


def test_the_page_and_its_own_files_are_served(client):
    page = client.get("/")
    assert page.status_code == 200 and "text2anim studio" in page.text and "/static/studio.js" in page.text
    assert client.get("/static/studio.js").status_code == 200
    assert client.get("/static/../app.py").status_code == 404  # no path comes from the client
    assert client.get("/static/viewer.js").status_code == 404
    for vendored in ("three/three.module.js", "three/three.core.js", "three/examples/jsm/loaders/GLTFLoader.js"):
        assert client.get(f"/static/vendor/{vendored}").status_code == 200, vendored  # shipped with the package
    assert client.get("/static/vendor/../app.py").status_code == 404


def test_a_text_becomes_the_viewer_page_and_its_time_table(client):
    r = client.post("/api/animate", json={"text": "太郎は走って、ボールを蹴る。"})
    data = r.json()
    assert r.status_code == 200 and data["ok"]
    assert [(e["verb"], e["method"]) for e in data["table"]] == [("走る", "initial"), ("蹴る", "transition")]
    assert "__t2a" in data["html"] and data["duration"] > 1.0 and data["blends"]


def test_a_manner_is_on_its_row_and_one_not_shown_is_a_warning(client):
    data = client.post("/api/animate", json={"text": "花子はしょんぼり歩いて、にこにこ座った。"}).json()
    assert data["ok"]
    assert [(e["verb"], (e["manner"] or {}).get("by")) for e in data["table"]] == [("歩く", "modifiers"),
                                                                                    ("座る", None)]
    assert any("にこにこ is not shown" in w for w in data["warnings"])


def test_what_cannot_be_animated_says_why_in_the_users_terms(client):
    r = client.post("/api/animate", json={"text": "太郎は泳ぐ。"})
    assert r.status_code == 422 and "泳ぐ" in r.json()["error"] and "Traceback" not in r.text
    r = client.post("/api/animate", json={"text": "雨が降る。"})
    assert r.status_code == 422 and "no motion" in r.json()["error"]
    assert client.post("/api/animate", json={"text": "  "}).json()["ok"] is False


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
