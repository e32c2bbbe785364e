"""``text2anim compare TEXT``: one time table joined by several methods, the quality figures side by side.

The text is analysed, scheduled and its clips retrieved once; the same tracks
are then synthesised with each method of ``--methods`` (``optimal``, paper
000; ``constraint``, paper 003; ``pose`` and ``crossfade``, the common
baselines) and the figures of docs/timetable.md §3 are printed as one row per
method (or as JSON). ``--out DIR`` writes one BVH per method (and actor);
``--plot FILE`` overlays every method's upper- and lower-body speed curves as
Fig. 5 of paper 000 does.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .arg_types import fps_type, method_list, unit_float
from .bvh_options import add_budget_option
from .cmd_parse import read_text
from .terminal import safe_json, say

NAME = "compare"
HELP = "join the same time table with several methods and compare foot skate, jerk, core fidelity"

_HEAD = (("foot_skate_cm_s", "skate cm/s", "{:10.2f}"), ("slide_cm", "slide cm", "{:8.1f}"),
         ("skating_ratio", "ratio", "{:6.3f}"), ("root_pop", "pop m/s2", "{:8.1f}"),
         ("jerk_p99", "jerk p99", "{:8.0f}"), ("floor_penetration_cm", "floor cm", "{:8.2f}"),
         ("frozen_fraction", "frozen", "{:6.3f}"), ("join_skating_ratio", "join ratio", "{:10.3f}"),
         ("join_root_pop", "join pop", "{:8.1f}"), ("join_jerk_p99", "join jerk", "{:9.0f}"),
         ("joins_ok", "joins ok", "{:>8}"), ("core_fidelity_cm", "core cm", "{:7.1f}"),
         ("duration_s", "dur s", "{:6.2f}"))


class CompareError(ValueError):
    """A bad ``--methods`` list or output folder."""

    user_facing = True


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("text", metavar="TEXT", help="the text, or - to read it from standard input")
    p.add_argument("--methods", type=method_list, default=["optimal", "constraint", "pose", "crossfade"],
                   help="comma-separated methods (default optimal,constraint,pose,crossfade)")
    p.add_argument("--out", metavar="DIR", help="write one BVH per method into DIR (DIR/optimal.bvh, ...)")
    p.add_argument("--plot", metavar="FILE", help="plot every method's upper/lower-body speeds (Fig. 5 of "
                   "paper 000; needs text2anim[plot])")
    p.add_argument("--json", action="store_true", help="print the figures as JSON")
    p.add_argument("--smoothness", type=unit_float, default=0.5, metavar="W",
                   help="W for the optimal method: 0 time first, 1 smoothness first (default 0.5)")
    p.add_argument("--fps", type=fps_type, default=30.0, help="output frame rate, 1 to 240 (default 30)")
    p.add_argument("--db", metavar="URL", help="motion database (default: $TEXT2ANIM_DB or the user's data directory)")
    p.add_argument("--skip-unknown", action="store_true", help="drop motions whose verb the database lacks")
    add_budget_option(p)


def run(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from text2anim.motiondb import MotionDB
    from text2anim.synthesis.comparison import figures
    from text2anim.pipeline import Request, Work, animation, run

    text = read_text(args.text)
    out_dir = Path(args.out) if args.out else None
    if out_dir is not None and out_dir.exists() and not out_dir.is_dir():
        raise CompareError(f"{out_dir} is not a folder")
    if args.plot:
        from text2anim.animation import check_plot_path

        check_plot_path(args.plot)
    request = Request(text, args.fps, args.skip_unknown, max_seconds=args.max_seconds, smoothness=args.smoothness)
    with MotionDB.open(args.db) as db:
        work = replace(run(Work(request, db), until="tracks"), db=None)
    tracks = work.tracks
    anims = {m: animation(run(replace(work, request=replace(request, blend=m)), after="tracks")) for m in args.methods}
    results = {m: (anim.result, figures(anim.result)) for m, anim in anims.items()}
    written = []
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
        for m, anim in anims.items():
            written.extend(anim.save_bvh(out_dir / f"{m}.bvh"))
    if args.plot:
        written.append(_plot(anims, args.plot, text))
    rows, missed = {}, {}
    for m, (res, fig) in results.items():
        row, missed[m] = _quality_row(res, tracks, anims[m].terms)
        rows[m] = {**fig, **row}
    if args.json:
        doc = {"text": text, "fps": args.fps, "smoothness": args.smoothness, "methods": rows,
               "joins": {m: [j["blend"] for j in res.report()["joins"]] for m, (res, _) in results.items()},
               "joins_missed": {m: lines for m, lines in missed.items() if lines},
               "warnings": {m: list(anims[m].warnings) for m, (res, _) in results.items() if res.warnings},
               "written": [str(p) for p in written]}
        print(safe_json(json.dumps(doc, ensure_ascii=False, indent=2)))
        return 0
    print(f"{'method':10} " + " ".join(h for _, h, _ in _HEAD) + "  joins")
    for m, fig in rows.items():
        joins = ",".join(j.blend for j in results[m][0].joins) or "-"
        print(f"{m:10} " + " ".join(f.format(fig[k]).rjust(len(h)) for k, h, f in _HEAD) + f"  {joins}")
    for m, lines in missed.items():
        for line in lines:
            say(f"{m}: {line}")
    for m, anim in anims.items():
        for w in anim.warnings:
            say(f"text2anim: {m}: warning: {w}", file=sys.stderr)
    if written:
        say("wrote " + ", ".join(str(p) for p in written))
    return 0


def _quality_row(result, tracks, terms) -> tuple[dict, list[str]]:
    """The literature's figures of one method at 30 fps: the worst actor, the worst join window, and
    ``joins_ok`` = "met/measured" joins meeting all five criteria against their sources; and for each join
    that misses one, which join (``terms``: rows, verbs, seconds) and which criteria, figure and limit."""
    from text2anim.quality import actor_quality, actor_series, join_quality, missed_criteria

    per_actor = actor_series(result.motions)  # resampled and measured once for both
    whole = list(actor_quality(result.motions, series_of=per_actor).values())
    measured = [(j, q) for j, q in zip(result.joins, join_quality(result, tracks, series_of=per_actor))
                if q is not None]
    joins = [q for _, q in measured]
    missed = [f"join {terms.join(j.first, j.second)} misses " + "; ".join(missed_criteria(q))
              for j, q in measured if missed_criteria(q)]
    row = {k: max((getattr(q, k) for q in whole), default=0.0)
           for k in ("skating_ratio", "root_pop", "jerk_p99", "floor_penetration_cm", "frozen_fraction")}
    for k in ("skating_ratio", "root_pop", "jerk_p99"):
        row[f"join_{k}"] = max((q["join"][k] for q in joins), default=0.0)
    met = sum(all(q["meets"].values()) for q in joins if "meets" in q)
    row["joins_ok"] = f"{met}/{sum('meets' in q for q in joins)}"
    return row, missed


def _plot(anims: dict, path, title: str) -> Path:
    """Every method's speed curves on one figure; the time table's elements marked, the blend intervals of
    the first method (``optimal`` by default) shaded."""
    from text2anim.output.plots import plot_speeds

    first = next(iter(anims.values()))
    labelled = {}
    for m, anim in anims.items():
        for actor, motion in anim.motions.items():
            labelled[m if len(anim.motions) == 1 else f"{m} {actor}"] = motion
    spans = [s for s in first.spans() if s.kind == "element" or s.kind == "blend"]
    plot_speeds(labelled, path, spans, title=title)
    return Path(path)
