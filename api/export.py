"""What a user's tools expect of an exported motion: their rig, root motion or in place, units, a loop.

>>> opts = ExportOptions(rig="mychar.bvh", root_motion=True, units="cm")
>>> anim.save_bvh("out.bvh", opts)

Order: retarget onto the rig (:func:`core.retarget.retarget`), loop
(:func:`core.conventions.looped`), root motion or in place
(:mod:`core.conventions`), then units (:func:`core.conventions.scaled`).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

from text2anim.core.bvh import read_bvh
from text2anim.core.motion import Motion
from text2anim.core.rigs import load_joint_map, rig_roles
from text2anim.core.skeleton import Skeleton

#: ``--units``: metres per file unit.
UNITS = {"m": 1.0, "cm": 100.0}


class ExportError(ValueError):
    """Export options that do not fit together or this animation."""

    user_facing = True


@dataclass(frozen=True)
class ExportOptions:
    """How motions are written for another tool.

    Attributes:
        rig: a BVH file whose skeleton the motion is retargeted onto (its rest pose, any of T/A pose);
            ``None`` keeps the built-in skeleton.
        joint_map: a JSON file ``{role: joint name}`` for the rig's joints no known rig names
            (:func:`core.rigs.load_joint_map`).
        root_motion: travel and heading on a root bone at the floor, the hips relative to it.
        in_place: the hips' travel removed (excludes ``root_motion``).
        units: ``"m"`` or ``"cm"`` (lengths times 100: Unreal, MotionBuilder).
        loop: cut and blend a single cyclic motion so its last frame flows into its first.
    """

    rig: str | os.PathLike | None = None
    joint_map: str | os.PathLike | None = None
    root_motion: bool = False
    in_place: bool = False
    units: str = "m"
    loop: bool = False

    def __post_init__(self) -> None:
        if self.root_motion and self.in_place:
            raise ExportError("--root-motion and --in-place exclude each other: choose one")
        if self.units not in UNITS:
            raise ExportError(f"unknown units {self.units!r}; known: {', '.join(UNITS)}")
        if self.joint_map is not None and self.rig is None:
            raise ExportError("--map names joints of a rig: give the rig with --rig FILE.bvh")

    @property
    def is_default(self) -> bool:
        return self == ExportOptions()

    @cached_property
    def target_map(self) -> dict[str, str] | None:
        return None if self.joint_map is None else load_joint_map(Path(self.joint_map))

    @cached_property
    def skeleton(self) -> Skeleton | None:
        """The rig's skeleton in metres (``None`` without a rig)."""
        if self.rig is None:
            return None
        path = Path(self.rig)
        if path.suffix.lower() != ".bvh":
            raise ExportError(f"{path}: --rig reads BVH files (.bvh); glTF/VRM rigs are not supported yet")
        return read_bvh(path).skeleton


    def check(self) -> "ExportOptions":
        """Read the rig and the map now and place the rig's joints, so a bad rig fails before any work."""
        if self.skeleton is not None:
            rig_roles(self.skeleton, self.target_map)
        return self


def export_motion(motion: Motion, opts: ExportOptions) -> Motion:
    """``motion`` as ``opts`` asks (see the module docstring for the order)."""
    if opts.is_default:
        return motion
    # loaded here, not at import: scipy.signal and scipy.ndimage are ~0.3 s of a run's start
    from text2anim.core.conventions import in_place, looped, root_motion, scaled
    from text2anim.core.retarget import retarget

    joint_map = None
    if opts.skeleton is not None:
        motion = retarget(motion, opts.skeleton, target_map=opts.target_map)
        joint_map = opts.target_map
    if opts.loop:
        motion = looped(motion)
    if opts.root_motion:
        try:
            motion = root_motion(motion, joint_map)
        except ValueError as exc:
            raise ExportError(f"--root-motion: {exc}") from None
    elif opts.in_place:
        motion = in_place(motion, joint_map)
    if UNITS[opts.units] != 1.0:
        motion = scaled(motion, UNITS[opts.units])
    return motion


def check_loopable(elements: list, cyclic: dict[int, bool]) -> None:
    """``--loop`` needs one whole-body cyclic motion: raises :class:`ExportError` otherwise."""
    whole = [e for e in elements if e.method != "composition"]
    if len(whole) != 1 or not cyclic.get(whole[0].id, False):
        raise ExportError("--loop makes a loop of a single cyclic motion (a walk, a run); this text gives "
                          f"{len(whole)} motion{'s' if len(whole) != 1 else ''}"
                          + ("" if len(whole) != 1 else " that does not loop"))


__all__ = ["UNITS", "ExportError", "ExportOptions", "check_loopable", "export_motion"]
