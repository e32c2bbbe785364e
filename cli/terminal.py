"""What a command prints from a file or the database, made safe for a terminal.

A verb, clip or joint name may hold ESC, BEL, a C1 byte or a text-direction override
(imported before they were refused, or read from a user's BVH): printed raw they can
retitle the window or clear the screen. Every such print goes through :func:`say`
(control characters shown as ``\\x1b`` escapes, line breaks kept) or :func:`say_json`
(the same characters as JSON ``\\u`` escapes, so the output stays valid JSON).
"""
from __future__ import annotations

import json
import re
import sys

from text2anim.core.inputs import BIDI_CONTROLS, printable

_JSON_UNSAFE = re.compile("[\x7f-\x9f" + "".join(sorted(BIDI_CONTROLS)) + "]")


#: characters: the longest message a command prints on one line (a 9,999-joint file's error named every joint: 69 KB)
MESSAGE_WIDTH = 1000


def message(text: str, width: int = MESSAGE_WIDTH) -> str:
    """``text`` cut in its middle to at most ``width`` characters, saying how much was left out, then
    escaped (:func:`printable`), so one bad file never floods the terminal."""
    if len(text) <= width:
        text = printable(text)  # escapes lengthen it: cut again below if so
        if len(text) <= width:
            return text
    left = len(text) - width  # cut before escaping: escaping 63 MB to cut it took seconds and gigabytes
    head, tail = printable(text[:width * 3 // 4])[:width * 3 // 4], printable(text[-width // 4:])[-width // 4:]
    return f"{head} … ({left:,} characters left out) … {tail}"


def say(*parts, sep: str = " ", file=None, flush: bool = False) -> None:
    """``print`` with every control character but the line breaks escaped."""
    text = sep.join(str(p) for p in parts)
    print(printable(text, keep="\n"), file=file or sys.stdout, flush=flush)


def safe_json(text: str) -> str:
    """JSON text (as ``json.dumps(..., ensure_ascii=False)`` makes it, C0 escaped) with DEL, C1 and
    text-direction controls escaped too, the JSON way (``\\u009b``): the same data, safe to print."""
    return _JSON_UNSAFE.sub(lambda m: f"\\u{ord(m.group()):04x}", text)


def say_json(obj) -> None:
    """``obj`` as indented JSON, non-ASCII kept readable, control characters as ``\\u`` escapes."""
    print(safe_json(json.dumps(obj, ensure_ascii=False, indent=1)))
