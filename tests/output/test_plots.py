"""The speed-curve figure (Fig. 5) and the Gantt chart: written whole, of the asked size, no warnings."""
from __future__ import annotations

import sys

import numpy as np
import pytest

from shared_data import cmu
from text2anim.core import read_bvh
from text2anim.core.atomic import OutputError
from text2anim.output.viewer import Span

mpimg = pytest.importorskip("matplotlib.image")
from text2anim.output import plots  # noqa: E402


@pytest.fixture(scope="module")
def walk():
    return read_bvh(cmu("02_01_walk"), drop_first=True)


@pytest.fixture(scope="module")
def kick():
    return read_bvh(cmu("10_01_kick"), drop_first=True)


SPANS = [
    Span("太郎", "1 歩く (initial)", 0.0, 2.8, alt="1 walk (initial)"),
    Span("太郎", "2 蹴る (transition)", 2.2, 5.0),
    Span("太郎", "blend", 2.2, 2.7, "blend", "lower"),
    Span("太郎", "blend", 2.3, 2.9, "blend", "upper"),
    Span("太郎", "3 喜ぶ (connection)", 4.8, 6.5),
    Span("太郎", "blend", 4.8, 5.2, "blend"),
    Span("花子", "1 蹴る (initial)", 0.0, 6.6),
    Span("花子", "2 手を振る (composition)", 1.0, 3.0),
    Span("花子", "blend", 1.0, 1.4, "blend", "right_arm"),
]


def _png(path):
    img = mpimg.imread(path)
    assert img.ndim == 3
    return img


def test_speed_figure(tmp_path, walk, kick, strict):
    out = tmp_path / "speeds.png"
    plots.plot_speeds({"optimal": walk, "crossfade": kick}, out, SPANS, title="太郎は歩いて、ボールを蹴る。",
                      size=(1000, 600))
    img = _png(out)
    assert img.shape[:2] == (600, 1000)
    assert img[..., :3].std() > 0.05  # not blank
    # the two curves are drawn in their colours
    for hexcol in plots.LINE_COLORS[:2]:
        rgb = np.array([int(hexcol[i:i + 2], 16) for i in (1, 3, 5)]) / 255
        assert (np.abs(img[..., :3] - rgb).max(axis=-1) < 0.1).sum() > 500
    assert [p.name for p in tmp_path.iterdir()] == ["speeds.png"]


def test_speed_figure_of_one_motion_and_svg(tmp_path, walk, strict):
    plots.plot_speeds(walk, tmp_path / "one.svg")
    text = (tmp_path / "one.svg").read_text()
    assert text.lstrip().startswith("<?xml") and "upper body speed" in text


def test_gantt(tmp_path, strict):
    out = tmp_path / "gantt.png"
    plots.plot_gantt(SPANS, out, title="time table", width=900)
    img = _png(out)
    assert img.shape[1] == 900 and 150 < img.shape[0] < 600
    upper = np.array([int(plots.UPPER_COLOR[i:i + 2], 16) for i in (1, 3, 5)]) / 255
    assert (np.abs(img[..., :3] - upper).max(axis=-1) < 0.22).sum() > 100  # blends drawn (alpha 0.8)


def test_without_a_cjk_font_labels_fall_back_quietly(tmp_path, monkeypatch, walk, strict):
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    latin = frozenset(FT2Font(font_manager.findfont(plots.BASE_FAMILY)).get_charmap())
    monkeypatch.setattr(plots, "_fonts", lambda: (None, latin))
    assert plots._label("1 歩く (initial)", "1 walk (initial)") == "1 walk (initial)"
    assert plots._label("2 蹴る (transition)") == "2 (transition)"
    assert plots._label("太郎", fallback="actor 1") == "actor 1"
    assert plots._label("kick_ball") == "kick_ball"
    plots.plot_speeds({"提案手法": walk}, tmp_path / "s.png", SPANS, title="太郎")
    plots.plot_gantt(SPANS, tmp_path / "g.png", title="太郎")
    assert _png(tmp_path / "g.png").shape[1] == 1200


def test_missing_folder_is_a_user_facing_error(tmp_path, walk):
    with pytest.raises(OutputError) as e:
        plots.plot_speeds(walk, tmp_path / "no" / "such" / "s.png")
    assert e.value.user_facing and "does not exist" in str(e.value)
    with pytest.raises(OutputError):
        plots.plot_gantt(SPANS, tmp_path / "no" / "g.png")


def test_bad_requests_are_user_facing(tmp_path, walk):
    for call in (lambda: plots.plot_speeds(walk, tmp_path / "s.jpeg2000"),
                 lambda: plots.plot_gantt([], tmp_path / "g.png"),
                 lambda: plots.plot_speeds({}, tmp_path / "s.png")):
        with pytest.raises(plots.PlotError) as e:
            call()
        assert e.value.user_facing
    assert list(tmp_path.iterdir()) == []


def test_a_failed_plot_leaves_the_old_file(tmp_path, monkeypatch, walk):
    from matplotlib.figure import Figure

    out = tmp_path / "s.png"
    out.write_bytes(b"old")

    def boom(self, *a, **k):
        raise RuntimeError("disk full halfway")

    monkeypatch.setattr(Figure, "savefig", boom)
    with pytest.raises(RuntimeError):
        plots.plot_speeds(walk, out)
    assert out.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["s.png"]


def test_without_matplotlib_the_error_says_what_to_install(monkeypatch, tmp_path, walk):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # what Python does for a package it cannot import
    with pytest.raises(plots.PlotDependencyError) as e:
        plots.plot_speeds(walk, tmp_path / "s.png")
    assert e.value.user_facing and "pip install 'text2anim[plot]'" in str(e.value)
