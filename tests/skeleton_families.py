"""BVH files of the skeleton families users bring, made from the built-in walk by renaming its joints.

Each family's names come from its table in :data:`text2anim.core.rigs.RIGS` (role -> joint name); joints
with no role there (CMU's ``LHipJoint``, ``Neck1``, fingers) get names no table knows (``Bone7``), as the
extra joints of a real file would. Some families are written in centimetres, as their tools export.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from shared_data import library_motion
from text2anim.core.rigs import RIGS
from text2anim.output.bvh_write import write_bvh

#: family -> (name prefix, length unit in metres)
FAMILIES = {
    "daz": ("", 0.01), "genesis": ("", 0.01), "biped": ("", 0.01), "bandai": ("", 0.01), "rokoko": ("", 1.0),
    "rigify": ("", 1.0), "mixamo": ("mixamorig:", 0.01), "smpl": ("", 1.0), "unreal": ("", 0.01), "vrm": ("", 1.0),
}


def family_names(family: str, names: tuple[str, ...]) -> tuple[str, ...]:
    """The built-in skeleton's joint ``names`` (CMU) as ``family`` names them."""
    cmu_role = {name: role for role, name in RIGS["cmu"].items()}
    prefix, _ = FAMILIES[family]
    table = RIGS[family]
    return tuple(prefix + table[cmu_role[n]] if cmu_role.get(n) in table else f"Bone{j}" for j, n in enumerate(names))


def family_bvh(family: str, path: Path) -> Path:
    """Write the built-in walk (30 fps) with ``family``'s joint names and unit to ``path``."""
    walk = library_motion("walk")
    _, unit = FAMILIES[family]
    s = walk.skeleton
    skel = replace(s, names=family_names(family, s.names), offsets=s.offsets / unit,
                   end_sites=tuple((j, o / unit) for j, o in s.end_sites))
    write_bvh(walk.replace(skeleton=skel, root_positions=walk.root_positions / unit), path)
    return path
