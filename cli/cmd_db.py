"""``text2anim db ACTION``: look after the motion database.

Actions: ``import`` BVH files as clips, ``list`` and ``show`` clips, ``export``
a clip as BVH, ``remove`` clips, list the ``verbs``, ``preview`` a clip as a
contact sheet. Every action takes ``--db URL`` (an SQLAlchemy URL or an SQLite
file path; default ``TEXT2ANIM_DB``, else the XDG data folder).
"""
from __future__ import annotations

import argparse
import sys
import unicodedata

from text2anim.core.bodyparts import GROUPS
from text2anim.core.inputs import printable
from text2anim.core.styles import STYLES

from .arg_types import core_span, frame_count
from .bvh_options import add_read_options, read_options
from .terminal import say, say_json

NAME = "db"
HELP = "the motion database: import BVH clips, list, show, export, remove, verbs, preview"

_PARTS = GROUPS
#: motiondb.style_pack.PACKS (repeated here so that building the parser imports no database code).
_PACKS = ("bandai-namco",)
#: motiondb.types.POSTURES (repeated here so that building the parser imports no database code).
_POSTURES = ("standing", "seated", "crouched", "kneeling", "lying")


def _db_option(p: argparse.ArgumentParser, default=None) -> None:
    p.add_argument("--db", dest="db_url", metavar="URL", default=default,
                   help="database URL (sqlite:///FILE, postgresql+psycopg2://...) or SQLite file; "
                        "default: $TEXT2ANIM_DB, else $XDG_DATA_HOME/text2anim/motions.sqlite")


def add_arguments(p: argparse.ArgumentParser) -> None:
    _db_option(p)
    sub = p.add_subparsers(dest="db_action", metavar="ACTION")

    def action(name: str, help: str) -> argparse.ArgumentParser:
        a = sub.add_parser(name, help=help, description=help)
        _db_option(a, default=argparse.SUPPRESS)  # after the action too; the one before it otherwise
        return a

    a = action("import", "import BVH files as clips (all or nothing)")
    a.add_argument("files", nargs="+", metavar="FILE", help="BVH files; each becomes a clip named after the file")
    a.add_argument("--verb", action="append", required=True, metavar="VERB",
                   help="a verb lemma that retrieves the clips; repeat for synonyms (the first is the primary verb)")
    a.add_argument("--object", action="append", default=[], metavar="NOUN", help="an object the action is about (ボール)")
    a.add_argument("--character", default="default", help="the character the clips belong to (default: default)")
    a.add_argument("--core", type=core_span, metavar="BEGIN:END",
                   help="the part that must be kept, seconds (default: the whole clip)")
    a.add_argument("--part", choices=_PARTS, help="the body part a partial action is declared for")
    a.add_argument("--cyclic", action="store_true", help="the clips loop (locomotion)")
    a.add_argument("--name", help="clip name (one file only; default: the file name without .bvh)")
    a.add_argument("--replace", action="store_true", help="replace clips of the same names")
    a.add_argument("--start-posture", choices=_POSTURES,
                   help="the posture the clips start in (default: classified from each file's first frame)")
    a.add_argument("--end-posture", choices=_POSTURES,
                   help="the posture the clips end in (default: classified from each file's last frame)")
    a.add_argument("--style", choices=sorted(STYLES),
                   help="the style the clips were performed in (docs/language.md §2.1): a text asking for it plays "
                        "them before changing a neutral clip (default: neutral)")
    a.add_argument("--map", dest="joint_map", metavar="FILE",
                   help="JSON {role: joint name} for joints no known rig names, used when a clip is retargeted "
                        "onto its character's skeleton (roles are VRM humanoid bone names)")
    add_read_options(a)

    a = action("import-pack", "import a style pack you downloaded (the Bandai Namco Research Motion Dataset), "
                              "its styles mapped to ours")
    a.add_argument("pack", choices=_PACKS, help="the pack: bandai-namco")
    a.add_argument("folder", metavar="DIR", help="the folder of its BVH files (searched recursively)")
    a.add_argument("--character", default="bandai-namco", help="the character its clips belong to (default: bandai-namco)")
    a.add_argument("--replace", action="store_true", help="replace clips of the same names")

    a = action("list", "list clips (ranked as a search when --verb is given)")
    a.add_argument("--verb", help="only clips retrieved by this verb, best first")
    a.add_argument("--object", help="with --verb: rank clips declaring this object first")
    a.add_argument("--character", help="only this character's clips")
    a.add_argument("--part", choices=_PARTS, help="with --verb: a request for this body part")
    a.add_argument("--start-posture", choices=_POSTURES,
                   help="with --verb: rank clips starting in this posture first (what follows a clip ending in it)")
    a.add_argument("--json", action="store_true", help="JSON instead of a table")

    a = action("show", "show one clip: metadata, verbs, objects, foot contacts")
    a.add_argument("clip")
    a.add_argument("--json", action="store_true", help="JSON instead of text")

    a = action("export", "write a clip as a BVH file (metres)")
    a.add_argument("clip")
    a.add_argument("-o", "--output", required=True, metavar="FILE.bvh", help="the file to write (atomically)")

    a = action("remove", "remove clips (all or nothing)")
    a.add_argument("clips", nargs="+", metavar="CLIP")

    a = action("verbs", "list the verbs with their readings and clip counts")
    a.add_argument("--json", action="store_true", help="JSON instead of a table")

    a = action("preview", "draw a clip or a BVH file (an animation you made) as a contact sheet "
                          "(stick figures, front and side view)")
    a.add_argument("clip", metavar="CLIP|FILE.bvh", help="a clip's name, or a BVH file to draw without a database")
    a.add_argument("-o", "--output", required=True, metavar="SHEET.png", help="the image to write")
    a.add_argument("--frames", type=frame_count, default=8, metavar="N",
                   help="how many frames to draw, evenly spaced (default 8, at most 48)")

    p.set_defaults(_db_parser=p)


# ------------------------------------------------------------------ printing
def _width(s: str) -> int:
    return sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in s)


def _table(rows: list[list[str]], header: list[str]) -> str:
    rows = [[printable(c) for c in r] for r in rows]  # escaped before measuring, so the columns line up
    widths = [max(_width(r[k]) for r in [header, *rows]) for k in range(len(header))]
    lines = []
    for r in [header, *rows]:
        cells = [c + " " * (w - _width(c)) for c, w in zip(r, widths)]
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


def _clip_row(c, styles: bool = False) -> list[str]:
    return [c.name, c.character, "/".join(c.verbs), "/".join(c.objects) or "-", c.body_part or "-",
            _postures(c), *([c.style or "-"] if styles else []), str(c.frames), f"{c.fps:g}", f"{c.duration:.2f}",
            "yes" if c.cyclic else "", _source(c.source)]


def _source(source: str) -> str:
    """Where a clip came from, short: ``capture:CMU 16_15 0.57-1.70s``, ``keyframed:walk.json``, a file path."""
    return source.removeprefix("builtin:") or "-"


def _postures(c) -> str:
    """``seated→standing``, or one word when the clip starts and ends in the same posture."""
    return c.start_posture if c.start_posture == c.end_posture else f"{c.start_posture}→{c.end_posture}"



def _print_clips(clips, as_json: bool) -> None:
    if as_json:
        say_json([c.to_dict() for c in clips])
        return
    if not clips:
        say("(no clips)")
        return
    styles = any(c.style for c in clips)  # the column only when a clip has a style
    say(_table([_clip_row(c, styles) for c in clips],
               ["clip", "character", "verbs", "objects", "part", "posture", *(["style"] if styles else []),
                "frames", "fps", "seconds", "cyclic", "source"]))


def _show(c) -> str:
    def intervals(iv):
        return ", ".join(f"{a}-{b}" for a, b in iv) or "none"

    lines = [
        f"clip:       {c.name}",
        f"character:  {c.character} ({c.joints} joints)",
        f"verbs:      {c.verbs[0]}" + (f" (synonyms: {', '.join(c.verbs[1:])})" if len(c.verbs) > 1 else ""),
        f"objects:    {', '.join(c.objects) or '-'}",
        f"frames:     {c.frames} at {c.fps:g} fps = {c.duration:.3f} s",
        f"core:       {c.core[0]:.3f} .. {c.core[1]:.3f} s",
        f"body part:  {c.body_part or 'whole body'}",
        f"postures:   starts {c.start_posture}, ends {c.end_posture}",
        f"style:      {c.style or 'neutral'}",
        f"does:       {_actions(c)}",
        f"body:       {_body(c.description)}",
        f"cyclic:     {'yes' if c.cyclic else 'no'}",
        f"contacts:   left {intervals(c.left_contacts)}",
        f"            right {intervals(c.right_contacts)}   (frames [start, stop))",
        f"source:     {c.source or '-'}",
        f"stored:     {c.created.strftime('%Y-%m-%d %H:%M:%S')} UTC",
    ]
    return "\n".join(lines)


def _actions(c) -> str:
    """A clip's WordNet actions for people: ``walk (verb.motion)``; what it stands in for (api/fallback.py)."""
    if not c.description.actions:
        if c.source.startswith("builtin"):
            return "- (stands in for no verb it does not list)"
        return f"- (when a stand-in is sought: what {c.verb} means)"
    from text2anim.nlp import senses

    return ", ".join(senses.name(a) if senses.known(a) else a for a in c.description.actions)


def _body(d) -> str:
    """What the body does, measured (:class:`motiondb.types.ClipDescription`)."""
    moving = ", ".join(d.moving) or "nothing"
    return (f"{'travels' if d.locomotion else 'in place'}; moving: {moving}; "
            f"energy {d.energy:.2f} leg lengths/s")


def _progress(done: int, total: int, path: str) -> None:
    if path:
        say(f"text2anim db import: [{done + 1}/{total}] {path}", file=sys.stderr, flush=True)
    elif total > 1:
        say(f"text2anim db import: read {total} files, storing", file=sys.stderr, flush=True)


# ---------------------------------------------------------------------- run
def run(args) -> int:
    if not getattr(args, "db_action", None):
        args._db_parser.print_help(sys.stderr)
        return 2
    if args.db_action == "preview" and args.clip.lower().endswith(".bvh"):
        return _preview_file(args)  # a file needs no database
    from text2anim.motiondb import ClipValidationError, MotionDB

    if args.db_action == "import" and args.name and len(args.files) != 1:
        raise ClipValidationError("--name needs exactly one file")
    db = MotionDB.open(args.db_url)
    try:
        return _ACTIONS[args.db_action](db, args)
    finally:
        db.close()


def _import(db, args) -> int:
    from text2anim.core.rigs import load_joint_map
    from text2anim.motiondb import ImportOptions

    joint_map = load_joint_map(args.joint_map) if args.joint_map else None
    options = ImportOptions(verbs=tuple(args.verb), objects=tuple(args.object or ()), character=args.character,
                            core=args.core, part=args.part, cyclic=args.cyclic,
                            names=(args.name,) if args.name else None, replace=args.replace,
                            start_posture=args.start_posture, end_posture=args.end_posture, joint_map=joint_map,
                            style=args.style, **read_options(args))
    infos = db.import_bvh(args.files, options, progress=_progress,
                          notify=lambda path, msg: say(f"text2anim db import: {path}: {msg}", file=sys.stderr))
    say(f"imported {len(infos)} clip{'s' if len(infos) != 1 else ''} into {db.url}:")
    for c in infos:
        say(f"  {c.name}: {c.frames} frames at {c.fps:g} fps ({c.duration:.2f} s), "
            f"{len(c.left_contacts)}+{len(c.right_contacts)} foot contacts, verbs {'/'.join(c.verbs)}, "
            f"posture {_postures(c)}" + (f", style {c.style}" if c.style else ""))
    return 0


def _import_pack(db, args) -> int:
    from text2anim.motiondb.style_pack import NOTICE, import_pack

    say(f"text2anim db import-pack: {NOTICE}", file=sys.stderr)
    clips, plan = import_pack(db, args.pack, args.folder, character=args.character, replace=args.replace,
                              progress=_progress,
                              notify=lambda path, msg: say(f"text2anim db import-pack: {path}: {msg}", file=sys.stderr))
    reasons: dict[str, int] = {}
    for _, why in plan.left_out:
        reasons[why] = reasons.get(why, 0) + 1
    for why, n in sorted(reasons.items()):
        say(f"text2anim db import-pack: left out {n} file{'s' if n != 1 else ''}: {why}", file=sys.stderr)
    styles: dict[str, int] = {}
    for c in clips:
        styles[c.style or "neutral"] = styles.get(c.style or "neutral", 0) + 1
    say(f"imported {len(clips)} clip{'s' if len(clips) != 1 else ''} of {args.pack} into {db.url} "
        f"(character {args.character}): " + ", ".join(f"{k} {v}" for k, v in sorted(styles.items())))
    return 0


def _list(db, args) -> int:
    if args.verb:
        clips = db.search(args.verb, object=args.object, character=args.character, body_part=args.part,
                          prefer_start_posture=args.start_posture)
    else:
        clips = db.clips(character=args.character)
    _print_clips(clips, args.json)
    return 0


def _show_action(db, args) -> int:
    c = db.info(args.clip)
    if args.json:
        say_json(c.to_dict())
    else:
        say(_show(c))
    return 0


def _export(db, args) -> int:
    from text2anim.output.bvh_write import write_bvh

    m = db.load(args.clip)
    write_bvh(m, args.output)
    say(f"wrote {args.output}: {m.n_frames} frames at {m.fps:g} fps, {m.duration:.3f} s")
    return 0


def _remove(db, args) -> int:
    db.remove(args.clips)
    say(f"removed {', '.join(args.clips)}")
    return 0


def _verbs(db, args) -> int:
    verbs = db.verbs()
    if args.json:
        say_json([{"lemma": v.lemma, "reading": v.reading, "clips": v.clips, "primary": v.primary}
                  for v in verbs])
    elif not verbs:
        say("(no verbs)")
    else:
        say(_table([[v.lemma, v.reading, str(v.clips), str(v.primary)] for v in verbs],
                   ["verb", "reading", "clips", "primary"]))
    return 0


def _contact_sheet():
    """The contact-sheet drawer, once its extra (matplotlib) is known to be there: before any work."""
    from text2anim.core import extras

    extras.require("matplotlib", "db preview")
    from text2anim.output.sheet import contact_sheet

    return contact_sheet


def _romanised(word: str) -> str:
    """``word`` in Latin letters: its reading in Hepburn romaji (ASCII words as they are)."""
    from text2anim.motiondb.readings import reading, romaji

    return word if word.isascii() else romaji(reading(word))


def _alt_title(title: str, words: list[str], rest: str) -> str | None:
    """Without a font for ``title``'s glyphs (no CJK font): ``words`` romanised (odoru/dansusuru), then ``rest``."""
    from text2anim.output import fonts

    return None if fonts.drawable(title) else f"{': '.join(words)} {rest}"


def _preview(db, args) -> int:
    contact_sheet = _contact_sheet()
    info = db.info(args.clip)
    motion = db.load(info)
    rest = f"({info.character}, {info.frames} frames, {info.fps:g} fps)"
    title = f"{info.name}: {'/'.join(info.verbs)} {rest}"
    alt = _alt_title(title, [_romanised(info.name), "/".join(_romanised(v) for v in info.verbs)],
                     f"({_romanised(info.character)}, {info.frames} frames, {info.fps:g} fps)")
    contact_sheet(motion, args.output, title=title, n=args.frames, core=info.core, alt_title=alt)
    say(f"wrote {args.output}")
    return 0


def _preview_file(args) -> int:
    """Draw a BVH file as it is (an output of ``text2anim``, or any capture) without opening a database."""
    import os

    from text2anim.core.bvh import read_bvh

    contact_sheet = _contact_sheet()
    motion = read_bvh(args.clip)
    name = os.path.basename(args.clip)
    rest = f"({motion.n_frames} frames, {motion.fps:g} fps, {motion.n_frames / motion.fps:.2f} s)"
    title = f"{name} {rest}"
    alt = _alt_title(title, [_romanised(name)], rest)
    contact_sheet(motion, args.output, title=title, n=args.frames, alt_title=alt)
    say(f"wrote {args.output}")
    return 0


_ACTIONS = {"import": _import, "import-pack": _import_pack, "list": _list, "show": _show_action, "export": _export, "remove": _remove,
            "verbs": _verbs, "preview": _preview}
