"""BVH reading and writing: real CMU files and the awkward cases real files contain."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from shared_data import CMU_FILES, cmu, requires_cmu
from text2anim.core import BVHError, parse_bvh, read_bvh
from text2anim.core.bvh import CMU_UNIT, parse_channels
from text2anim.output.bvh_write import format_bvh, write_bvh


@requires_cmu
@pytest.mark.parametrize("path", CMU_FILES, ids=lambda p: p.stem)
def test_every_cmu_file_round_trips(path):
    m = read_bvh(path)
    again = parse_bvh(format_bvh(m))
    assert again.skeleton.names == m.skeleton.names
    assert again.skeleton.channels == m.skeleton.channels
    assert len(again.skeleton.end_sites) == len(m.skeleton.end_sites)
    assert again.n_frames == m.n_frames
    assert again.fps == pytest.approx(m.fps, rel=1e-6)
    np.testing.assert_allclose(again.positions, m.positions, atol=1e-6)
    np.testing.assert_allclose(again.end_site_positions(), m.end_site_positions(), atol=1e-6)



@requires_cmu
def test_raw_channels_are_the_files_numbers_and_rotations_are_scipys():
    path = cmu("16_35_run")
    text = path.read_text()
    skel, frame_time, values = parse_channels(text, str(path))
    lines = [ln for ln in text.split("Frame Time:")[1].splitlines()[1:] if ln.strip()]
    assert frame_time == float(text.split("Frame Time:")[1].split()[0])
    assert values.shape == (len(lines), sum(len(c) for c in skel.channels))
    for k in (0, len(lines) // 2, len(lines) - 1):
        assert np.array_equal(values[k], [float(x) for x in lines[k].split()])
    m = parse_bvh(text, scale=1)
    assert np.array_equal(m.skeleton.offsets, skel.offsets)
    col = 0
    for j, chans in enumerate(skel.channels):  # each joint's Euler angles, as scipy turns them into quaternions
        rot = [col + i for i, c in enumerate(chans) if c.endswith("rotation")]
        expect = Rotation.from_euler(skel.rotation_order(j), values[:, rot], degrees=True).as_quat()
        assert np.array_equal(m.rotations[:, j], expect), skel.names[j]
        col += len(chans)

def test_cmu_units_become_metres():
    m = read_bvh(cmu("02_01_walk"), drop_first=True)
    hips_height = m.positions[:, 0, 1].mean()
    assert 0.85 < hips_height < 1.05
    raw = read_bvh(cmu("02_01_walk"), scale=1, drop_first=True)
    assert raw.positions[:, 0, 1].mean() * CMU_UNIT == pytest.approx(hips_height)


def test_drop_first_removes_the_t_pose():
    full = read_bvh(cmu("16_35_run"))
    dropped = read_bvh(cmu("16_35_run"), drop_first=True)
    assert dropped.n_frames == full.n_frames - 1
    np.testing.assert_allclose(dropped.positions, full.positions[1:])


TWO_JOINTS = """hierarchy
root Hips
{
\toffset 0 0 0
\tchannels 6 Zrotation Xposition Yposition Zposition Xrotation Yrotation
\tjoint a:Arm.L-1
\t{
\t\tOFFSET 1 0 0
\t\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
\t\tJOINT Hand
\t\t{
\t\t\tOFFSET 0 2 0
\t\t\tCHANNELS 3 Zrotation Yrotation Xrotation
\t\t\tend site
\t\t\t{
\t\t\t\tOFFSET 0 0 0.5
\t\t\t}
\t\t}
\t}
}
motion
frames: 2
frame time: 3.3333333e-02

0 0 0 0 0 0 0 1 0 0 0 0 0 0 0

90 1 2 3 0 0 0 0.5 0 0 0 0 0 0 90
"""


def test_awkward_but_valid_file():
    text = TWO_JOINTS.replace("\n", "\r\n")
    m = parse_bvh(text, scale=1)
    assert m.skeleton.names == ("Hips", "a:Arm.L-1", "Hand")
    assert m.skeleton.rotation_order(0) == "ZXY" and m.skeleton.rotation_order(1) == "ZXY"
    assert m.fps == pytest.approx(30.0)
    p = m.positions
    # Frame 0: the arm's position channels (0, 1, 0) are added to its offset (1, 0, 0).
    np.testing.assert_allclose(p[0], [[0, 0, 0], [1, 1, 0], [1, 3, 0]], atol=1e-9)
    # Frame 1: root at (1, 2, 3) turned 90 degrees about Z: (x, y) -> (-y, x).
    np.testing.assert_allclose(p[1, 0], [1, 2, 3], atol=1e-9)
    np.testing.assert_allclose(p[1, 1], [0.5, 3, 3], atol=1e-9)  # offset (1, 0.5, 0) turned
    np.testing.assert_allclose(p[1, 2], [-1.5, 3, 3], atol=1e-9)  # hand offset (0, 2, 0) turned
    # The hand's 90-degree X turn takes its end site (0, 0, 0.5) to (0, -0.5, 0), the root's Z turn to (0.5, 0, 0).
    np.testing.assert_allclose(m.end_site_positions()[1, 0], [-1.0, 3, 3], atol=1e-9)
    again = parse_bvh(format_bvh(m), scale=1)
    np.testing.assert_allclose(again.positions, p, atol=1e-6)
    assert again.skeleton.channels == m.skeleton.channels


def test_zero_frames_is_an_empty_motion():
    text = TWO_JOINTS.split("motion")[0] + "MOTION\nFrames: 0\nFrame Time: 0.01\n"
    m = parse_bvh(text, scale=1)
    assert m.n_frames == 0 and m.positions.shape == (0, 3, 3)
    assert parse_bvh(format_bvh(m), scale=1).n_frames == 0


@pytest.mark.parametrize("mutate, message", [
    (lambda t: t.replace("frames: 2", "frames: 3"), "declares 3 frames but has 2"),
    (lambda t: t.replace("frames: 2", "frames: 1"), "declares 1 frames but has 2"),
    (lambda t: t[: t.index("motion")], "unexpected end of file"),
    (lambda t: t[: t.index("end site")], "unexpected end of file"),
    (lambda t: t.replace("JOINT Hand", "JOINT Hips"), "duplicate joint name 'Hips'"),
    (lambda t: t.replace("motion", "ROOT Other\n{\nOFFSET 0 0 0\n}\nmotion"), "more than one ROOT"),
    (lambda t: t.replace("90 1 2 3", "90 1 two 3"), "'two' is not a number"),
    (lambda t: t.replace("90 1 2 3", "90 1 nan 3"), "not a finite number"),
    (lambda t: t.replace("90 1 2 3", "90 1 1_000 3"), "'1_000' is not a number"),  # float() reads these two
    (lambda t: t.replace("90 1 2 3", "90 1 \uff11\uff12 3"), "'\uff11\uff12' is not a number"),
    (lambda t: t.replace("Xrotation Yrotation\n\t\tJOINT", "Qrotation Yrotation\n\t\tJOINT"), "unknown channel"),
    (lambda t: t.replace("frame time: 3.3333333e-02", "frame time: 0"), "frame time must be a positive"),
])
def test_malformed_files_raise_bvherror_with_line(mutate, message):
    with pytest.raises(BVHError, match=r"<bvh>:\d+: .*" + message.replace("(", r"\(")):
        parse_bvh(mutate(TWO_JOINTS), scale=1)


def test_bvherror_names_the_file(tmp_path):
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\nOFFSET 0 0\n")
    with pytest.raises(BVHError, match=r"bad\.bvh:\d+"):
        read_bvh(bad)


def test_z_up_files_become_y_up(tmp_path):
    m = read_bvh(cmu("16_35_run"), drop_first=True)
    # Make a Z-up copy: rotate the whole character so +Y becomes +Z.
    rz = Rotation.from_euler("x", 90, degrees=True)
    skel = m.skeleton
    from text2anim.core import Motion, Skeleton
    zskel = Skeleton(skel.names, skel.parents, rz.apply(np.array(skel.offsets)),
                     tuple((j, rz.apply(np.array(o))) for j, o in skel.end_sites), skel.channels)
    T, J = m.rotations.shape[:2]
    r = Rotation.from_quat(m.rotations.reshape(-1, 4))
    rr = Rotation.concatenate([rz] * len(r))
    zm = Motion(zskel, m.fps, rz.apply(np.array(m.root_positions)), (rr * r * rr.inv()).as_quat().reshape(T, J, 4))
    path = tmp_path / "zup.bvh"
    write_bvh(zm, path)
    back = read_bvh(path, up="z", scale=1)
    np.testing.assert_allclose(back.positions, m.positions, atol=1e-5)


def test_write_is_atomic_and_leaves_nothing_on_error(tmp_path):
    m = read_bvh(cmu("16_35_run"))
    target = tmp_path / "out.bvh"
    write_bvh(m, target)
    assert read_bvh(target).n_frames == m.n_frames
    assert [p.name for p in tmp_path.iterdir()] == ["out.bvh"]
    with pytest.raises(OSError):
        write_bvh(m, tmp_path / "missing" / "out.bvh")
    assert [p.name for p in tmp_path.iterdir()] == ["out.bvh"]
