"""``--rig``, ``--map``, ``--root-motion``, ``--in-place``, ``--units``, ``--loop``: output for another tool."""
from __future__ import annotations

import argparse


def add_export_arguments(p: argparse.ArgumentParser) -> None:
    """The export options of ``text2anim TEXT`` (BVH, GLB and VRMA outputs; ``--units`` is BVH's alone)."""
    g = p.add_argument_group("your rig and engine")
    g.add_argument("--rig", metavar="CHARACTER",
                   help="retarget the animation onto this character: a BVH, glTF binary (.glb) or VRM (.vrm) "
                        "skeleton (Mixamo, VRM, SMPL, Unreal, CMU joint names or a VRM humanoid; T- or A-pose rest)")
    g.add_argument("--map", dest="joint_map", metavar="FILE",
                   help='JSON {role: joint name} for rig joints with other names, e.g. {"hips": "pelvis"}; '
                        "roles are VRM humanoid bone names")
    g.add_argument("--root-motion", action="store_true",
                   help="travel and heading on a root bone at the floor, the hips relative to it")
    g.add_argument("--in-place", action="store_true", help="remove the hips' travel (they keep their sway)")
    g.add_argument("--units", choices=("m", "cm"), default="m",
                   help="BVH length unit (default m; cm for Unreal and MotionBuilder)")
    g.add_argument("--loop", action="store_true",
                   help="for a single cyclic motion: cut and blend it so the last frame flows into the first")


def export_options(args: argparse.Namespace):
    """The :class:`text2anim.export.ExportOptions` of parsed arguments, the rig read and its joints placed."""
    from text2anim.export import ExportOptions

    return ExportOptions(rig=args.rig, joint_map=args.joint_map, root_motion=args.root_motion,
                         in_place=args.in_place, units=args.units, loop=args.loop).check(
                             glb=getattr(args, "glb", None) is not None)
