"""The scene seen from above: its numbers (paths, facings, elements, footprints), the picture and ``--top-view``."""
from __future__ import annotations

import numpy as np
import pytest

from cli_run import assert_clean_error, text2anim as run
from scene_props import scene
from text2anim.output.topview import plot_top_view, top_view
from text2anim.output.viewer import PALETTE

mpimg = pytest.importorskip("matplotlib.image")


def _rgb(color: str) -> np.ndarray:
    return np.array([int(color[i:i + 2], 16) for i in (1, 3, 5)]) / 255


def test_the_numbers_follow_the_actors_and_things(library_db):
    anim, (ball, chair) = scene(library_db)
    view = top_view(anim.tracks(), anim.spans(), [ball, chair])
    taro, hanako = view.actors
    assert (taro.name, taro.color, hanako.color) == ("太郎", PALETTE[0], PALETTE[1])
    motion = anim.motions["太郎"]
    np.testing.assert_allclose(taro.path, motion.positions[:, 0][:, [0, 2]])  # the hips, x and z
    assert taro.path[-1, 1] - taro.path[0, 1] > 3  # he runs up +z ...
    assert taro.start_facing[1] > 0.9  # ... facing where he runs
    kick = next(s for s in anim.spans() if s.actor == "太郎" and "蹴る" in s.label)
    label, _, x, z = next(m for m in taro.marks if m[0].endswith("蹴る"))
    f = round(kick.start * motion.fps)
    assert label == kick.label.split(" (")[0] and (x, z) == pytest.approx(tuple(motion.positions[f, 0][[0, 2]]))
    moving, still = view.props
    assert moving.path is not None and np.allclose(moving.path, ball.positions[:, [0, 2]])
    assert moving.start.kind == "circle" and moving.start.radius == pytest.approx(0.11)
    assert still.path is None and still.start.kind == "polygon"
    pts = np.array(still.start.points)
    area = 0.5 * abs(np.dot(pts[:, 0], np.roll(pts[:, 1], 1)) - np.dot(pts[:, 1], np.roll(pts[:, 0], 1)))
    assert area == pytest.approx(0.45 * 0.45, rel=1e-6)  # the chair's seat, seen from above


def test_the_picture_is_of_the_asked_size_and_seen_from_above(tmp_path, library_db, strict):
    anim, props = scene(library_db)
    out = tmp_path / "top.png"
    plot_top_view(anim.tracks(), out, anim.spans(), props, title=anim.text, size=(800, 640))
    img = mpimg.imread(out)[..., :3]
    assert img.shape[:2] == (640, 800)
    where = {}
    for name, color in zip(("太郎", "花子"), PALETTE):
        ys, xs = np.nonzero(np.abs(img - _rgb(color)).max(axis=-1) < 0.08)
        assert len(ys) > 60, f"{name}: {len(ys)} pixels of its path, start dot and arrow"
        where[name] = (xs.mean(), ys.min(), ys.max())
    # 太郎 starts at x = -0.75 m, 花子 at +0.75 m: seen from above with +z up the page, +x is on the left
    assert where["太郎"][0] > where["花子"][0]
    # 太郎 runs 7 m up +z: his path reaches far up the page, 花子 stays near the start
    assert where["太郎"][2] - where["太郎"][1] > 3 * (where["花子"][2] - where["花子"][1])
    ys, xs = np.nonzero(np.abs(img - (0.65 + 0.35 * _rgb(props[1].color))).max(axis=-1) < 0.06)  # the chair, 35 %
    assert len(ys) > 100 and xs.mean() > where["太郎"][0]  # on 太郎's right: the page's right


def test_the_command_writes_it_with_the_others_or_refuses_a_bad_name(tmp_path, library_db):
    proc = run("太郎は歩く。3秒後に花子が走る。", "--top-view", "top.png", "--html", "v.html", "--db", library_db,
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["top.png", "v.html"]
    assert mpimg.imread(tmp_path / "top.png").shape[:2] == (900, 900)
    for bad, says in (("top.jpg", "cannot tell the image format from the suffix; use one of .png, .svg, .pdf"),
                      ("no/top.png", "does not exist")):
        proc = run("太郎は歩く。", "--top-view", bad, "-o", "b.bvh", "--db", tmp_path / "never.sqlite", cwd=tmp_path)
        assert_clean_error(proc, says)
        assert len(proc.stderr.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["top.png", "v.html"]  # nothing else written


def test_the_api_saves_it_all_or_nothing(tmp_path, library_db):
    anim, _ = scene(library_db)
    (tmp_path / "r.json").write_text("old")
    with pytest.raises(Exception):
        anim.save(top_view=tmp_path / "t.png", report=tmp_path / "r.json", html=tmp_path / "missing" / "v.html")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.json"] and (tmp_path / "r.json").read_text() == "old"
    assert anim.save_top_view(tmp_path / "t.svg") == tmp_path / "t.svg"
    assert (tmp_path / "t.svg").read_text().lstrip().startswith("<?xml")
