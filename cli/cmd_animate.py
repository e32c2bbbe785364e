"""``text2anim TEXT``: text to animation (BVH per actor, and a viewer page, GLB, report, plot, top view)."""
from __future__ import annotations

import argparse
import sys

from .arg_types import fps_type, unit_float
from .bvh_options import add_budget_option
from .cmd_parse import read_text
from .project import is_project, read_project
from .export_options import add_export_arguments, export_options
from .terminal import say

#: The BVH written when the command asks for no output at all (``text2anim TEXT``).
DEFAULT_BVH = "animation.bvh"

NAME = "animate"
HELP = "turn a text into animation (the default command: text2anim TEXT ...)"
#: The modules every run imports (the API's stages, the default blend's synthesis, the BVH writer): loaded with
#: the command, out of the collector's way (``main.PAUSED_GC``)
LOADS = ("text2anim.pipeline", "text2anim.animation", "text2anim.export", "text2anim.scene.staging",
         "text2anim.tracks", "text2anim.manners", "text2anim.synthesis.registry", "text2anim.synthesis.optimal",
         "text2anim.synthesis.join.joinpass", "text2anim.scene.place", "text2anim.placed",
         "text2anim.output.bvh_write")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("text", metavar="TEXT", help="the text, - to read it from standard input, or a studio project "
                   "(FILE.t2a.json: its text, time-table edits and stand-ins)")
    p.add_argument("-o", "--output",
                   help=f"BVH file to write, or - for standard output (default {DEFAULT_BVH} when no other output "
                        "is asked for; with several actors, one file each: animation_太郎.bvh, ...)")
    p.add_argument("--html", metavar="FILE", help="also write a self-contained viewer page")
    p.add_argument("--glb", metavar="FILE", help="also write a glTF binary (skinned skeleton + animation; with "
                   "--rig CHARACTER.glb|.vrm, your character animated)")
    p.add_argument("--vrma", metavar="FILE", help="also write a VRM Animation (.vrma) for VRM avatars")
    p.add_argument("--report", metavar="FILE", help="also write the synthesis report (JSON)")
    p.add_argument("--plot", metavar="FILE", help="also plot upper/lower-body speeds (needs text2anim[plot])")
    p.add_argument("--top-view", metavar="FILE", help="also draw the scene seen from above: paths, facings, "
                   "elements, things (.png, .svg or .pdf; needs text2anim[plot])")
    p.add_argument("--fps", type=fps_type, default=30.0, help="output frame rate, 1 to 240 (default 30)")
    p.add_argument("--db", metavar="URL", help="motion database (SQLAlchemy URL or SQLite path; "
                   "default: $TEXT2ANIM_DB or the user's data directory)")
    p.add_argument("--skip-unknown", action="store_true", help="drop motions whose verb the database lacks")
    p.add_argument("--fallback", choices=("strict", "nearest"), default="strict",
                   help="a verb the database lacks: strict (default) stops with the nearest verbs by meaning; "
                        "nearest animates the database verb nearest in meaning and says so")
    p.add_argument("--no-foot-lock", action="store_true", help="do not lock planted feet during blends")
    p.add_argument("--no-sway", action="store_true", help="do not transfer sway in compositions")
    add_budget_option(p)
    add_blend_arguments(p)
    add_export_arguments(p)


def add_blend_arguments(p: argparse.ArgumentParser) -> None:
    """``--blend`` and ``--smoothness`` (shared with ``compare``)."""
    from text2anim.synthesis.registry import METHODS

    p.add_argument("--blend", choices=METHODS, default="optimal",
                   help="how consecutive motions are joined: optimal (paper 000, default), constraint "
                        "(paper 003), pose (closest poses, linear), crossfade (linear, fixed length)")
    p.add_argument("--smoothness", type=unit_float, default=0.5, metavar="W",
                   help="for --blend optimal: 0 joins as fast as it can, 1 as smoothly as it can (default 0.5)")


def _say(msg: str) -> None:
    say(f"text2anim: {msg}", file=sys.stderr, flush=True)


class OutputArgumentError(ValueError):
    """Outputs that cannot all be written (``-o -`` with several actors)."""

    user_facing = True


def check_outputs(args: argparse.Namespace) -> dict:
    """The outputs asked for, checked before any work: each a writable path, no two on one file. Only what
    was asked for is written: the BVH file :data:`DEFAULT_BVH` only when nothing else is."""
    from text2anim.core.atomic import check_distinct, check_output_path

    outputs = {"bvh": args.output, "html": args.html, "glb": args.glb, "report": args.report, "plot": args.plot,
               "vrma": args.vrma, "top_view": args.top_view}
    outputs = {k: v for k, v in outputs.items() if v is not None} or {"bvh": DEFAULT_BVH}
    files = [check_output_path(v) for k, v in outputs.items() if not (k == "bvh" and v == "-")]
    check_distinct(files)
    from text2anim.animation import TOP_VIEW, check_plot_path

    if args.plot:
        check_plot_path(args.plot)
    if args.top_view:
        check_plot_path(args.top_view, TOP_VIEW)
    return outputs


def run(args: argparse.Namespace) -> int:
    import text2anim
    from text2anim.limits import check_text

    outputs = check_outputs(args)
    to_stdout = outputs.get("bvh") == "-"
    text, edits, fallback = read_text(args.text), (), args.fallback
    if is_project(args.text):  # the studio's work: its text, edits and stand-ins, animated as the page did
        project = read_project(args.text)
        text, edits = check_text(project.text), project.edits
        fallback = project.fallback if args.fallback == "strict" else args.fallback
    export = export_options(args)
    _say("analysing, retrieving clips and synthesising ...")
    anim = text2anim.animate(text, db=args.db, fps=args.fps, skip_unknown=args.skip_unknown,
                             lock_feet=not args.no_foot_lock, sway=not args.no_sway, blend=args.blend,
                             smoothness=args.smoothness, fallback=fallback, max_seconds=args.max_seconds,
                             edits=edits)
    for note in anim.planned.analysis.notes:
        _say(note)
    for sub in anim.planned.fallbacks:
        _say(f"fallback: {sub}")
    for verb in anim.planned.skipped:
        _say(f"skipped {verb}: not in the motion database")
    for w in anim.warnings:  # the report (figures at 30 fps) is built only if asked for
        _say(f"warning: {w}")
    if "glb" in outputs and anim.props() and not anim.exported_props(export):
        _say("the GLB has the bodies alone: --in-place and --loop take them off the scene its things stand in")
    if to_stdout:
        if len(anim.motions) > 1:
            raise OutputArgumentError(f"the text has {len(anim.motions)} actors and a BVH file holds one: "
                                      "-o - cannot take them; give a file name (one file per actor)")
        outputs.pop("bvh")
    written = anim.save(**outputs, export=export)
    summary = sys.stderr if to_stdout else sys.stdout  # standard output carries the BVH alone
    for e in anim.table.elements:
        actor = e.actor or "default"
        say(f"{e.id:>2} {actor} {e.verb:8} {e.clip:18} {e.method:12} {e.start:6.2f}-{e.end:6.2f} s", file=summary)
    for name, m in anim.motions.items():
        say(f"{name}: {m.n_frames} frames at {m.fps:g} fps ({m.duration:.2f} s)", file=summary)
    if to_stdout:
        from text2anim.output.bvh_write import format_bvh

        sys.stdout.write(format_bvh(next(iter(anim.exported_motions(export).values()))))
        sys.stdout.flush()
    names = ["standard output"] if to_stdout else []
    say("wrote " + ", ".join(names + [str(p) for p in written]), file=summary)
    return 0
