"""Japanese on a machine without a Japanese font: the page embeds the glyphs it shows, and contact sheets
draw with the font the package ships (a subset of Noto Sans CJK JP, SIL OFL 1.1), never boxes (the sheets:
tests/output/test_fontfiles.py)."""
from __future__ import annotations

import base64
import io
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from fontTools.ttLib import TTFont

from text2anim.output import embedded_font
from text2anim.output.viewer import render_html

CHROMIUM = "/usr/bin/chromium"
FACE = re.compile(r'@font-face \{ font-family: "t2a-jp";.*?url\(data:font/woff;base64,([A-Za-z0-9+/=]+)\)')
README = Path(__file__).resolve().parents[2] / "README.md"


@pytest.fixture(scope="module")
def page(library_db):
    import text2anim

    anim = text2anim.animate("太郎は走って、ボールを蹴る。3秒後に花子が手を振る。", db=library_db)
    return anim, render_html(anim.tracks(), anim.spans(), title=anim.text, props=anim.props())


def _shown(anim) -> set[str]:
    """What the page shows in Japanese: its title, the actors' names, the time table's labels, the things."""
    text = anim.text + "".join(t.name for t in anim.tracks()) + "".join(s.label for s in anim.spans())
    text += "".join(p.name for p in anim.props())
    return {c for c in text if ord(c) >= embedded_font.CJK_FROM}  # below it (→, …) every font draws them


def test_the_page_carries_the_glyphs_of_the_japanese_it_shows(page):
    anim, html = page
    faces = FACE.findall(html)
    assert len(faces) == 1
    font = TTFont(io.BytesIO(base64.b64decode(faces[0])))
    cmap = font.getBestCmap()
    shown = _shown(anim)
    assert {"太", "郎", "蹴", "花", "振", "ボ"} <= shown
    assert {c for c in shown if ord(c) not in cmap} == set()
    assert len(cmap) < 3 * len(shown) + 20  # a subset for this page, not the shipped font
    assert font["name"].getDebugName(13).startswith("This Font Software is licensed under the SIL Open Font License")
    assert len(faces[0]) < 40_000  # base64 bytes for about 40 characters


def test_a_page_without_japanese_embeds_no_font(library_db):
    from text2anim.motiondb.library import builtin_clips

    walk = next(c for c in builtin_clips() if c.name == "walk").motion
    assert "@font-face" not in render_html(walk, title="walk")


def test_the_font_ships_with_its_licence_and_the_readme_names_it():
    path = embedded_font.font_path()
    licence = path.with_name(path.stem + ".LICENSE.txt")
    assert path.is_file() and licence.is_file()
    assert "SIL Open Font License" in licence.read_text(encoding="utf-8")
    assert path.stat().st_size < 2_000_000
    readme = README.read_text(encoding="utf-8")
    assert "Noto Sans CJK JP" in readme and "SIL Open Font License" in readme and licence.name in readme


@pytest.mark.skipif(not Path(CHROMIUM).exists(),
                    reason=f"{CHROMIUM} not installed (apt-get install chromium); the page is not tested in a browser")
def test_chromium_draws_the_pages_japanese_with_the_embedded_font(page, tmp_path):
    """The fonts Chromium used for the title, the legend and the table (DevTools' platform fonts): every
    Japanese glyph is drawn by a Japanese font, the page's own when the machine has none."""
    playwright = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed (pip install '.[test]')")
    anim, html = page
    path = tmp_path / "page.html"
    path.write_text(html, encoding="utf-8")
    system_ja = bool(shutil.which("fc-list")) and bool(
        subprocess.run(["fc-list", ":lang=ja"], capture_output=True, text=True).stdout.strip())
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, headless=True, args=["--no-sandbox"])
        page_ = browser.new_page(viewport={"width": 1000, "height": 700})
        page_.goto(path.as_uri())
        page_.wait_for_function("document.body.dataset.ready === '1'", timeout=30000)
        loaded = page_.evaluate("[...document.fonts].filter(f => f.family.replace(/\"/g, '') === 't2a-jp')"
                                ".map(f => f.status)")
        cdp = page_.context.new_cdp_session(page_)
        cdp.send("DOM.enable")
        cdp.send("CSS.enable")
        root = cdp.send("DOM.getDocument")["root"]["nodeId"]
        used: dict[str, int] = {}
        for selector in ("#title", "#legend .actor span:last-child"):
            node = cdp.send("DOM.querySelector", {"nodeId": root, "selector": selector})["nodeId"]
            for f in cdp.send("CSS.getPlatformFontsForNode", {"nodeId": node})["fonts"]:
                key = "embedded" if f["isCustomFont"] else f["familyName"]
                used[key] = used.get(key, 0) + f["glyphCount"]
        browser.close()
    assert loaded == ["loaded"]
    japanese = sum(1 for c in anim.text if ord(c) > 0x7F) + sum(1 for c in "太郎" if c)
    latin = {k: v for k, v in used.items() if k != "embedded" and not re.search(r"CJK|JP|Gothic|Hiragino|Meiryo", k)}
    if not system_ja:
        assert used.get("embedded", 0) >= japanese, used
    assert sum(latin.values()) <= sum(1 for c in anim.text if ord(c) <= 0x7F), used
