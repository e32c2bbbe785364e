"""What a user's tools expect of an exported motion: their rig, root motion or in place, units, a loop.

>>> opts = ExportOptions(rig="mychar.bvh", root_motion=True, units="cm")
>>> anim.save_bvh("out.bvh", opts)

Order: retarget onto the rig (:func:`core.retarget.retarget`), loop
(:func:`core.conventions.looped`), root motion or in place
(:mod:`core.conventions`), then units (:func:`core.conventions.scaled`).

A rig is a BVH file or a skinned glTF character (``.glb``, ``.vrm``: :mod:`core.gltf_rig`;
a VRM's humanoid bone map names its joints). The same options give the GLB
(:func:`glb_files`: the user's own character file animated, when the rig is glTF)
and the VRM Animation (:func:`vrma_motion`, :mod:`output.vrma`); glTF is in metres,
so ``units`` applies to BVH only. The scene's props go into the GLB where the export puts
the bodies (:func:`export_props`); the BVH and the VRM Animation are the body alone.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

from text2anim.core.bvh import read_bvh
from text2anim.core.motion import Motion
from text2anim.core.rigs import load_joint_map, rig_roles
from text2anim.core.skeleton import Skeleton

if TYPE_CHECKING:
    from text2anim.core.gltf_rig import GltfRig
    from text2anim.core.soles import Sole

#: ``--units``: metres per file unit.
UNITS = {"m": 1.0, "cm": 100.0}


class ExportError(ValueError):
    """Export options that do not fit together or this animation."""

    user_facing = True


@dataclass(frozen=True)
class ExportOptions:
    """How motions are written for another tool.

    Attributes:
        rig: a BVH, glTF binary or VRM file whose skeleton the motion is retargeted onto (its rest
            pose, any of T/A pose); ``None`` keeps the built-in skeleton.
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
            raise ExportError("--map names joints of a rig: give the rig with --rig FILE.bvh|.glb|.vrm")

    @property
    def is_default(self) -> bool:
        return self == ExportOptions()

    @cached_property
    def gltf_rig(self) -> GltfRig | None:
        """The rig's glTF character (``None`` without a rig or for a BVH rig)."""
        from text2anim.core.gltf_rig import GLTF_SUFFIXES, read_gltf_rig

        if self.rig is None or Path(self.rig).suffix.lower() not in GLTF_SUFFIXES:
            return None
        return read_gltf_rig(Path(self.rig))

    @cached_property
    def target_map(self) -> dict[str, str] | None:
        """``{role: joint name}``: a VRM rig's humanoid bones, then the ``--map`` file's entries over them."""
        out = dict(self.gltf_rig.humanoid) if self.gltf_rig is not None else {}
        if self.joint_map is not None:
            out.update(load_joint_map(Path(self.joint_map)))
        return out or None

    @cached_property
    def skeleton(self) -> Skeleton | None:
        """The rig's skeleton in metres (``None`` without a rig)."""
        if self.rig is None:
            return None
        path = Path(self.rig)
        if self.gltf_rig is not None:
            return self.gltf_rig.skeleton
        if path.suffix.lower() != ".bvh":
            raise ExportError(f"{path}: --rig reads BVH (.bvh), glTF binary (.glb) and VRM (.vrm) files")
        return read_bvh(path).skeleton

    @cached_property
    def soles(self) -> dict[str, Sole] | None:
        """A glTF rig's feet as its mesh has them: ``{"leftFoot"/"rightFoot": Sole}``
        (:func:`core.soles.sole_lines`), for the retarget to stand them on their soles; ``None`` for a BVH
        rig or a mesh that does not show its feet."""
        if self.gltf_rig is None:
            return None
        from text2anim.core.soles import sole_lines

        _, roles = rig_roles(self.gltf_rig.skeleton, self.target_map)
        feet = {f"{s}Foot": (roles[f"{s}Foot"], roles.get(f"{s}Toes", roles[f"{s}Foot"])) for s in ("left", "right")}
        return sole_lines(self.gltf_rig, feet) or None

    def check(self, glb: bool = False) -> "ExportOptions":
        """Read the rig and the map now and place the rig's joints, so a bad rig fails before any work;
        ``glb``: a GLB output is asked for too (``--root-motion`` then needs a glTF rig's own root bone)."""
        if self.skeleton is not None:
            _, roles = rig_roles(self.skeleton, self.target_map)
            if glb and self.root_motion and self.gltf_rig is not None and roles["hips"] == 0:
                raise _no_root_bone(self.gltf_rig)
        return self


def _no_root_bone(rig: GltfRig) -> ExportError:
    return ExportError(f"--root-motion: {rig.path} has no root bone above its hips to carry the travel in a GLB "
                       "(a BVH output gets a new root joint); use --in-place or a rig with a root bone")


def export_motion(motion: Motion, opts: ExportOptions, *, units: bool = True) -> Motion:
    """``motion`` as ``opts`` asks (see the module docstring for the order); ``units=False`` keeps metres."""
    if opts.is_default:
        return motion
    # loaded here, not at import: scipy.signal and scipy.ndimage are ~0.3 s of a run's start
    from text2anim.core.retarget import retarget

    if opts.skeleton is not None:
        motion = retarget(motion, opts.skeleton, target_map=opts.target_map, soles=opts.soles)
    motion = _conventions(motion, opts, opts.target_map if opts.skeleton is not None else None)
    return in_units(motion, opts) if units else motion


def in_units(motion: Motion, opts: ExportOptions) -> Motion:
    """``motion`` (metres) in the BVH length unit ``opts.units`` asks for."""
    from text2anim.core.conventions import scaled

    return scaled(motion, UNITS[opts.units]) if UNITS[opts.units] != 1.0 else motion


def _conventions(motion: Motion, opts: ExportOptions, joint_map: dict[str, str] | None,
                 root: bool = True) -> Motion:
    """Loop, then root motion (with ``root``) or in place."""
    from text2anim.core.conventions import in_place, looped, root_motion

    if opts.loop:
        motion = looped(motion)
    if opts.root_motion and root:
        try:
            motion = root_motion(motion, joint_map)
        except ValueError as exc:
            raise ExportError(f"--root-motion: {exc}") from None
    elif opts.in_place:
        motion = in_place(motion, joint_map)
    return motion


def export_props(props: list, motions: dict[str, Motion], opts: ExportOptions) -> list:
    """The scene's props (:class:`output.viewer.types.Prop`) where ``opts`` puts the actors (``motions``: theirs
    before export). A rig moves the body by its leg-length ratio ``s`` about the origin (:mod:`core.retarget`),
    so the props' places and sizes are scaled by ``s`` too (the first actor's ratio: the actors share a skeleton);
    ``--in-place`` and ``--loop`` take the body off the scene's frames (its travel removed, its frames cut and
    blended), so no prop can stay where the body meets it: none is kept."""
    if not props or opts.is_default:
        return list(props)
    if opts.in_place or opts.loop:
        return []
    if opts.skeleton is None:
        return list(props)
    from text2anim.core.retarget import map_skeletons

    first = next(iter(motions.values()))
    k = map_skeletons(first.skeleton, opts.skeleton, target_map=opts.target_map).scale
    return [p.scaled(k) for p in props]


def glb_files(exported: dict[str, Motion], opts: ExportOptions, props=()) -> dict[str, bytes] | bytes:
    """The GLB output of every actor's motion as ``opts`` asks for it, in metres (``exported``: by
    :func:`export_motion` with ``units=False``), with the scene's ``props`` (placed by :func:`export_props`):
    with a glTF rig, the user's file animated, one per actor (``{actor: bytes}``; the props in each, so each
    file shows what its character meets); else one file with every actor on a skinned box skeleton
    (:func:`output.gltf.glb_bytes`)."""
    from text2anim.output.gltf import add_props, glb_bytes
    from text2anim.core.gltf_rig import rig_glb_bytes

    rig = opts.gltf_rig
    if rig is None:
        return glb_bytes(exported, props=props)
    out = {}
    for name, moved in exported.items():
        if not moved.skeleton.same_hierarchy(rig.skeleton):
            raise _no_root_bone(rig)
        out[name] = rig_glb_bytes(rig, moved, extra=(lambda b, gl, anim: add_props(b, gl, props, anim)) if props
                                  else None)
    return out


def vrma_motion(motion: Motion, opts: ExportOptions) -> Motion:
    """``motion`` on a VRMA skeleton (:func:`output.vrma.vrma_skeleton`): the user's VRM avatar's proportions
    when the rig is one, else the motion's own; looped and in place as ``opts`` asks (VRMA travel stays on
    the hips, so ``--root-motion`` does not apply)."""
    from text2anim.core.retarget import retarget
    from text2anim.output.vrma import vrma_skeleton

    rig = opts.gltf_rig
    if rig is not None and rig.vrm is not None:
        skel = vrma_skeleton(rig.skeleton, rig_roles(rig.skeleton, opts.target_map)[1], turn=rig.vrm == "0.x",
                             grounded=True)
    else:
        skel = vrma_skeleton(motion.skeleton, rig_roles(motion.skeleton)[1])
    return _conventions(retarget(motion, skel), opts, None, root=False)


def check_loopable(elements: list, cyclic: dict[int, bool]) -> None:
    """``--loop`` needs one whole-body cyclic motion: raises :class:`ExportError` otherwise."""
    whole = [e for e in elements if e.method != "composition"]
    if len(whole) != 1 or not cyclic.get(whole[0].id, False):
        raise ExportError("--loop makes a loop of a single cyclic motion (a walk, a run); this text gives "
                          f"{len(whole)} motion{'s' if len(whole) != 1 else ''}"
                          + ("" if len(whole) != 1 else " that does not loop"))


__all__ = ["UNITS", "ExportError", "ExportOptions", "check_loopable", "export_motion", "export_props", "glb_files",
           "in_units", "vrma_motion"]
