"""The label under a contact sheet's height strip names the drawing scale only when it is not 1.

A sheet of a normal-size BVH once said "drawn at a person's size, 6 times the character's" (the scale
was overwritten by a loop variable before it was printed)."""
from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")

from matplotlib.figure import Figure  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from text2anim.cli.main import main  # noqa: E402
from text2anim.core.conventions import scaled  # noqa: E402
from text2anim.motiondb.library import builtin_clips  # noqa: E402
from text2anim.core.size import HUMAN_LEG, leg_length  # noqa: E402
from text2anim.output.bvh_write import write_bvh  # noqa: E402
from text2anim.output.sheet import contact_sheet  # noqa: E402


@pytest.fixture
def drawn_texts(monkeypatch):
    """Every text on each figure saved during the test (the sheet's labels as the PNG carries them)."""
    texts: list[str] = []
    save = Figure.savefig

    def spy(fig, *args, **kwargs):
        texts.extend(t.get_text() for t in fig.findobj(Text) if t.get_text())
        return save(fig, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", spy)
    return texts


def _strip(texts: list[str]) -> str:
    strip = [t for t in texts if t.startswith("seconds")]
    assert len(strip) == 1
    return strip[0]


def test_a_normal_size_bvh_is_drawn_as_it_is(tmp_path, monkeypatch, capsys, drawn_texts):
    monkeypatch.setenv("TEXT2ANIM_DB", str(tmp_path / "never.sqlite"))
    walk = next(c for c in builtin_clips() if c.name == "walk").motion
    write_bvh(walk, tmp_path / "walk.bvh")
    assert main(["db", "preview", str(tmp_path / "walk.bvh"), "-o", str(tmp_path / "sheet.png")]) == 0
    assert _strip(drawn_texts) == "seconds (bars: contacts, left above right)"


@pytest.mark.parametrize("height", [0.2, 20.0])
def test_a_character_far_from_a_persons_size_says_how_much_it_was_scaled(tmp_path, drawn_texts, height):
    walk = next(c for c in builtin_clips() if c.name == "walk").motion
    shrink = height / 1.7
    contact_sheet(scaled(walk, shrink), tmp_path / "sheet.png", n=4)
    k = HUMAN_LEG / (leg_length(walk.skeleton) * shrink)
    assert _strip(drawn_texts).endswith(f"; drawn at a person's size, {k:.3g} times the character's")
