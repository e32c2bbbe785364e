"""Test rigs made from the built-in skeleton (no downloads): Mixamo names with an A-pose rest, SMPL's 22 joints,
the Unreal mannequin (a root bone above the pelvis), VRM humanoid bone names; each with its own proportions,
as BVH files."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core import Motion, Skeleton, write_bvh
from text2anim.motiondb.library.skeleton import canonical_skeleton


def _rest() -> dict[str, np.ndarray]:
    skel = canonical_skeleton()
    return dict(zip(skel.names, skel.rest_positions()))


def _mid(p: dict, a: str, b: str) -> np.ndarray:
    return (p[a] + p[b]) / 2


def _positions(p: dict) -> dict[str, np.ndarray]:
    """Where a humanoid's joints (by VRM role; ``*Index``: a finger) sit on the built-in body, metres."""
    out = {"hips": p["Hips"], "spine": p["Spine"], "chest": _mid(p, "Spine", "Spine1"), "upperChest": p["Spine1"],
           "neck": p["Neck1"], "head": p["Head"]}
    for side, s in (("left", 1.0), ("right", -1.0)):
        L = "Left" if side == "left" else "Right"
        out.update({f"{side}Shoulder": p["Spine1"] + np.array([0.04 * s, 0.09, 0.0]),
                    f"{side}UpperArm": p[f"{L}Arm"], f"{side}LowerArm": p[f"{L}ForeArm"],
                    f"{side}Hand": p[f"{L}Hand"], f"{side}Index": p[f"{L}HandIndex1"],
                    f"{side}UpperLeg": p[f"{L}UpLeg"], f"{side}LowerLeg": p[f"{L}Leg"],
                    f"{side}Foot": p[f"{L}Foot"], f"{side}Toes": p[f"{L}ToeBase"]})
    return out


def _a_pose(pos: dict[str, np.ndarray], degrees: float = 45.0) -> dict[str, np.ndarray]:
    """Arms lowered by ``degrees`` about the body's forward axis at the shoulder joints."""
    out = dict(pos)
    for side, sign in (("left", -1.0), ("right", 1.0)):
        rot = Rotation.from_euler("z", sign * degrees, degrees=True)
        pivot = pos[f"{side}UpperArm"]
        for part in ("LowerArm", "Hand", "Index"):
            out[f"{side}{part}"] = pivot + rot.apply(pos[f"{side}{part}"] - pivot)
    return out


def _skeleton(rows, pos: dict[str, np.ndarray], channels, ends: dict[str, tuple]) -> Skeleton:
    """``rows``: (name, parent name, role); positions by role; offsets from the parent's position."""
    names = [r[0] for r in rows]
    parents = [-1 if r[1] is None else names.index(r[1]) for r in rows]
    world = np.array([pos[r[2]] if r[2] in pos else np.zeros(3) for r in rows])
    offsets = np.array([world[j] - (world[p] if p >= 0 else 0.0) for j, p in enumerate(parents)])
    end_sites = tuple((names.index(n), np.array(o)) for n, o in ends.items())
    return Skeleton(names, parents, offsets, end_sites, tuple(channels(n, j) for j, n in enumerate(names)))


def _write(skel: Skeleton, path: Path, unit: float = 1.0) -> Path:
    """A one-frame BVH of the rest pose in ``unit`` per metre."""
    rest = Motion(skel.scaled(unit), 30.0, skel.scaled(unit).offsets[:1], np.tile([0.0, 0, 0, 1], (1, skel.n_joints, 1)))
    write_bvh(rest, path)
    return path


def mixamo_rig(path: Path, scale: float = 1.08) -> Path:
    """Mixamo joint names (``mixamorig:``), an A-pose rest, ZXY channels, fingers, 8% taller; written in cm."""
    pos = {k: v * scale for k, v in _a_pose(_positions(_rest())).items()}
    m = "mixamorig:"
    rows = [(m + "Hips", None, "hips"), (m + "Spine", m + "Hips", "spine"), (m + "Spine1", m + "Spine", "chest"),
            (m + "Spine2", m + "Spine1", "upperChest"), (m + "Neck", m + "Spine2", "neck"),
            (m + "Head", m + "Neck", "head")]
    for side, L in (("left", "Left"), ("right", "Right")):
        rows += [(f"{m}{L}Shoulder", m + "Spine2", f"{side}Shoulder"),
                 (f"{m}{L}Arm", f"{m}{L}Shoulder", f"{side}UpperArm"),
                 (f"{m}{L}ForeArm", f"{m}{L}Arm", f"{side}LowerArm"), (f"{m}{L}Hand", f"{m}{L}ForeArm", f"{side}Hand"),
                 (f"{m}{L}HandIndex1", f"{m}{L}Hand", f"{side}Index")]
    for side, L in (("left", "Left"), ("right", "Right")):
        rows += [(f"{m}{L}UpLeg", m + "Hips", f"{side}UpperLeg"), (f"{m}{L}Leg", f"{m}{L}UpLeg", f"{side}LowerLeg"),
                 (f"{m}{L}Foot", f"{m}{L}Leg", f"{side}Foot"), (f"{m}{L}ToeBase", f"{m}{L}Foot", f"{side}Toes")]
    zxy = ("Zrotation", "Xrotation", "Yrotation")
    chans = lambda n, j: (("Xposition", "Yposition", "Zposition") + zxy) if j == 0 else zxy  # noqa: E731
    ends = {m + "Head": (0, 0.17 * scale, 0), m + "LeftToeBase": (0, 0, 0.06), m + "RightToeBase": (0, 0, 0.06)}
    return _write(_skeleton(rows, pos, chans, ends), path, unit=100.0)


def smpl_rig(path: Path, scale: float = 0.93) -> Path:
    """SMPL's 22 body joints by name, children in SMPL's index order, a T-pose, 7% shorter."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    rows = [("pelvis", None, "hips")]
    for side in ("left", "right"):
        rows += [(f"{side}_hip", "pelvis", f"{side}UpperLeg"), (f"{side}_knee", f"{side}_hip", f"{side}LowerLeg"),
                 (f"{side}_ankle", f"{side}_knee", f"{side}Foot"), (f"{side}_foot", f"{side}_ankle", f"{side}Toes")]
    rows += [("spine1", "pelvis", "spine"), ("spine2", "spine1", "chest"), ("spine3", "spine2", "upperChest"),
             ("neck", "spine3", "neck"), ("head", "neck", "head")]
    for side in ("left", "right"):
        rows += [(f"{side}_collar", "spine3", f"{side}Shoulder"), (f"{side}_shoulder", f"{side}_collar", f"{side}UpperArm"),
                 (f"{side}_elbow", f"{side}_shoulder", f"{side}LowerArm"), (f"{side}_wrist", f"{side}_elbow", f"{side}Hand")]
    chans = lambda n, j: Skeleton.default_channels(2)[0 if j == 0 else 1]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)


def unreal_rig(path: Path, scale: float = 1.02) -> Path:
    """Unreal mannequin names: a ``root`` bone at the floor above ``pelvis`` (which has position channels)."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    pos["root"] = pos["hips"] - np.array([0.0, pos["hips"][1] - min(pos["leftToes"][1], pos["leftFoot"][1]), 0.0])
    rows = [("root", None, "root"), ("pelvis", "root", "hips"), ("spine_01", "pelvis", "spine"),
            ("spine_02", "spine_01", "chest"), ("spine_03", "spine_02", "upperChest"), ("neck_01", "spine_03", "neck"),
            ("head", "neck_01", "head")]
    for side, s in (("left", "l"), ("right", "r")):
        rows += [(f"clavicle_{s}", "spine_03", f"{side}Shoulder"), (f"upperarm_{s}", f"clavicle_{s}", f"{side}UpperArm"),
                 (f"lowerarm_{s}", f"upperarm_{s}", f"{side}LowerArm"), (f"hand_{s}", f"lowerarm_{s}", f"{side}Hand"),
                 (f"index_01_{s}", f"hand_{s}", f"{side}Index")]
    for side, s in (("left", "l"), ("right", "r")):
        rows += [(f"thigh_{s}", "pelvis", f"{side}UpperLeg"), (f"calf_{s}", f"thigh_{s}", f"{side}LowerLeg"),
                 (f"foot_{s}", f"calf_{s}", f"{side}Foot"), (f"ball_{s}", f"foot_{s}", f"{side}Toes")]
    full = ("Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation")
    chans = lambda n, j: full if j <= 1 else full[3:]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)


def vrm_rig(path: Path, scale: float = 0.85) -> Path:
    """VRM humanoid bone names (a T-pose avatar 15% shorter), with an index finger left at rest."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    rows = [("hips", None, "hips"), ("spine", "hips", "spine"), ("chest", "spine", "chest"),
            ("upperChest", "chest", "upperChest"), ("neck", "upperChest", "neck"), ("head", "neck", "head")]
    for side in ("left", "right"):
        rows += [(f"{side}Shoulder", "upperChest", f"{side}Shoulder"),
                 (f"{side}UpperArm", f"{side}Shoulder", f"{side}UpperArm"),
                 (f"{side}LowerArm", f"{side}UpperArm", f"{side}LowerArm"),
                 (f"{side}Hand", f"{side}LowerArm", f"{side}Hand"),
                 (f"{side}IndexProximal", f"{side}Hand", f"{side}Index")]
    for side in ("left", "right"):
        rows += [(f"{side}UpperLeg", "hips", f"{side}UpperLeg"), (f"{side}LowerLeg", f"{side}UpperLeg", f"{side}LowerLeg"),
                 (f"{side}Foot", f"{side}LowerLeg", f"{side}Foot"), (f"{side}Toes", f"{side}Foot", f"{side}Toes")]
    chans = lambda n, j: Skeleton.default_channels(2)[0 if j == 0 else 1]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)
