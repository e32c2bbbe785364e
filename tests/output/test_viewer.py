"""The self-contained HTML viewer: its data, its safety, and the page itself in headless Chromium.

The motions are clips of the built-in library (walk, and kick resampled to a capture's 120 fps),
so no shared data is needed.

The browser tests run ``/usr/bin/chromium`` (Debian's package; ``.ci/run`` installs it)
and skip when it is absent:

    chromium --headless --no-sandbox --disable-gpu ... --user-data-dir=TMP
             --enable-logging=stderr --v=0 --virtual-time-budget=MS --dump-dom file://PAGE
    chromium --headless ... --window-size=1000,700 --screenshot=OUT.png file://PAGE
"""
from __future__ import annotations

import base64
import json
import re
import shutil
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest

from shared_data import library_motion
from text2anim.core import Motion, Skeleton, concatenate
from text2anim.core.bodyparts import body_map
from text2anim.core.atomic import OutputError
from text2anim.output.viewer import PALETTE, Prop, Span, Track, render_html, viewer_data

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync",
                  "--hide-scrollbars", "--mute-audio"]
requires_chromium = pytest.mark.skipif(
    not Path(CHROMIUM).exists(),
    reason=f"{CHROMIUM} not installed (apt-get install chromium); the page is not tested in a browser")


def _chain(T=20, fps=30.0):
    skel = Skeleton(["root", "a", "b"], [-1, 0, 1], [[0, 0, 0], [0, 0.5, 0], [0, 0.5, 0]], end_sites=[(2, [0, 0.2, 0])])
    ang = np.linspace(0, 1, T)
    rot = np.zeros((T, 3, 4))
    rot[..., 3] = 1
    rot[:, 1, 2], rot[:, 1, 3] = np.sin(ang / 2), np.cos(ang / 2)
    return Motion(skel, fps, np.c_[np.linspace(0, 1, T), np.full(T, 0.9), np.zeros(T)], rot)


def _decode(actor: dict, encoding: str) -> np.ndarray:
    """The page's decoding, in numpy: world positions (T, N, 3) in metres."""
    def raw(s):
        b = base64.b64decode(s)
        return zlib.decompress(b) if encoding == "deflate" else b

    T, N = actor["frames"], actor["points"]
    rel = np.frombuffer(raw(actor["rel"]), "<i2").reshape(N, 3, T).astype(np.int64).cumsum(axis=2)
    root = np.frombuffer(raw(actor["root"]), "<i4").reshape(3, T).astype(np.int64).cumsum(axis=1)
    return (rel + root[None]).transpose(2, 0, 1) / 1000.0


def _data_of(page: str) -> dict:
    m = re.search(r'<script type="application/json" id="t2a-data">(.*?)</script>', page, re.S)
    assert m, "no data block"
    return json.loads(m.group(1))


@pytest.fixture(scope="module")
def walk():
    return library_motion("walk")


@pytest.fixture(scope="module")
def kick():
    """The built-in kick at a capture's rate (120 fps), which the page must resample."""
    return library_motion("kick").resample(120)


def _spans(actor="太郎"):
    return [Span(actor, "1 歩く (initial)", 0.0, 2.8), Span(actor, "2 蹴る (transition)", 2.2, 5.0),
            Span(actor, "blend", 2.2, 2.7, "blend", "lower"), Span(actor, "blend", 2.3, 2.9, "blend", "upper"),
            Span(actor, "blend", 4.8, 5.0, "blend")]


# ----------------------------------------------------------------------------- data
@pytest.mark.parametrize("compress", [True, False])
def test_positions_roundtrip_to_the_millimetre(walk, compress):
    data = viewer_data([Track("a", walk)], compress=compress)
    (actor,) = data["actors"]
    pos = _decode(actor, data["encoding"])
    want = np.concatenate([walk.positions, walk.end_site_positions()], axis=1)
    assert pos.shape == want.shape
    assert np.abs(pos - want).max() <= 0.0005 + 1e-9
    assert actor["parents"][: walk.skeleton.n_joints] == list(walk.skeleton.parents)
    assert len(actor["contact"]) == walk.n_frames and set(actor["contact"]) <= set("0123")
    assert "1" in actor["contact"] or "3" in actor["contact"]  # a walk puts its feet down


def test_fast_motions_are_resampled_for_the_page(kick):
    assert kick.fps > 100
    (actor,) = viewer_data([Track("k", kick)], max_fps=30)["actors"]
    assert actor["fps"] == 30
    assert actor["frames"] == int(np.floor((kick.n_frames - 1) / kick.fps * 30 + 1e-9)) + 1
    pos = _decode(actor, "deflate")
    # frame k of the page is the capture at k/30 s
    for k in (0, 10, actor["frames"] - 1):
        src = kick.positions[int(round(k / 30 * kick.fps))]
        assert np.abs(pos[k, : kick.skeleton.n_joints] - src).max() < 0.02


def test_ten_second_page_stays_small(walk):
    reps = int(np.ceil(300 / walk.n_frames))
    ten = concatenate([walk] * reps)[:300]
    assert ten.skeleton.n_joints == 31 and abs(ten.duration - 10) < 1e-9
    page = render_html([Track("太郎", ten)], _spans(), title="10 s")
    raw = render_html([Track("太郎", ten)], _spans(), title="10 s", compress=False)
    assert len(page.encode()) < 110_000, len(page.encode())
    assert len(page.encode()) < len(raw.encode())


def test_page_is_self_contained_and_escapes_text(walk):
    evil = '</script><script>alert("x")</script><!--'
    page = render_html([Track(evil, walk)], [Span(evil, evil, 0, 1)], title=evil)
    assert page.count("</script>") == page.count("<script")  # nothing closes a script early
    assert "<script>alert" not in page
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", page)
    data = _data_of(page)
    assert data["title"] == evil and data["actors"][0]["name"] == evil and data["spans"][0]["label"] == evil
    assert "<title>&lt;/script&gt;" in page


def test_spans_and_rows(walk, kick):
    spans = _spans() + [Span("花子", "1 蹴る", 0, 6.7), Span("次郎", "only a span", 1, 2)]
    data = viewer_data([Track("太郎", walk), Track("花子", kick)], spans)
    assert data["rows"] == ["太郎", "花子", "次郎"]
    assert [a["color"] for a in data["actors"]] == list(PALETTE[:2])
    lanes = [s["lane"] for s in data["spans"] if s["kind"] == "blend"]
    assert lanes == ["lower", "upper", "both"]
    assert data["duration"] == pytest.approx(6.7)


def test_bad_input_is_refused(walk):
    with pytest.raises(ValueError, match="share the name"):
        render_html([Track("a", walk), Track("a", walk)])
    with pytest.raises(ValueError, match="no tracks"):
        render_html([])
    with pytest.raises(ValueError, match="kind"):
        Span("a", "x", 0, 1, "gap")
    with pytest.raises(ValueError, match="before start"):
        Span("a", "x", 2, 1)
    with pytest.raises(ValueError, match="no frames"):
        Track("a", walk[0:0])


def test_other_inputs_accepted():
    m = _chain()
    for tracks in (m, {"x": m}, Track("x", m)):
        data = viewer_data(tracks)
        assert len(data["actors"]) == 1 and data["actors"][0]["head"] == -1  # no body map: drawn plainly


def test_written_atomically(tmp_path, walk):
    out = tmp_path / "v.html"
    page = render_html([Track("a", walk)], path=out)
    assert out.read_text(encoding="utf-8") == page
    with pytest.raises(OutputError) as e:
        render_html([Track("a", walk)], path=tmp_path / "missing" / "v.html")
    assert e.value.user_facing
    assert sorted(p.name for p in tmp_path.iterdir()) == ["v.html"]


# --------------------------------------------------------------------------- browser
def _chromium(args: list[str], profile: Path, timeout=60) -> subprocess.CompletedProcess:
    cmd = [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


def _console(stderr: str) -> list[str]:
    return [ln for ln in stderr.splitlines() if ":CONSOLE" in ln]


def _body(dom: str) -> dict:
    m = re.search(r"<body([^>]*)>", dom)
    assert m, dom[:500]
    return dict(re.findall(r'data-([\w-]+)="([^"]*)"', m.group(1)))


@pytest.fixture(scope="module")
def page(tmp_path_factory, walk, kick):
    d = tmp_path_factory.mktemp("viewer")
    k = kick.replace(root_positions=kick.root_positions + [1.5, 0, 0])
    path = d / "viewer.html"
    render_html([Track("太郎", walk), Track("花子", k)], _spans() + [Span("花子", "1 蹴る (initial)", 0, k.duration)],
                title="太郎は歩いて、ボールを蹴る。", path=path)
    return path


@requires_chromium
def test_page_loads_without_console_messages_and_frames_advance(page, tmp_path):
    seen = []
    for budget in (500, 2500):
        proc = _chromium([f"--virtual-time-budget={budget}", "--dump-dom", page.as_uri()], tmp_path / f"p{budget}")
        assert proc.returncode == 0, proc.stderr[-2000:]
        assert _console(proc.stderr) == [], _console(proc.stderr)
        body = _body(proc.stdout)
        assert body.get("ready") == "1", body
        assert 'data-errors=' not in proc.stdout.split("<body", 1)[0]
        seen.append((int(body["frame"]), float(body["time"])))
    (f0, t0), (f1, t1) = seen
    assert 0 < t0 < t1 and f0 < f1, seen
    assert t1 == pytest.approx(2.5, abs=0.3)  # plays in real time


@requires_chromium
def test_screenshot_shows_the_characters(page, tmp_path):
    mpimg = pytest.importorskip("matplotlib.image")
    shot = tmp_path / "shot.png"
    proc = _chromium(["--virtual-time-budget=1500", "--window-size=1000,700", f"--screenshot={shot}", page.as_uri()],
                     tmp_path / "prof")
    assert proc.returncode == 0 and shot.exists(), proc.stderr[-2000:]
    assert _console(proc.stderr) == []
    img = mpimg.imread(shot)[..., :3]
    assert img.shape[:2] == (700, 1000)
    for color in PALETTE[:2]:
        rgb = np.array([int(color[i:i + 2], 16) for i in (1, 3, 5)]) / 255
        near = np.abs(img - rgb).max(axis=-1) < 0.2  # the colour, give or take the shading
        # the 3D view below the header, above the controls and timeline, right of the legend
        ys, xs = np.nonzero(near[40:480, 80:])
        assert len(ys) > 800, f"{color}: only {len(ys)} pixels of the actor's colour in the view"
        assert 100 < xs.mean() < 800 and 50 < ys.mean() < 400, (xs.mean(), ys.mean())  # framed, not at an edge
    # the background is dark and the figure is not: the view is not blank
    view = img[40:480]
    assert (view.max(axis=-1) > 0.5).mean() > 0.005


def _rate(a: dict, b: dict) -> float:
    """Seconds of animation played per second of the page's own clock between two snapshots (``now``: the
    viewer's ``clock``, ms, read at the step that set ``time``; read apart from it, with steps 0.1-0.25 s apart
    on a slowed CPU, the rate came out 1.11 at 1x).

    A slow machine plays slower than real time (the page steps a late frame by 0.25 s at most; with the CPU
    slowed 20 times a second of the page's clock played 0.66 s), and the driver's sleeps stretch: speeds are
    compared on the page's clock and to each other, not as time gained over a sleep of the driver."""
    return (b["time"] - a["time"]) / max((b["now"] - a["now"]) / 1000.0, 1e-9)


PLAY_RATE = """(seconds) => new Promise((done) => {
  const a = {time: window.__t2a.time, now: window.__t2a.clock};
  setTimeout(() => done([a, {time: window.__t2a.time, now: window.__t2a.clock}]), seconds * 1000);
})"""


def _played(page, seconds: float = 1.0) -> float:
    """:func:`_rate` of a playwright ``page`` over ``seconds`` of its own clock."""
    return _rate(*page.evaluate(PLAY_RATE, seconds))


NEXT_FRAME = "new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)))"


@requires_chromium
@pytest.mark.parametrize("slowdown", [1, 8])
def test_a_person_can_drive_it(page, tmp_path, slowdown):
    """Space, arrow keys, timeline click, orbit drag, wheel zoom, double-click reset, speed: through DevTools;
    also with Chromium's CPU slowed ``slowdown`` times (DevTools' CPU throttling), as on a loaded machine."""
    if shutil.which("node") is None:
        pytest.skip("node not installed: the page is driven through the DevTools protocol by a node script")
    script = Path(__file__).parents[1] / "browser" / "viewer_drive.mjs"
    shot = tmp_path / "driven.png"
    proc = subprocess.run(["node", str(script), CHROMIUM, page.as_uri(), str(tmp_path / "prof"), str(shot),
                           str(slowdown)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    r = json.loads(proc.stdout)
    assert "error" not in r, r.get("error", "") + r.get("stderr", "")
    assert r["ready"] == "1"
    assert r["console"] == [] and r["pageErrors"] == []
    one = _rate(r["start"], r["afterPlaying"])
    assert 0 < one <= 1.001 and r["afterPlaying"]["playing"]  # plays, never ahead of real time
    assert not r["paused"]["playing"] and r["stillPaused"]["time"] == r["paused"]["time"]
    fps = 30
    assert r["stepped"]["time"] == pytest.approx((round(r["paused"]["time"] * fps) + 1) / fps)
    assert r["seeked"]["time"] == pytest.approx(r["seekTarget"], abs=0.05)
    cam0, cam1 = r["seeked"]["camera"], r["dragged"]["camera"]
    assert abs(cam1["yaw"] - cam0["yaw"]) > 0.5 and cam1["pitch"] > cam0["pitch"]
    assert r["zoomed"]["camera"]["dist"] > cam1["dist"] * 1.2
    assert r["reset"]["camera"]["yaw"] == pytest.approx(r["start"]["camera"]["yaw"])
    assert r["reset"]["camera"]["dist"] == pytest.approx(r["start"]["camera"]["dist"])
    ds = r["doubleSpeed"]
    assert ds["speed"] == 2 and ds["playing"]
    # faster than 1x can ever play, never faster than 2x (a late frame's step is clamped: 1x read 0.55 on a
    # slowed CPU in the second after loading while 2x read 2.0 later, so the two are not compared to each other)
    assert 1.001 < _rate({"time": ds["from"], "now": ds["fromNow"]}, ds) <= 2.002
    assert shot.stat().st_size > 10_000


# ----------------------------------------------------------------------------- props
def _decode_prop(p: dict, encoding: str) -> tuple[np.ndarray, np.ndarray]:
    """The page's decoding of a thing, in numpy: centres (T, 3) metres and quaternions (T, 4)."""
    def raw(s):
        b = base64.b64decode(s)
        return zlib.decompress(b) if encoding == "deflate" else b

    T = p["frames"]
    pos = np.frombuffer(raw(p["pos"]), "<i4").reshape(3, T).astype(np.int64).cumsum(axis=1).T / 1000.0
    rot = np.frombuffer(raw(p["rot"]), "<i4").reshape(4, T).astype(np.int64).cumsum(axis=1).T / 32767.0
    return pos, rot


@pytest.fixture(scope="module")
def scene(library_db):
    from scene_props import scene as make

    return make(library_db)


def _without_font(page: str) -> str:
    return re.sub(r"@font-face \{[^}]*\}", "", page)


def test_props_cost_nothing_when_there_are_none(scene):
    from text2anim.output.viewer import PROPS_SLOT

    anim, props = scene
    bare = render_html(anim.tracks(), anim.spans(), title=anim.text)
    assert "props" not in _data_of(bare) and "Props = (function" not in bare and PROPS_SLOT in bare
    assert render_html(anim.tracks(), anim.spans(), title=anim.text, props=[]) == bare
    full = render_html(anim.tracks(), anim.spans(), title=anim.text, props=props)
    assert "Props = (function" in full and PROPS_SLOT not in full
    # a ball that moves every frame and a still chair: a few KB (their code and data; the glyphs of their names
    # in the page's embedded font are the font's, tests/output/test_embedded_font.py)
    extra = len(_without_font(full).encode()) - len(_without_font(bare).encode())
    assert extra < 16_000, extra


@pytest.mark.parametrize("compress", [True, False])
def test_props_roundtrip_to_the_millimetre(scene, compress):
    anim, (ball, chair) = scene
    data = viewer_data(anim.tracks(), props=[ball, chair], compress=compress)
    moving, still = data["props"]
    assert [moving["name"], still["name"]] == ["ボール", "椅子"] and still["shape"] == "chair"
    pos, rot = _decode_prop(moving, data["encoding"])
    assert pos.shape == (ball.n_frames, 3) and np.abs(pos - ball.positions).max() <= 0.0005 + 1e-9
    assert np.abs(np.abs(np.sum(rot * ball.unit_rotations, axis=1)) - 1).max() < 1e-3
    pos, rot = _decode_prop(still, data["encoding"])
    assert still["frames"] == 1 and np.abs(pos[0] - chair.positions[0]).max() <= 0.0005 + 1e-9
    assert len(still["parts"]) == 8 and all(len(p) == 8 for p in still["parts"])  # seat, 4 legs, 2 posts, back


def test_fast_props_are_resampled_with_the_actors(kick):
    from scene_props import in_hand

    ball = in_hand(kick)  # 120 fps
    data = viewer_data([Track("k", kick)], props=[ball], max_fps=30)
    (p,) = data["props"]
    (actor,) = data["actors"]
    assert p["fps"] == 30 and p["frames"] == actor["frames"]
    pos, _ = _decode_prop(p, "deflate")
    hands = _decode(actor, "deflate")[:, body_map(kick.skeleton).hands["right"]]
    assert np.abs(pos - hands).max() < 0.002  # the page's ball is where the page's hand is


def _project(camera: dict, width: float, height: float, point) -> tuple[float, float]:
    """Where the page's camera puts a world point, in CSS pixels of the 3D view (viewer.js updateBasis, toScreen)."""
    yaw, pitch, dist, target = camera["yaw"], camera["pitch"], camera["dist"], np.array(camera["target"])
    d = np.array([np.cos(pitch) * np.sin(yaw), np.sin(pitch), np.cos(pitch) * np.cos(yaw)])
    eye, f = target + d * dist, -d
    r = np.array([-f[2], 0.0, f[0]])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    q = np.asarray(point) - eye
    x, y, z = q @ r, q @ u, q @ f
    focal = (height / 2) / np.tan(np.radians(40) / 2)
    return width / 2 + focal * x / z, height / 2 - focal * y / z


def _drawn_in_its_box(img: np.ndarray, prop, frame: int, camera: dict, view: list) -> bool:
    """True when the pixels of ``prop``'s colour (any shade of its hue) near it lie in the screen box of its
    projected bounding box, and cover a tenth of that box; the band above the box, where its name is, is left out."""
    from scipy.spatial.transform import Rotation

    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) / 2
    corners = Rotation.from_quat(prop.unit_rotations[frame]).apply(signs * prop.size) + prop.positions[frame]
    xy = np.array([_project(camera, view[2], view[3], c) for c in corners]) + view[:2]
    (x0, y0), (x1, y1) = xy.min(axis=0), xy.max(axis=0)
    rgb = np.array([int(prop.color[i:i + 2], 16) for i in (1, 3, 5)]) / 255
    hue = img / np.maximum(img.max(axis=-1, keepdims=True), 1e-6)
    mask = (np.abs(hue - rgb / rgb.max()).max(axis=-1) < 0.18) & (img.max(axis=-1) > 0.2)
    ys, xs = np.mgrid[0:img.shape[0], 0:img.shape[1]]
    inside = mask & (xs >= x0 - 2) & (xs <= x1 + 2) & (ys >= y0 - 2) & (ys <= y1 + 2)
    band = mask & ~inside & (xs >= x0 - 30) & (xs <= x1 + 30) & (ys >= y0) & (ys <= y1 + 30)
    area = (x1 - x0 + 4) * (y1 - y0 + 4)
    ok = inside.sum() > 0.1 * area and band.sum() < 0.05 * inside.sum()
    if not ok:
        print(prop.name, frame, "box", (x0, y0, x1, y1), "inside", inside.sum(), "of", area, "around", band.sum())
    return bool(ok)


@requires_chromium
def test_the_things_are_drawn_where_their_projection_says(scene, tmp_path):
    """Two actors, a ball in 花子's waving hand and a chair, paused at three times: the ball's red and the chair's
    wood are drawn in the screen boxes where the page's camera (read back from the page) projects them."""
    playwright = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed (pip install '.[test]')")
    mpimg = pytest.importorskip("matplotlib.image")
    anim, (ball, chair) = scene
    path = tmp_path / "scene.html"
    render_html(anim.tracks(), anim.spans(), title=anim.text, path=path, props=[ball, chair])
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1000, "height": 700}, device_scale_factor=1)
        problems: list[str] = []
        page.on("pageerror", lambda e: problems.append(str(e)))
        page.on("console", lambda m: problems.append(m.text))
        page.goto(path.as_uri())
        page.wait_for_function("document.body.dataset.ready === '1'", timeout=30000)
        legend = page.inner_text("#legend")
        for frame in (0, ball.n_frames // 2, ball.n_frames - 1):
            page.evaluate(f"window.__t2a.pause(); window.__t2a.seek({frame / ball.fps})")
            page.evaluate(NEXT_FRAME)  # drawn at the new time (a fixed 300 ms wait was too short under load)
            camera = page.evaluate("window.__t2a.camera")
            box = page.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                                " return [r.left, r.top, r.width, r.height]; })()")
            shot = tmp_path / f"shot{frame}.png"
            page.screenshot(path=str(shot))
            img = mpimg.imread(shot)[..., :3]
            for prop in (ball, chair):
                assert _drawn_in_its_box(img, prop, min(frame, prop.n_frames - 1), camera, box), (prop.name, frame)
        browser.close()
    assert problems == []
    assert "ボール" in legend and "椅子" in legend


@requires_chromium
def test_a_ball_kicked_far_away_leaves_the_picture_and_nothing_hangs(library_db, tmp_path):
    """A kicked ball that rolls tens of metres (the scene stage's seed sentence sends it 30 m): the home camera frames
    the actor, not the ball's whole path (it zoomed out to 200 m, and the grid of a camera that far drew millions
    of lines a frame: the page hung), and zoomed out as far as the wheel goes the page still plays."""
    import text2anim

    playwright = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed (pip install '.[test]')")
    anim = text2anim.animate("太郎は走って、ボールを蹴る。", db=library_db)
    (ball,) = anim.props()  # the scene stage's, at the kicking foot and then away; sent 40 m farther here
    away = np.clip((np.arange(ball.n_frames) - ball.n_frames // 2) / (ball.n_frames // 2), 0, 1)[:, None]
    far = Prop(ball.name, ball.shape, ball.size, ball.positions + away * [0.0, 0.0, 40.0], ball.rotations, ball.fps,
               ball.color)
    path = tmp_path / "kick.html"
    render_html(anim.tracks(), anim.spans(), title=anim.text, path=path, props=[far])
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1000, "height": 700})
        page.goto(path.as_uri())
        page.wait_for_function("document.body.dataset.ready === '1'", timeout=30000)
        assert page.evaluate("window.__t2a.camera.dist") < 20
        page.mouse.move(500, 300)
        for _ in range(40):
            page.mouse.wheel(0, 400)
        page.wait_for_function("window.__t2a.camera.dist >= 299", timeout=10000)
        assert _played(page) > 0.5  # it plays about in real time: a hung page's frames took seconds each
        browser.close()
