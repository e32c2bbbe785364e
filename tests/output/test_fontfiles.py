"""A CJK font installed after matplotlib cached its font list is found by file name: contact-sheet and
plot titles are Japanese at once, with that font, not the one the package ships. Asserted both ways: on a
machine with a CJK font file (``apt install fonts-noto-cjk``) and, always, in folders without one (the
package's own font draws them)."""
from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("matplotlib")  # the figures' extra: without it no title is drawn (tests/cli/test_extras.py)

from text2anim.core import read_bvh  # noqa: E402
from text2anim.output import fontfiles, fonts  # noqa: E402
from text2anim.output.sheet import contact_sheet  # noqa: E402

TINY = Path(__file__).resolve().parents[1] / "data" / "walk_tiny.bvh"
ON_THIS_MACHINE = fontfiles.cjk_font_files()


@pytest.fixture
def stale_cache(monkeypatch):
    """matplotlib's font list as cached before any CJK font was installed (and nothing found yet)."""
    from matplotlib import font_manager

    installed = {str(p) for p in ON_THIS_MACHINE}
    fm = font_manager.fontManager
    monkeypatch.setattr(fm, "ttflist", [f for f in fm.ttflist
                                        if f.name not in fonts.CJK_FAMILIES and f.fname not in installed])
    fm._findfont_cached.cache_clear()
    fonts.available.cache_clear()
    yield
    fonts.available.cache_clear()
    fm._findfont_cached.cache_clear()


def _titles_differ(tmp_path) -> bool:
    """Whether a sheet titled 踊る differs from one titled in romaji (the same when no font draws 踊る)."""
    m = read_bvh(TINY, drop_first=True)
    contact_sheet(m, tmp_path / "ja.png", title="dance: 踊る", alt_title="dance: odoru", n=3)
    contact_sheet(m, tmp_path / "romaji.png", title="dance: odoru", n=3)
    return (tmp_path / "ja.png").read_bytes() != (tmp_path / "romaji.png").read_bytes()


def test_without_a_cjk_font_file_titles_are_drawn_with_the_shipped_font(tmp_path, monkeypatch, stale_cache):
    """No CJK font on the machine: the package's own (a subset of Noto Sans CJK JP) draws the title; a character
    outside it is still never a box."""
    from text2anim.output import embedded_font

    monkeypatch.setattr(fontfiles, "FONT_DIRS", (str(tmp_path / "fonts"),))
    (tmp_path / "fonts").mkdir()
    (tmp_path / "fonts" / "DejaVuSans.ttf").write_bytes(b"")  # not a CJK font's name: not looked at
    assert fontfiles.cjk_font_files() == []
    cjk, chars = fonts.available()
    assert cjk == embedded_font.FAMILY and {ord(c) for c in "踊る太郎"} <= chars
    assert _titles_differ(tmp_path)
    assert fonts.label("dance: 踊る/𠮷", "dance: odoru") == "dance: odoru"  # 𠮷 is outside JIS X 0208


def test_a_cjk_font_installed_after_the_cache_is_found_by_its_file(tmp_path, monkeypatch, stale_cache, caplog):
    if not ON_THIS_MACHINE:  # nothing installed: the machine's folders give the shipped font
        from text2anim.output import embedded_font

        assert fonts.available()[0] == embedded_font.FAMILY and _titles_differ(tmp_path)
        return
    folder = tmp_path / "fonts" / "opentype"
    folder.mkdir(parents=True)
    for path in fontfiles.weights_of(ON_THIS_MACHINE[0]):  # as installed: the family's weights side by side
        (folder / path.name).symlink_to(path)
    monkeypatch.setattr(fontfiles, "FONT_DIRS", (str(tmp_path / "fonts"),))
    cjk, chars = fonts.available()
    assert cjk is not None and {ord(c) for c in "踊る太郎"} <= chars
    assert fonts.families() == [fonts.BASE_FAMILY, cjk]
    with caplog.at_level("WARNING", logger="matplotlib"):
        assert _titles_differ(tmp_path)
    assert [r.getMessage() for r in caplog.records if r.name.startswith("matplotlib")] == []  # bold found too


def test_the_most_wanted_file_comes_first(tmp_path):
    for name in ("wqy-zenhei.ttc", "ipaexg.ttf", "NotoSansCJK-Bold.ttc", "NotoSansCJK-Regular.ttc", "a.ttf"):
        (tmp_path / name).write_bytes(b"")
    assert [p.name for p in fontfiles.cjk_font_files([str(tmp_path)])] == [
        "NotoSansCJK-Regular.ttc", "ipaexg.ttf", "wqy-zenhei.ttc"]
