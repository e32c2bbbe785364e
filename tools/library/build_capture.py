"""Rebuild ``capture.npz`` from the CMU capture and the cut list ``capture.toml``.

Run from a checkout (``../shared/mocap/cmu`` next to it, or ``--cmu DIR``)::

    python tools/library/build_capture.py [--cmu DIR] [--out FILE]

For every take named in the cut list (each file read once), then every clip cut from it:

1. read the BVH (metres), drop the added T-pose frame 0;
2. put the take's floor at ``y = 0`` (:func:`core.floor.place_on_floor`, from the whole
   take's foot contacts), retarget it onto the built-in character
   (:func:`core.retarget.retarget`: world rotations carried over, hips scaled by leg length;
   without its IK re-placing of ankles and wrists, which flips a nearly straight leg's twist)
   and put that on the floor again (the floored take is kept beside it);
3. low-pass the take where the cut list asks (``lowpass = Hz``: takes with capture glitches,
   :mod:`smooth`), cut the clip's seconds (with ``blend`` seconds before them for a blended loop);
4. resample to 30 fps (slerp), give swinging feet back the capture's own clearance
   (:func:`core.clearance.keep_clearance`: the character's longer foot points lower), hold planted feet
   still, keep swinging feet clear of the floor and feet, hands and their tips above it
   (:func:`feet.lock_feet`, :func:`core.clearance.clear_swings`, :func:`core.clearance.clear_floor`);
5. turn it about +Y and move it so it starts at the origin facing +Z (``face = "travel"``:
   its travel points +Z);
6. a looping clip has its last ``blend`` seconds blended into the frames before the cut, so
   its last frame flows into its first: in place (``loop = "blend"``, the idle) or moved on by
   the cycle's travel (``loop = "stride"``, a gait cycle), so the synthesizer finds nothing
   to correct at the seam; a dance (``loop = "spot"``) has its net travel taken out first and
   loops on the spot, turned by its own net turn (:func:`spot_loop`); a ``cycle`` of the cut is
   played ``cycles`` more times (:func:`repeat_cycle`: a wave's swing);
7. a clip that ``starts_from`` another (standing up after sitting down) is turned to that
   clip's last heading and eased out of its last pose over ``ease`` seconds.

Contacts are computed when the clips are stored (:func:`motiondb.store.prepare_record`).
The output is a zip of ``.npy`` arrays with fixed names, order and timestamps: the same
inputs give the same bytes.
"""
from __future__ import annotations

import argparse
import io
import sys
import zipfile
from pathlib import Path

from text2anim import reproducible

reproducible.pin()  # before numpy: tests compare the shipped arrays bytewise with a fresh build, pinned alike

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core.bvh import read_bvh
from text2anim.core.clearance import clear_floor, keep_clearance, clear_swings
from text2anim.core.contacts import detect_contacts
from text2anim.core.easing import smoothstep
from text2anim.core.floor import place_on_floor
from text2anim.core.metrics import skating_ratio_gmd
from text2anim.core.motion import Motion
from text2anim.core.retarget import retarget

from text2anim.motiondb.library.capture import ARRAYS, FPS, Cut, cut_list
from text2anim.motiondb.library.skeleton import canonical_skeleton

from feet import lock_feet  # this folder's modules: run as a script, the folder is on sys.path
from smooth import lowpass

#: Rate of the CMU files (their Frame Time).
SOURCE_FPS = 120.0
#: Seconds over which the facing at a clip's start is averaged (the pelvis swings in gait).
FACING_WINDOW = 0.3
DEFAULT_CMU = Path(__file__).resolve().parents[2] / ".." / "shared" / "mocap" / "cmu"


def load_take(path: Path) -> tuple[Motion, Motion]:
    """A CMU take on the built-in skeleton, and as captured, each with its floor at ``y = 0``, at 120 fps."""
    m = read_bvh(path, scale="auto").frames(1)
    m, _ = place_on_floor(m)
    # replant=False: the retarget's ankle re-placing flips the thigh's twist by 1.5-2.7 rad for a frame
    # or two where a leg is nearly straight (walk: 10 flips in 4 s); the contacts are cleaned below instead
    on, _ = place_on_floor(retarget(m, canonical_skeleton(), replant=False))
    return on, m


def _frames(t: float, fps: float) -> int:
    return int(round(t * fps))


def _yaw_about_origin(m: Motion, yaw: float, origin: np.ndarray) -> Motion:
    """``m`` turned by ``yaw`` radians about +Y through ``origin`` (x, z), then moved so it is at 0."""
    r = Rotation.from_rotvec([0.0, yaw, 0.0])
    root = m.root_positions - np.array([origin[0], 0.0, origin[1]])
    root = r.apply(root)
    rots = m.rotations.copy()
    rots[:, 0] = (r * Rotation.from_quat(m.rotations[:, 0])).as_quat()
    return m.replace(root_positions=root, rotations=rots)


def _heading(m: Motion, frames: slice) -> float:
    fwd = Rotation.from_quat(m.rotations[frames, 0]).apply([0.0, 0.0, 1.0])
    f = fwd[:, [0, 2]].mean(axis=0)
    return float(np.arctan2(f[0], f[1]))


def face(m: Motion, how: str) -> Motion:
    """``m`` starting at the origin facing +Z (``how="start"``) or travelling along +Z (``"travel"``)."""
    if how == "travel":
        d = m.root_positions[-1] - m.root_positions[0]
        heading = float(np.arctan2(d[0], d[2]))
    else:
        heading = _heading(m, slice(0, max(1, _frames(FACING_WINDOW, m.fps))))
    return _yaw_about_origin(m, -heading, m.root_positions[0, [0, 2]])


def blend_loop(m: Motion, pre: int, travel: np.ndarray | None = None) -> Motion:
    """A loop: ``m``'s first ``pre`` frames lead into the rest, whose last ``pre`` frames are
    blended (smoothstep) into them, moved on by ``travel`` (root ``(dx, dz)`` of one cycle; none
    for a standing loop), so the result's last frame flows into its first (of the next cycle).

    ``m``: ``(pre + N)`` frames; returns ``N`` frames. Root positions blend linearly, rotations by slerp.
    """
    n = m.n_frames - pre
    if pre < 1 or n <= pre:
        raise ValueError(f"a blended loop needs more than {pre} frames after its {pre} lead-in frames")
    body = m.frames(pre)
    lead = m.frames(0, pre)
    lead_root = lead.root_positions.copy()
    if travel is not None:
        lead_root[:, [0, 2]] += travel
    # rising to 1 on the last two frames: they are the lead-in's last two, whose motion flows into frame 0
    u = np.minimum(1.0, (np.arange(pre) + 1) / max(1, pre - 1))
    w = smoothstep(u)
    root = body.root_positions.copy()
    rots = body.rotations.copy()
    tail = slice(n - pre, n)
    root[tail] = (1 - w)[:, None] * root[tail] + w[:, None] * lead_root
    a = Rotation.from_quat(rots[tail].reshape(-1, 4))
    b = Rotation.from_quat(lead.rotations.reshape(-1, 4))
    ww = np.repeat(w, m.skeleton.n_joints)
    rel = (a.inv() * b).as_rotvec() * ww[:, None]
    rots[tail] = (a * Rotation.from_rotvec(rel)).as_quat().reshape(pre, -1, 4)
    return body.replace(root_positions=root, rotations=rots)


def remove_drift(m: Motion, pre: int, drift: np.ndarray) -> Motion:
    """``m`` with the hips' net travel ``drift`` (root ``(dx, dz)``, metres) taken out of frames ``pre``..
    (frame ``pre`` keeps its place, the frame after the last comes back onto it).

    The correction grows with the distance the hips have moved horizontally so far (the cumulative
    path length, normalised to 1 over the cycle): where the dancer stands it does not change, where she
    steps it shortens the steps, so a planted foot that :func:`feet.lock_feet` holds still afterwards
    needs its leg to bend by little. ``m``: ``(pre + N)`` frames; the first ``pre`` (the lead-in) are kept.
    """
    root = m.root_positions.copy()
    step = np.linalg.norm(np.diff(root[pre - 1:, [0, 2]], axis=0), axis=1)  # (N,): into each frame of the cycle
    path = np.concatenate([[0.0], np.cumsum(step[1:])])
    end = path[-1] + step[-1] if len(step) else 1.0  # plus the step out of the last frame (about the one into it)
    root[pre:, [0, 2]] -= np.outer(path / max(end, 1e-9), drift)
    return m.replace(root_positions=root)


def spot_loop(take: Motion, m: Motion, pre: int, j0: int, j1: int) -> Motion:
    """A loop danced on the spot (``loop = "spot"``): the cycle ends where it began, turned by its own
    net turn (so repeated cycles turn in place instead of travelling away).

    ``take``: the whole take at its own rate; ``j0``, ``j1``: the take's frames of the cycle's start and
    of the frame after its end; ``m``: the cut at :data:`FPS` with ``pre`` lead-in frames. The hips' net
    travel over the cycle is removed (:func:`remove_drift`), the lead-in turned by the cycle's turn
    about the cycle's start, and the cycle's last frames blended into it (:func:`blend_loop`).
    """
    drift = take.root_positions[j1, [0, 2]] - take.root_positions[j0, [0, 2]]
    turn = _heading(take, slice(j1, j1 + 1)) - _heading(take, slice(j0, j0 + 1))
    turn = (turn + np.pi) % (2 * np.pi) - np.pi
    m = lock_feet(remove_drift(m, pre, drift), detect_contacts(m))  # planted where they were planted before
    lead = _yaw_about_origin(m.frames(0, pre), turn, m.root_positions[pre, [0, 2]])
    start = m.root_positions[pre] * [1.0, 0.0, 1.0]
    lead = lead.replace(root_positions=lead.root_positions + start)  # turned about the cycle's start, left in place
    m = m.replace(root_positions=np.concatenate([lead.root_positions, m.root_positions[pre:]]),
                  rotations=np.concatenate([lead.rotations, m.rotations[pre:]]))
    return clear_swings(lock_feet(blend_loop(m, pre, None)))


def repeat_cycle(m: Motion, cut: Cut) -> Motion:
    """The cut ``m`` (at :data:`FPS`) with its ``cut.cycle`` played ``cut.cycles`` more times (a wave's
    swing, where the take goes on to something else): the cycle is made to loop in place
    (:func:`blend_loop`, its last ``blend`` seconds blended into the frames before it) and inserted
    before itself, so the frames before the cycle flow into it, each copy into the next, the last
    into the cycle as captured and the rest of the cut.
    """
    assert cut.cycle is not None
    a, b = (_frames(t - cut.cut[0], FPS) for t in cut.cycle)
    pre = _frames(cut.blend, FPS)
    if a < pre:
        raise ValueError(f"{cut.name}: a {cut.blend} s blend needs {cut.blend} s of the cut before its cycle")
    c = blend_loop(m.frames(a - pre, b), pre, None)
    parts = [m.frames(0, a)] + [c] * cut.cycles + [m.frames(a)]
    return m.replace(root_positions=np.concatenate([p.root_positions for p in parts]),
                     rotations=np.concatenate([p.rotations for p in parts]))


#: Seconds over which a mimed climb's support height is averaged (about one step of a ladder or a stair).
MIME_WINDOW = 0.6


def mime_in_place(m: Motion) -> Motion:
    """A climb on the flat: the height of the supporting (lower) foot, averaged over :data:`MIME_WINDOW`,
    taken out of the hips, so the lower foot stays on the floor while the other steps up to the next rung."""
    from scipy.ndimage import uniform_filter1d

    from text2anim.core.floor import lowest_foot_heights

    support = lowest_foot_heights(m).min(axis=1)  # (T,) m: the lower foot's lowest joint
    support = uniform_filter1d(support - support[0], max(1, int(round(MIME_WINDOW * m.fps))), mode="nearest")
    root = m.root_positions.copy()
    root[:, 1] -= support
    return m.replace(root_positions=root)


def cut_clip(take: Motion, captured: Motion, cut: Cut) -> Motion:
    """One clip of the cut list from its (retargeted, floored) take, at :data:`FPS`, facing +Z;
    ``captured``: the take as captured (floored), whose feet's clearance the clip keeps."""
    t0, t1 = cut.cut
    pre = _frames(cut.blend, FPS) if cut.loop else 0  # lead-in frames at FPS, a whole number of take frames each
    i0 = _frames(t0, take.fps) - _frames(pre / FPS, take.fps)
    i1 = _frames(t1, take.fps)
    if i0 < 0:
        raise ValueError(f"{cut.name}: a {cut.blend} s blend needs {cut.blend} s before the cut at {t0}")
    if i1 > take.n_frames - (cut.loop in ("stride", "spot")):
        raise ValueError(f"{cut.name}: the cut ends at {t1} s, after the take's {take.duration:.2f} s")
    src, ref = (lowpass(take, cut.lowpass), lowpass(captured, cut.lowpass)) if cut.lowpass else (take, captured)
    m = keep_clearance(src.frames(i0, i1).resample(FPS), ref.frames(i0, i1).resample(FPS))
    if cut.mime:
        m = mime_in_place(m)
    m = clear_floor(clear_swings(lock_feet(m)))
    if cut.cycle is not None:
        m = clear_swings(lock_feet(repeat_cycle(m, cut)))
    if cut.loop == "spot":
        m = spot_loop(take, m, pre, _frames(t0, take.fps), i1)
    elif cut.loop:
        travel = None
        if cut.loop == "stride":  # one cycle's travel: from the cycle's first frame to the frame after it
            root = take.root_positions
            travel = root[i1, [0, 2]] - root[_frames(t0, take.fps), [0, 2]]
        m = clear_swings(lock_feet(blend_loop(m, pre, travel)))  # the blend moved a planted foot by the frames' difference
    return face(m, cut.face)


def source_gmd(captured: Motion, cut: Cut) -> float:
    """GMD's skating ratio of the cut as captured (floored take, :data:`FPS`, its own lowest foot point)."""
    i0, i1 = _frames(cut.cut[0], captured.fps), _frames(cut.cut[1], captured.fps)
    return skating_ratio_gmd(captured.frames(i0, i1).resample(FPS))


def start_from(m: Motion, before: Motion, n: int) -> Motion:
    """``m`` starting exactly in ``before``'s last pose: turned to its heading, then eased from it.

    Over the first ``n`` frames the local rotations (the root's too) and the root height go
    from ``before``'s last frame to ``m``'s own (smoothstep); ``m``'s travel is kept. So a clip
    cut later from the same take (standing up after sitting down) meets the one before it.
    """
    turn = _heading(before, slice(-1, None)) - _heading(m, slice(0, 1))
    m = _yaw_about_origin(m, turn, m.root_positions[0, [0, 2]])
    u = np.minimum(1.0, np.arange(m.n_frames) / max(1, n))
    w = smoothstep(u)[:, None]
    last = np.broadcast_to(before.rotations[-1], m.rotations.shape).reshape(-1, 4)
    a = Rotation.from_quat(last)
    rel = (a.inv() * Rotation.from_quat(m.rotations.reshape(-1, 4))).as_rotvec()
    ww = np.repeat(w[:, 0], m.skeleton.n_joints)[:, None]
    rots = (a * Rotation.from_rotvec(rel * ww)).as_quat().reshape(m.rotations.shape)
    root = m.root_positions.copy()
    root[:, 1] = (1 - w[:, 0]) * before.root_positions[-1, 1] + w[:, 0] * root[:, 1]
    return m.replace(root_positions=root, rotations=rots)


def _npy(a: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.lib.format.write_array(buf, np.ascontiguousarray(a), allow_pickle=False)
    return buf.getvalue()


def write_arrays(path: Path, arrays: dict[str, np.ndarray]) -> int:
    """A ``.npz`` (zip, deflated) with fixed timestamps and the arrays in the given order; returns bytes."""
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        for name, a in arrays.items():
            info = zipfile.ZipInfo(name + ".npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, _npy(a), compresslevel=9)
    data = buf.getvalue()
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_bytes(data)
    tmp.replace(path)
    return len(data)


def build(cmu: Path, out: Path = ARRAYS, log=print) -> int:
    """Cut, retarget and write every clip of the cut list; returns the file's size in bytes."""
    cuts = cut_list()
    takes: dict[tuple[str, str], tuple[Motion, Motion]] = {}
    arrays: dict[str, np.ndarray] = {}
    built: dict[str, Motion] = {}
    for c in cuts:
        if (c.folder, c.file) not in takes:
            path = (cmu if c.folder == "cmu" else cmu.parent / c.folder) / c.file
            if not path.is_file():
                raise FileNotFoundError(f"{path}: not found (pass --cmu DIR)")
            takes[c.folder, c.file] = load_take(path)
        m = cut_clip(*takes[c.folder, c.file], c)
        if c.starts_from:
            m = lock_feet(start_from(m, built[c.starts_from], _frames(c.ease, FPS)))
        built[c.name] = m
        arrays[f"{c.name}.root"] = m.root_positions.astype(np.float32)
        arrays[f"{c.name}.rot"] = m.rotations.astype(np.float32)
        arrays[f"{c.name}.source_gmd"] = np.array([source_gmd(takes[c.folder, c.file][1], c)], np.float32)
        log(f"  {c.name:16s} {c.trial:7s} {c.cut[0]:6.2f}-{c.cut[1]:6.2f} s  {m.n_frames:4d} frames")
    size = write_arrays(out, arrays)
    log(f"wrote {out}: {len(cuts)} clips, {size / 1e6:.2f} MB")
    return size


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python tools/library/build_capture.py", description=__doc__.split("\n")[0])
    p.add_argument("--cmu", type=Path, default=DEFAULT_CMU, help="folder of the CMU BVH files (../shared/mocap/cmu)")
    p.add_argument("--out", type=Path, default=ARRAYS, help="where to write the arrays (the package's capture.npz)")
    args = p.parse_args(argv)
    try:
        build(args.cmu.resolve(), args.out)
    except (FileNotFoundError, ValueError) as exc:
        print(f"build: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
