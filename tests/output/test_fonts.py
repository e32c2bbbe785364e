"""Japanese titles on figures: drawn with a CJK font when matplotlib has one, else romanised, never boxes."""
from __future__ import annotations

import pytest

from text2anim.motiondb.readings import reading, romaji

pytest.importorskip("matplotlib")

from text2anim.output import fonts  # noqa: E402
from text2anim.output.sheet import contact_sheet  # noqa: E402
from text2anim.motiondb import MotionDB  # noqa: E402
from text2anim.cli.main import main  # noqa: E402


@pytest.fixture
def latin_only(monkeypatch):
    """The fonts of a machine without a CJK font: DejaVu Sans's own character map (read from the file)."""
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    latin = frozenset(FT2Font(font_manager.findfont(fonts.BASE_FAMILY)).get_charmap())
    assert ord("a") in latin and ord("踊") not in latin
    monkeypatch.setattr(fonts, "available", lambda: (None, latin))
    return latin


@pytest.mark.parametrize("word, expected", [
    ("踊る", "odoru"), ("ジャンプする", "janpusuru"), ("キャッチする", "kyatchisuru"), ("しゃがむ", "shagamu"),
    ("ガッツポーズする", "gattsupoozusuru"), ("手を振る", "tewofuru"), ("立ち止まる", "tachidomaru"),
])
def test_readings_are_romanised_in_hepburn(word, expected):
    assert romaji(reading(word)) == expected


def test_a_title_the_fonts_cannot_draw_falls_back(latin_only):
    assert not fonts.drawable("dance: 踊る") and fonts.drawable("dance: odoru")
    assert fonts.label("dance: 踊る", "dance: odoru") == "dance: odoru"
    assert fonts.label("dance: 踊る/ダンスする (default)") == "dance: (default)"  # no alternative: what can be drawn
    assert fonts.label("踊る", fallback="clip") == "clip"
    with_cjk = latin_only | {ord(c) for c in "踊る"}
    assert fonts.label("dance: 踊る", "dance: odoru", chars=with_cjk) == "dance: 踊る"


def _sheet(motion, path, **kw) -> bytes:
    contact_sheet(motion, path, **kw)
    return path.read_bytes()


def test_contact_sheet_draws_the_romanised_title_without_a_cjk_font(tmp_path, latin_only, record):
    m = record("dance", ("踊る",)).motion
    japanese = _sheet(m, tmp_path / "a.png", title="dance: 踊る", alt_title="dance: odoru")
    romanised = _sheet(m, tmp_path / "b.png", title="dance: odoru")
    assert japanese == romanised


def test_contact_sheet_keeps_a_title_the_fonts_can_draw(tmp_path, monkeypatch, latin_only, record):
    monkeypatch.setattr(fonts, "available", lambda: (None, latin_only | {ord(c) for c in "踊る"}))
    m = record("dance", ("踊る",)).motion
    japanese = _sheet(m, tmp_path / "a.png", title="dance: 踊る", alt_title="dance: odoru")
    assert japanese != _sheet(m, tmp_path / "b.png", title="dance: odoru")


def test_db_preview_titles_a_sheet_in_romaji_without_a_cjk_font(tmp_path, db_url, latin_only, record, capsys):
    clip = record("dance", ("踊る", "ダンスする"))
    with MotionDB.open(db_url, seed=False) as db:
        db.add([clip])
        info = db.info("dance")
        motion = db.load(info)
    assert main(["db", "preview", "dance", "-o", str(tmp_path / "cli.png"), "--db", db_url]) == 0
    title = f"dance: odoru/dansusuru ({info.character}, {info.frames} frames, {info.fps:g} fps)"
    expected = _sheet(motion, tmp_path / "direct.png", title=title, core=info.core)
    assert (tmp_path / "cli.png").read_bytes() == expected
