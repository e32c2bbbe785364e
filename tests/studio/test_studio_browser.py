"""The studio in a real browser: Debian's Chromium driven by Playwright, against the real server on a free port.

Type and watch, add a sentence while it plays (playback goes on from the frame on screen), export a BVH and
read it back, open a shared link. Skipped, saying why, without /usr/bin/chromium or Playwright.
"""
from __future__ import annotations

import threading
import time
from pathlib import Path

import pytest

from text2anim.cli.cmd_studio import free_port
from text2anim.core.bvh import parse_bvh

CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--no-sandbox", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync",
         "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]  # WebGL on the CPU, for the skinned view
playwright_api = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed (pip install '.[test]')")
pytestmark = pytest.mark.skipif(not Path(CHROMIUM).exists(),
                                reason=f"{CHROMIUM} not installed (apt-get install chromium); the studio is not tested "
                                       "in a browser")


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    """The studio's URL, served by uvicorn in a thread for the module's tests, on a database of its own
    (the drop tests import clips into it)."""
    import uvicorn

    from text2anim.cli.studio.app import create_app

    db = f"sqlite:///{tmp_path_factory.mktemp('studio-db') / 'motions.sqlite'}"
    port = free_port("127.0.0.1")
    server = uvicorn.Server(uvicorn.Config(create_app(db, "127.0.0.1", port), host="127.0.0.1", port=port,
                                           log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 20
    while not server.started and time.monotonic() < deadline:
        time.sleep(0.05)
    yield f"http://127.0.0.1:{port}/"
    server.should_exit = True
    thread.join(10)


@pytest.fixture(scope="module")
def browser():
    with playwright_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=FLAGS)
        yield b
        b.close()


@pytest.fixture
def page(browser, studio, tmp_path):
    context = browser.new_context(viewport={"width": 1100, "height": 900}, accept_downloads=True)
    pg = context.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(studio)
    pg.wait_for_function("window.__studio && window.__studio.renders >= 1", timeout=30000)
    yield pg
    assert errors == []
    context.close()


def _canvas(pg) -> bytes:
    return pg.frame_locator("#view").locator("canvas").first.screenshot()


def test_typing_a_sentence_changes_the_animation_and_the_time_table(page, tmp_path):
    before = _canvas(page)
    assert page.evaluate("window.__studio.table.map(e => e.verb)") == ["走る", "蹴る", "喜ぶ"]
    page.fill("#text", "花子は歩いて、座る。")
    page.wait_for_function("window.__studio.renders >= 2 && !window.__studio.busy", timeout=30000)
    assert page.evaluate("window.__studio.table.map(e => e.verb)") == ["歩く", "座る"]
    assert page.locator("#timeline rect.bar").count() == 2
    assert _canvas(page) != before
    page.screenshot(path=str(tmp_path / "typed.png"))


def test_an_unknown_verb_is_shown_under_the_text_and_the_last_animation_stays(page):
    page.fill("#text", "太郎は泳ぐ。")
    page.wait_for_function("document.getElementById('error').textContent.includes('泳ぐ')", timeout=30000)
    assert "no stand-in" in page.inner_text("#error")
    assert page.evaluate("window.__studio.table.length") == 3  # the seed sentence still plays


def test_a_manner_not_shown_is_said_under_the_text_and_a_styled_bar_names_its_manner(page):
    page.fill("#text", "花子はしょんぼり歩いて、にこにこ座った。")
    page.wait_for_function("document.querySelectorAll('#marks .warning').length === 1", timeout=30000)
    assert "にこにこ is not shown" in page.inner_text("#marks .warning")
    assert "しょんぼり (sad)" in page.evaluate("document.getElementById('timeline').textContent")


def test_adding_a_sentence_while_it_plays_goes_on_from_the_frame_on_screen(page):
    view = page.frame_locator("#view")
    page.wait_for_function("document.getElementById('view').contentWindow.__t2a.time > 1.5", timeout=30000)
    page.fill("#add", "そして座る。")
    at = page.evaluate("document.getElementById('view').contentWindow.__t2a.time")
    page.click("#add-btn")
    page.wait_for_function("window.__studio.renders >= 2 && !window.__studio.busy", timeout=30000)
    now = page.evaluate("document.getElementById('view').contentWindow.__t2a.time")
    assert page.input_value("#text").endswith("そして座る。")
    assert page.evaluate("window.__studio.table.map(e => e.verb)")[-1] == "座る"
    assert now >= at - 0.05  # not restarted from 0
    assert page.evaluate("document.getElementById('view').contentWindow.__t2a.playing")
    assert view.locator("body").get_attribute("data-ready") == "1"


def test_the_exported_bvh_reads_back(page, tmp_path):
    with page.expect_download() as dl:
        page.click("#export")
    path = tmp_path / dl.value.suggested_filename
    dl.value.save_as(path)
    motion = parse_bvh(path.read_text(encoding="utf-8"))
    assert path.name == "animation.bvh" and motion.duration > 3.0


def test_a_shared_link_opens_with_its_text(browser, studio):
    pg = browser.new_page()
    pg.goto(studio + "?text=" + "太郎は歩く。")
    pg.wait_for_function("window.__studio && window.__studio.renders >= 1", timeout=30000)
    assert pg.input_value("#text") == "太郎は歩く。"
    assert pg.evaluate("window.__studio.table.map(e => e.verb)") == ["歩く"]
    pg.close()


def test_another_site_can_neither_frame_the_studio_nor_post_to_it(browser, studio, tmp_path):
    """Another page (here a file:// page, another origin) frames the studio: the browser shows nothing of it
    (X-Frame-Options, frame-ancestors). Its form posts JSON-looking text/plain to the studio: refused, nothing
    animated (issue 41: such a "simple" request was served when the browser sent no Origin)."""
    evil = tmp_path / "evil.html"
    evil.write_text(f'<iframe id="f" src="{studio}"></iframe>'
                    f'<form id="x" method="POST" action="{studio}api/animate" enctype="text/plain">'
                    '<input name=\'{"text": "太郎は歩く。", "x": "\' value=\'"}\'></form>', encoding="utf-8")
    pg = browser.new_page()
    pg.goto(evil.as_uri())
    pg.wait_for_timeout(1500)
    framed = [f for f in pg.frames if f != pg.main_frame]
    assert framed and all(f.evaluate("document.getElementById('text')") is None for f in framed
                          if not f.url.startswith("chrome-error"))
    with pg.expect_navigation() as nav:
        pg.evaluate("document.getElementById('x').submit()")
    answer = nav.value
    assert answer is not None and answer.status in (403, 415) and "__t2a" not in pg.content()
    pg.close()


def test_the_page_sends_its_session_token(page):
    """The page's own requests carry the token it was served (every one above would be refused without it)."""
    token = page.evaluate("document.querySelector('meta[name=\"t2a-token\"]').content")
    with page.expect_request(lambda r: r.url.endswith("/api/animate")) as req:
        page.fill("#text", "太郎は跳ぶ。")
    assert len(token) > 30 and req.value.headers.get("x-studio-token") == token
    assert page.get_attribute("#view", "sandbox") == "allow-scripts allow-same-origin"


def _row(page, verb):
    return page.evaluate(f"window.__studio.table.find(e => e.verb === '{verb}')")


def test_moving_a_bar_moves_the_motion_in_the_time_table_and_the_animation(page):
    before, length = _row(page, "喜ぶ"), page.evaluate("document.getElementById('view').contentWindow.__t2a.duration")
    page.locator('#timeline rect.bar[data-verb="喜ぶ"]').scroll_into_view_if_needed()
    bar = page.locator('#timeline rect.bar[data-verb="喜ぶ"]').bounding_box()
    page.mouse.move(bar["x"] + 20, bar["y"] + bar["height"] / 2)
    page.mouse.down()
    page.mouse.move(bar["x"] + 120, bar["y"] + bar["height"] / 2, steps=5)
    page.mouse.up()
    page.wait_for_function("window.__studio.renders >= 2 && !window.__studio.busy", timeout=30000)
    after = _row(page, "喜ぶ")
    assert after["start"] > before["start"] + 0.3  # later by the drag
    assert page.evaluate("document.getElementById('view').contentWindow.__t2a.duration") > length + 0.3
    assert page.evaluate("Object.values(window.__studio.edits)")[0]["verb"] == "喜ぶ"
    # the edit is kept while the text changes: appending a sentence keeps 喜ぶ late
    page.fill("#add", "そして座る。")
    page.click("#add-btn")
    page.wait_for_function("window.__studio.renders >= 3 && !window.__studio.busy", timeout=30000)
    assert _row(page, "喜ぶ")["start"] == pytest.approx(after["start"], abs=0.05)


def test_clicking_a_bar_changes_how_it_joins(page):
    assert _row(page, "蹴る")["method"] == "transition"
    page.locator('#timeline rect.bar[data-verb="蹴る"]').click()
    page.select_option("#method", "connection")
    page.wait_for_function("window.__studio.renders >= 2 && !window.__studio.busy", timeout=30000)
    kick, run = _row(page, "蹴る"), _row(page, "走る")
    assert kick["method"] == "connection" and kick["start"] >= run["end"] - 1e-6


def test_an_unknown_verb_is_underlined_with_what_may_stand_in_each_previewable(page):
    page.fill("#text", "太郎は公園をぶらついて、泳ぐ。")
    page.wait_for_function("document.querySelectorAll('#marks u.unknown').length === 2", timeout=30000)
    assert page.locator("#marks u.unknown").all_inner_texts() == ["ぶらつい", "泳ぐ"]
    standin = page.locator("#marks button.standin")
    assert standin.count() == 1 and standin.inner_text() == "stand-in 歩く"  # ぶらつく has one, 泳ぐ none
    n = page.evaluate("window.__studio.renders")
    standin.click()
    page.wait_for_function("window.__studio.previewing === '歩く'", timeout=30000)
    assert page.input_value("#text") == "太郎は公園をぶらついて、泳ぐ。"  # the text stays as written
    assert page.evaluate("window.__studio.renders") == n


def test_the_library_is_searched_and_a_verb_previewed(page):
    page.fill("#search", "ジャンプ")
    page.wait_for_function("document.querySelectorAll('#verbs button').length > 0", timeout=30000)
    first = page.locator("#verbs button").first
    assert "ジャンプ" in first.inner_text()
    first.click()
    page.wait_for_function("(window.__studio.previewing || '').includes('ジャンプ')", timeout=30000)


def _drop(page, path: Path, verb: str | None = None):
    """Hand ``path`` to the page as a drop does (a File in the page), answering the verb prompt."""
    if verb is not None:
        page.once("dialog", lambda d: d.accept(verb))
    data = list(path.read_bytes())
    page.evaluate("([name, bytes]) => window.__studio.drop(new File([new Uint8Array(bytes)], name))",
                  [path.name, data])


def test_a_dropped_bvh_is_imported_and_plays(page, tmp_path, library_db):
    """Into the studio's own database (the shared library is only where the test's clip comes from)."""
    import text2anim
    from text2anim.output.bvh_write import format_bvh

    wave = text2anim.animate("太郎は手を振る。", db=library_db)
    (motion,) = wave.motions.values()
    path = tmp_path / "my wave.bvh"
    path.write_text(format_bvh(motion))
    _drop(page, path, "手招きする")
    page.wait_for_function("document.getElementById('dropped').textContent.includes('stored as clip')", timeout=30000)
    assert "my_wave" in page.inner_text("#dropped")
    page.fill("#text", "花子は手招きする。")
    page.wait_for_function("window.__studio.table.length === 1 && window.__studio.table[0].clip === 'my_wave'",
                           timeout=30000)


def test_a_broken_file_dropped_says_why_and_changes_nothing(page, tmp_path):
    bad = tmp_path / "broken.bvh"
    bad.write_text("HIERARCHY\nROOT hips\n{\n")
    _drop(page, bad, "歩く")
    page.wait_for_function("document.getElementById('error').textContent.length > 0", timeout=30000)
    assert "broken.bvh" in page.inner_text("#error") and "Traceback" not in page.inner_text("#error")


def test_a_dropped_vrm_character_is_drawn_skinned_and_animated(page, tmp_path):
    from rig_builders import vrm_file

    avatar = vrm_file(tmp_path / "avatar.vrm")
    _drop(page, avatar)
    page.wait_for_function("document.getElementById('dropped').textContent.includes('this character')",
                           timeout=30000)
    page.wait_for_function("window.__studio3d && window.__studio3d.loads >= 1 && !window.__studio.busy", timeout=60000)
    assert page.locator("#view3d").is_visible() and not page.locator("#view").is_visible()
    t0 = page.evaluate("window.__studio3d.time")
    first = page.locator("#view3d canvas").screenshot()
    page.wait_for_function(f"window.__studio3d.time > {t0} + 0.2", timeout=30000)  # it plays (not a fixed wait)
    assert page.locator("#view3d canvas").screenshot() != first  # and the picture moves
    page.screenshot(path=str(tmp_path / "skinned.png"))
    with page.expect_download() as dl:
        page.select_option("#format", "glb")
        page.click("#export")
    out = tmp_path / dl.value.suggested_filename
    dl.value.save_as(out)
    assert out.read_bytes()[:4] == b"glTF" and out.stat().st_size > avatar.stat().st_size
    page.click("#builtin")  # back to the built-in character, in the viewer
    page.wait_for_function("!document.getElementById('view').hidden && !window.__studio.busy", timeout=30000)


def test_the_things_of_a_scene_show_in_the_viewer_the_top_view_and_on_a_dropped_character(page, tmp_path):
    """The things the text names (the scene stage's: a chair under the sitter, a book in the hand) are drawn in
    the viewer, in the live top view and, on a dropped character, in the skinned view with their names."""
    from rig_builders import vrm_file

    page.fill("#text", "太郎は椅子に座って本を読む。")
    page.wait_for_function("window.__studio.renders >= 2 && !window.__studio.busy", timeout=30000)
    view = page.frame_locator("#view")
    assert "椅子" in view.locator("#legend").inner_text() and "本" in view.locator("#legend").inner_text()
    names = page.evaluate("JSON.parse(document.getElementById('view').contentDocument"
                          ".getElementById('t2a-data').textContent).props.map(p => p.name)")
    assert names == ["椅子", "本"]
    # the top view: the actor's path, the chair's footprint, the book's at the start and the end and its path
    top = page.locator("#topview")
    assert top.locator("polyline.path").count() == 1 and top.locator("polyline.thing-path").count() == 1
    assert top.locator(".foot").count() == 3
    marker, api = top.locator("circle.now").first, "document.getElementById('view').contentWindow.__t2a"

    def at(t):  # the actor's marker, the viewer paused at t
        page.evaluate(f"{api}.pause(); {api}.seek({t})")
        page.wait_for_function(f"window.__studioTop.time === {api}.time", timeout=5000)
        return [float(marker.get_attribute(k)) for k in ("cx", "cy")]

    assert at(0) != at(page.evaluate(f"{api}.duration"))  # it follows the time on screen
    page.evaluate(f"{api}.play()")
    page.screenshot(path=str(tmp_path / "scene.png"), full_page=True)
    # a dropped character: the GLB drawn by three.js carries the things, each labelled
    _drop(page, vrm_file(tmp_path / "avatar.vrm"))
    page.wait_for_function("window.__studio3d && window.__studio3d.loads >= 1 && !window.__studio.busy", timeout=60000)
    assert page.evaluate("window.__studio3d.props") == ["椅子", "本"]
    labels = page.locator("#view3d .label3d")
    assert labels.all_inner_texts() == ["椅子", "本"] and labels.first.is_visible()
    page.screenshot(path=str(tmp_path / "skinned scene.png"), full_page=True)
    page.click("#builtin")
    page.wait_for_function("document.getElementById('builtin').hidden", timeout=30000)


def test_a_text_of_two_characters_on_a_dropped_character_plays_as_figures_and_says_so(page, tmp_path):
    """The skinned view draws one character; a text with two (a partner, a person only spoken to) is drawn as
    figures, the page saying why, with no error (it showed the zip of the export as a broken GLB)."""
    from rig_builders import vrm_file

    _drop(page, vrm_file(tmp_path / "avatar.vrm"))
    page.wait_for_function("document.getElementById('dropped').textContent.includes('this character')",
                           timeout=30000)
    page.fill("#text", "太郎は花子に近づいて、お辞儀する。")
    page.wait_for_function("document.getElementById('status').textContent.includes('2 characters')", timeout=60000)
    assert page.locator("#view").is_visible() and not page.locator("#view3d").is_visible()
    assert page.locator("#error").inner_text() == ""
    page.screenshot(path=str(tmp_path / "two on a character.png"))
    page.click("#builtin")
