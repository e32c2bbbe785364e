"""``text2anim parse``: the motions and temporal constraints of a text."""
from __future__ import annotations

import argparse
import sys

NAME = "parse"
HELP = "analyse Japanese text: motions and temporal constraints (no database needed)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("text", metavar="TEXT", help="the text, or - to read it from standard input")
    parser.add_argument("--json", action="store_true",
                        help="print the JSON object of docs/language.md §5")
    parser.add_argument("--explain", action="store_true",
                        help="also print the bunsetsu and the head each one depends on")


def read_text(arg: str) -> str:
    """TEXT itself, or standard input (surrounding whitespace removed) for ``-``.

    Checked at the boundary (:func:`text2anim.limits.check_text`): a text with control
    characters or over the length limit is refused with one line saying so.
    """
    from text2anim.limits import MAX_TEXT_CHARS, InputError, LimitError, check_text

    if arg == "-":
        bound = MAX_TEXT_CHARS * 4  # room for surrounding whitespace; never read more than this + 1
        try:
            raw = sys.stdin.read(bound + 1)
        except UnicodeDecodeError:
            raise InputError("standard input is not UTF-8 text") from None
        if len(raw) > bound:  # refused, not cut: the cut-off part (a second actor…) would vanish unseen
            raise LimitError(f"standard input holds more than {bound} characters; at most {MAX_TEXT_CHARS} "
                             "are accepted (split it into several texts)")
        arg = raw.strip()
    return check_text(arg)


def run(args: argparse.Namespace) -> int:
    from text2anim.core.inputs import printable
    from text2anim.nlp import analyze  # lazy: keeps `text2anim --help` fast

    from .terminal import safe_json, say

    analysis = analyze(read_text(args.text))
    for note in analysis.notes:
        say(f"text2anim: {note}", file=sys.stderr)
    out = sys.stdout  # the text is the user's, but may come from a file: printed with control characters escaped
    if args.json:
        out.write(safe_json(analysis.to_json()) + "\n")
    else:
        out.write(printable(format_listing(analysis), keep="\n"))
    if args.explain:
        out.write(printable(format_explain(analysis), keep="\n"))
    return 0


def format_listing(analysis) -> str:
    """The readable form: one line per motion, one per constraint."""
    lines = [f"text: {analysis.text}", "motions:"]
    for m in analysis.motions:
        extras = [f"{k}={v}" for k, v in (
            ("object", m.object), ("body_part", m.body_part),
            ("repeat", m.repeat if m.repeat != 1 else None),
            ("speed", m.speed if m.speed != 1.0 else None),
            ("duration", f"{m.duration:g}s" if m.duration is not None else None),
            ("hold", "yes" if m.hold else None),
            (m.target_role, m.target + (f" ({m.target_side})" if m.target_side else "") if m.target else None))
            if v is not None]
        actor = m.actor or "(default)"
        word = analysis.text[m.span[0]:m.span[1]]
        lines.append(f"  {m.id:>2}  {actor}  {m.verb}  {' '.join(extras)}".rstrip()
                     + f"  [{m.span[0]},{m.span[1]}) {word}")
    lines.append("constraints:" if analysis.constraints else "constraints: (none)")
    for c in analysis.constraints:
        if c.relation == "parallel":
            timing = "parallel"
        else:
            timing = "serial, " + ("overlap" if c.overlap else "no overlap")
        delay = f", delay {c.delay:g}s" if c.delay is not None else ""
        lines.append(f"  {c.first:>2} -> {c.second:<2} {c.method:<11} {timing}{delay}  ({c.cue})")
    return "\n".join(lines) + "\n"


def format_explain(analysis) -> str:
    """The bunsetsu, their roles and heads: why each link was made; whom a phrase naming persons names."""
    lines = ["bunsetsu (index, text, head, role, why):"]
    texts = {b.index: b.text.strip() for b in analysis.bunsetsu}
    for b in analysis.bunsetsu:
        head = f"-> {b.head} {texts[b.head]}" if b.head is not None else "-> (none)"
        why = f"  [{b.why}]" if b.why else ""
        who = f"  (names {'、'.join(b.persons)})" if b.persons else ""
        lines.append(f"  {b.index:>3} {b.text.strip()}  {head}  {b.role}{who}{why}")
    if analysis.notes:
        lines.append("read differently from how it is written:")
        lines.extend(f"  {note}" for note in analysis.notes)
    return "\n".join(lines) + "\n"
