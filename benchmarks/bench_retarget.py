"""Clips entering the database clean: floor offsets, retargeting errors, skating before and after.

    python benchmarks/bench_retarget.py [--character 02_01_walk] [FILES...]

Reads CMU captures from ``../shared/mocap/cmu`` (frame 0, the T-pose, dropped)
and does to each what ``db import`` does under one character whose skeleton
is ``--character``'s (subject 02 by default) and, in a second table, under
the built-in skeleton. Printed per file:

- floor: the floor found (cm; the clip is moved down by it) and how
  (``contacts`` or ``lowest``), and the floor found again afterwards;
- bones: the largest bone-length difference to the character's skeleton
  before (cm), and after (always 0: the clip is retargeted onto it);
- legs: the leg-length ratio ``s`` target / source;
- hands, toes, ankles: the largest and 95th-percentile distance (cm) between
  the output's wrists, toe joints or ankles and the source's scaled by ``s``,
  on the frames where a source foot is planted (toes are what retargeting
  places; ankles follow the foot's own shape; toe heights within 6 cm of the
  floor are kept unscaled, ``core.retarget.foot_height``);
- skate: the skating ratio of the source and the output, both resampled to
  30 fps (docs/timetable.md §3): ``core`` is ``core.metrics.skating_ratio`` (floor y = 0); ``gmd``
  is GMD's figure as GMD measures it, above the motion's own lowest foot point
  (``core.metrics.skating_ratio_gmd``);
- twist: the largest frame-to-frame turn of a thigh (rad; a flip of the knee's bend plane shows as
  more than 1);
- cpu: CPU time of what ``db import`` does to a clip (floor, retarget, the capture's clearance; ms), beside wall time.

A third table retargets the built-in library's animation of a few sentences
(a temporary database) onto the test rigs of ``tests/rig_builders.py``
(Mixamo names with an A-pose rest, SMPL, Unreal mannequin, VRM names, and the glTF
characters: a Mixamo GLB as Blender exports it and a VRM 1.0 avatar), with the
same error and skating columns (``--no-rigs`` skips it). A fourth puts that animation on a Mixamo foot
with a mesh (its toe bone 40° down), the feet aligned by their bones and by the mesh's soles
(``core.soles``): the sole's pitch and height on the planted frames.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
CMU = REPO.parent / "shared" / "mocap" / "cmu"
DEFAULT = ("02_01_walk", "02_02_walk", "07_02_walk", "07_04_slowwalk", "08_02_walk", "08_04_slowwalk",
           "09_02_run", "09_05_run", "16_15_walk", "127_07_run", "16_01_jump", "14_27_sit")


def effector_errors(src, out, mapping) -> list[float]:
    """(max, p95) in cm for hands (wrists) on the frames where a source foot is planted, and for each foot's
    toe and ankle on the frames where that foot is planted (a swinging foot is free to differ)."""
    from text2anim.core.contacts import detect_contacts

    fc = detect_contacts(src)
    either = fc.left | fc.right
    res: list[float] = []
    for roles in (("leftHand", "rightHand"), ("leftToes", "rightToes"), ("leftFoot", "rightFoot")):
        frames = [either if r.endswith("Hand") else fc.of(r[:-4]) for r in roles]  # leftToes, leftFoot: left
        e = 100 * np.concatenate([np.linalg.norm(out.positions[f, mapping.target[r]]
                                                 - mapping.scale * src.positions[f, mapping.source[r]], axis=-1)
                                  for r, f in zip(roles, frames)])
        res += [float(e.max()), float(np.percentile(e, 95))] if len(e) else [0.0, 0.0]
    return res


def thigh_twist(m, roles: dict[str, int]) -> float:
    """The largest frame-to-frame turn (rad) of either thigh's world rotation (``roles``: ``{role: joint}``)."""
    from scipy.spatial.transform import Rotation

    R = m.pose.rotations
    out = 0.0
    for j in (roles["leftUpperLeg"], roles["rightUpperLeg"]):
        step = (Rotation.from_matrix(R[1:, j]).inv() * Rotation.from_matrix(R[:-1, j])).magnitude()
        out = max(out, float(step.max(initial=0.0)))
    return out


def row(name: str, target) -> list[str]:
    from text2anim.core.bvh import read_bvh
    from text2anim.core.floor import find_floor, place_on_floor
    from text2anim.core.metrics import skating_ratio, skating_ratio_gmd
    from text2anim.core.retarget import map_skeletons, retarget

    from text2anim.motiondb.bvh_import import conform

    raw = read_bvh(CMU / f"{name}.bvh", drop_first=True)
    t0, c0 = time.perf_counter(), time.process_time()
    out, _ = conform(raw, target, name, "bench")  # as db import does: floor, retarget, the capture's clearance
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    src, floor = place_on_floor(raw)
    mapping = map_skeletons(src.skeleton, target)
    same = src.skeleton.same_hierarchy(target)
    bones = 100 * float(np.abs(np.linalg.norm(src.skeleton.offsets, axis=1)
                               - np.linalg.norm(target.offsets, axis=1)).max()) if same else float("nan")
    after = 100 * float(np.abs(np.linalg.norm(out.skeleton.offsets, axis=1)
                               - np.linalg.norm(target.offsets, axis=1)).max())
    hmax, h95, tmax, t95, amax, a95 = effector_errors(src, out, mapping)
    s30, o30 = src.resample(30), out.resample(30)
    return [name, f"{100 * floor.height:+.2f}", floor.method, f"{100 * find_floor(out).height:+.2f}",
            f"{bones:.2f}", f"{after:.2f}", f"{mapping.scale:.3f}", f"{hmax:.2f}/{h95:.2f}", f"{tmax:.2f}/{t95:.2f}", f"{amax:.2f}/{a95:.2f}",
            f"{skating_ratio(s30):.3f}>{skating_ratio(o30):.3f}", f"{skating_ratio_gmd(s30):.3f}>{skating_ratio_gmd(o30):.3f}",
            f"{thigh_twist(out, mapping.target):.2f}", f"{1000 * cpu:.0f}/{1000 * wall:.0f}"]


SENTENCES = ("太郎は歩く。", "太郎は走って、ボールを蹴る。")


def rig_rows(tmp: Path) -> list[list[str]]:
    import text2anim
    from text2anim.core.metrics import skating_ratio, skating_ratio_gmd
    from text2anim.core.retarget import map_skeletons, retarget

    sys.path.insert(0, str(REPO / "tests"))
    from rig_builders import mixamo_glb, mixamo_rig, smpl_rig, unreal_rig, vrm_file, vrm_rig
    from text2anim.core.bvh import read_bvh
    from text2anim.core.gltf_rig import read_gltf_rig

    rigs = {f.__name__: (read_bvh(f(tmp / f"{f.__name__}.bvh")).skeleton, None)
            for f in (mixamo_rig, smpl_rig, unreal_rig, vrm_rig)}
    for f, suffix in ((mixamo_glb, ".glb"), (vrm_file, ".vrm")):
        gr = read_gltf_rig(f(tmp / f"{f.__name__}{suffix}"))
        rigs[f.__name__] = (gr.skeleton, gr.humanoid or None)
    rows = []
    for text in SENTENCES:
        (src,) = text2anim.animate(text, db=str(tmp / "db.sqlite")).motions.values()
        for name, (skel, roles) in rigs.items():
            c0 = time.process_time()
            out = retarget(src, skel, target_map=roles)
            cpu = time.process_time() - c0
            m = map_skeletons(src.skeleton, skel, target_map=roles)
            hmax, h95, tmax, t95, amax, a95 = effector_errors(src, out, m)
            rows.append([text, name, f"{m.scale:.3f}", f"{hmax:.2f}/{h95:.2f}", f"{tmax:.2f}/{t95:.2f}",
                         f"{amax:.2f}/{a95:.2f}", f"{skating_ratio(src):.3f}>{skating_ratio(out):.3f}",
                         f"{skating_ratio_gmd(src):.3f}>{skating_ratio_gmd(out):.3f}", f"{thigh_twist(out, m.target):.2f}",
                         f"{1000 * cpu:.0f}"])
    return rows


def source_pitch(src) -> list[str]:
    """The built-in body's own feet, for comparison: the toe bone's median pitch on the planted frames above
    its rest pitch (its rest pose stands flat; + heel down), and the lowest foot point (joints and tips)."""
    from text2anim.core.bodyparts import body_map
    from text2anim.core.contacts import detect_contacts
    from text2anim.core.floor import chain_lowest

    planted, rest, cells = detect_contacts(src), src.skeleton.rest_positions(), []
    for side, (ankle, toe) in body_map(src.skeleton).feet.items():
        def pitch(d):
            return np.degrees(np.arctan2(-d[..., 1], np.hypot(d[..., 0], d[..., 2])))
        rise = pitch(rest[toe] - rest[ankle]) - pitch(src.positions[:, toe] - src.positions[:, ankle])
        low = chain_lowest(src, ankle)
        on = planted.of(side)
        cells += [f"{np.median(rise[on]):+.1f}", f"{100 * np.median(low[on]):.1f}/{100 * low.min():.1f}"]
    return cells


def sole_rows(tmp: Path) -> list[list[str]]:
    """The built-in animation on a Mixamo foot whose toe bone points 40° down (ours: 23°), the feet aligned
    by their bones (as before issue 46's soles) and by the mesh's soles (``core.soles``)."""
    import text2anim
    from text2anim.core.contacts import detect_contacts
    from text2anim.core.retarget import retarget
    from text2anim.core.soles import sole_pitch, underside_heights
    from text2anim.export import ExportOptions

    sys.path.insert(0, str(REPO / "tests"))
    from rig_builders import mixamo_feet_glb

    opts = ExportOptions(rig=mixamo_feet_glb(tmp / "feet.glb"))
    rows = []
    for text in SENTENCES:
        (src,) = text2anim.animate(text, db=str(tmp / "db.sqlite")).motions.values()
        rows.append([text, "source", *source_pitch(src), ""])
        for how, soles in (("bone", None), ("sole", opts.soles)):
            c0 = time.process_time()
            out = retarget(src, opts.skeleton, soles=soles)
            cpu = time.process_time() - c0
            planted = detect_contacts(out)
            cells = []
            for role, sole in opts.soles.items():
                on = planted.of(role[:-len("Foot")])
                low = underside_heights(out, sole).min(axis=1)
                cells += [f"{np.median(sole_pitch(out, sole)[on]):+.1f}",
                          f"{100 * np.median(low[on]):.1f}/{100 * low.min():.1f}"]
            rows.append([text, how, *cells, f"{1000 * cpu:.0f}"])
    return rows


def table(rows: list[list[str]], head: list[str]) -> str:
    w = [max(len(r[k]) for r in [head, *rows]) for k in range(len(head))]
    return "\n".join(" ".join(c.ljust(w[k]) for k, c in enumerate(r)) for r in [head, *rows])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*", default=list(DEFAULT), help="CMU clip names (default: a mix of subjects)")
    ap.add_argument("--character", default="02_01_walk", help="the clip whose skeleton is the character's")
    ap.add_argument("--no-rigs", action="store_true", help="skip the table of the built-in animation on test rigs")
    args = ap.parse_args()
    if not CMU.is_dir():
        sys.exit(f"no CMU captures at {CMU}")
    from text2anim.core.bvh import read_bvh
    from text2anim.motiondb.library.skeleton import canonical_skeleton

    head = ["clip", "floor cm", "how", "after", "bones cm", "after", "legs s", "hands cm max/p95",
            "toes max/p95", "ankles max/p95", "skate core 30fps", "skate gmd 30fps", "twist", "cpu/wall ms"]
    for label, target in ((f"character = {args.character}'s skeleton", read_bvh(CMU / f"{args.character}.bvh").skeleton),
                          ("character = the built-in skeleton", canonical_skeleton())):
        print(f"\n## {label}\n")
        print(table([row(n, target) for n in args.files], head))
    if not args.no_rigs:
        import tempfile

        print("\n## the built-in library's animation on the test rigs (30 fps)\n")
        with tempfile.TemporaryDirectory() as tmp:
            print(table(rig_rows(Path(tmp)), ["text", "rig", "legs s", "hands cm max/p95", "toes max/p95",
                                              "ankles max/p95", "skate core", "skate gmd", "twist", "cpu ms"]))
            print("\n## a Mixamo foot on its mesh's soles (tests/rig_builders.mixamo_feet_glb), planted frames\n")
            print(table(sole_rows(Path(tmp)), ["text", "feet by", "left pitch °", "left sole cm med/min",
                                               "right pitch °", "right sole cm med/min", "cpu ms"]))
            print("(pitch: the heel-to-ball line's median rise on the planted frames, + heel down; sole: the "
                  "underside's lowest point, median on the planted frames / lowest over the motion; source: the "
                  "built-in body's toe bone against its rest pitch, and its lowest foot joint or tip)")


if __name__ == "__main__":
    main()
