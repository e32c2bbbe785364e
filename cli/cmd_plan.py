"""``text2anim plan TEXT``: the motion time table of a text, clips from the motion database."""
from __future__ import annotations

import argparse
import sys

from text2anim.core.inputs import printable

from .arg_types import fps_type
from .bvh_options import add_budget_option
from .cmd_parse import read_text
from .terminal import safe_json, say

NAME = "plan"
HELP = "build the motion time table of a text (which clip, how joined, when)"
#: The modules every run imports: loaded with the command, out of the collector's way (``main.PAUSED_GC``)
LOADS = ("text2anim.planning", "text2anim.databases")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("text", metavar="TEXT", help="the text, or - to read it from standard input")
    p.add_argument("--json", action="store_true", help="print the JSON of docs/timetable.md §1")
    p.add_argument("--db", metavar="URL", help="motion database (SQLAlchemy URL or SQLite path; "
                   "default: $TEXT2ANIM_DB or the user's data directory)")
    p.add_argument("--fps", type=fps_type, default=30.0, help="frame rate recorded in the table, 1 to 240 (default 30)")
    p.add_argument("--skip-unknown", action="store_true", help="drop motions whose verb the database lacks")
    p.add_argument("--fallback", choices=("strict", "nearest"), default="strict",
                   help="a verb the database lacks: strict (default) stops with the nearest verbs by meaning; "
                        "nearest plans the database verb nearest in meaning and says so")
    add_budget_option(p)


def run(args: argparse.Namespace) -> int:
    import text2anim
    from text2anim.scheduler import format_table

    planned = text2anim.plan(read_text(args.text), args.db, fps=args.fps, skip_unknown=args.skip_unknown,
                             fallback=args.fallback, max_seconds=args.max_seconds)
    for note in planned.analysis.notes:
        say(f"text2anim: {note}", file=sys.stderr)
    for sub in planned.fallbacks:
        say(f"text2anim: fallback: {sub}", file=sys.stderr)
    for verb in planned.skipped:
        say(f"text2anim: skipped {verb}: not in the motion database", file=sys.stderr)
    sys.stdout.write(safe_json(planned.table.to_json()) + "\n" if args.json
                     else printable(format_table(planned.table), keep="\n"))
    return 0
