"""One corpus line through the pipeline, on whichever process runs it: the manifest record it makes.

A record (one line of ``DIR/manifest.jsonl``)::

    {"line": 12, "text_hash": "…", "options": "…", "status": "animated", "reason": null,
     "files": ["0000/line_0000012.bvh"], "skating_ratio": 0.0, "joins": [{…per-join figures…}],
     "time": 0.31, "cpu": 0.09, "check": "passed", …}

``time`` is the line's wall time and ``cpu`` the CPU time of the thread that ran it (s).

``status`` is what happened to the line: ``animated`` (files written), ``parsed``
(no animation asked for), ``refused`` (the text's fault: no motion in it, a
verb the database lacks, a time table that cannot be built) or ``failed`` (our
fault or the machine's: a bug, a lost database, a full disk, a worker that
died). ``check`` keeps the meaning ``--check`` always had: ``failed`` when the
line's expectation is not met, ``errored`` when it was refused or failed
without an expected error; a verb the database lacks is not an error there.
``expected_error`` says the line's expectation was an error (so a refusal was
what it asked for; :func:`summary.outcome`). A line whose expectation names clips
is planned even with ``--parse-only`` (the time table, no synthesis), so ``check``
can compare each motion's clip.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import threading
import time
from dataclasses import dataclass
from typing import Callable, Iterable

from text2anim.limits import MAX_SECONDS

from .corpus import Item, text_hash

#: Output files per shard folder: ``DIR/0012/line_0012345.bvh`` keeps folders at 1000 entries.
SHARD = 1000
ROUND = 6  # decimals kept of each quality figure in the manifest
#: The figures of a join's window (``report["joins"][i]["quality"]["join"]``) a record keeps.
WINDOW_FIGURES = ("skating_ratio", "root_pop", "jerk_p99", "floor_penetration_cm", "frozen_fraction")


@dataclass(frozen=True)
class Options:
    """What decides a line's outputs, shared by every worker.

    Attributes:
        out: absolute output folder (workers must see the same path), or None: parse only.
        db: the database URL the workers open (a shipped SQLite copy: ``shipped:KEY``).
        db_label: the database as the user named it (password hidden): part of :attr:`key`.
        fps: frame rate of the animations (frames/s).
        max_seconds: the output budget of one line (:mod:`text2anim.limits`).
        parse_only: write the parses, do not plan or animate.
    """

    out: str | None = None
    db: str | None = None
    db_label: str = ""
    fps: float = 30.0
    max_seconds: float = MAX_SECONDS
    parse_only: bool = False

    @property
    def animating(self) -> bool:
        return bool(self.out) and not self.parse_only

    @property
    def key(self) -> str:
        """16 hex digits naming everything but the text that decides a line's outputs."""
        from text2anim import __version__

        what = {"fps": self.fps, "animate": self.animating, "db": self.db_label if self.animating else "",
                "version": __version__, **({"max_seconds": self.max_seconds} if self.max_seconds != MAX_SECONDS else {})}
        return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()[:16]


def shard_path(line: int) -> str:
    """Where line ``line``'s BVH goes, relative to the output folder."""
    return f"{line // SHARD:04d}/line_{line:07d}.bvh"


# ------------------------------------------------------------------ databases
_DBS: dict = {}
_COPIES: dict[str, str] = {}  # shipped key -> local SQLite file (registered on each worker)
_LOCK = threading.Lock()
SHIPPED = "shipped:"


def register_copy(key: str, path: str) -> None:
    """Make ``shipped:KEY`` open the read-only SQLite file ``path`` in this process."""
    _COPIES[key] = path


def database(spec: str | None):
    """The motion database ``spec`` names, opened once per process (a shipped copy read-only)."""
    from text2anim.motiondb import MotionDB

    with _LOCK:
        if spec not in _DBS:
            url = spec
            if spec and spec.startswith(SHIPPED):
                path = _COPIES.get(spec[len(SHIPPED):])
                if path is None:
                    raise RuntimeError(f"this worker has no copy of the motion database {spec}")
                url = f"sqlite:///file:{path}?mode=ro&uri=true"
            _DBS[spec] = MotionDB.open(url)
        return _DBS[spec]


# ------------------------------------------------------------------ one line
def _refusals() -> tuple[type, ...]:
    from text2anim.core.bodyparts import BodyMapError
    from text2anim.motiondb import UnknownVerbError
    from text2anim.nlp import NLPError
    from text2anim.limits import InputError
    from text2anim.scheduler.errors import ScheduleError

    return NLPError, ScheduleError, UnknownVerbError, BodyMapError, InputError


def reason_of(exc: BaseException) -> str:
    """A short key that groups refusals and failures of one kind: the message up to its first quote."""
    verb = getattr(exc, "verb", None)
    if isinstance(verb, str):
        return f"unknown verb {verb}"
    head = re.split(r"""['"「:(;]""", str(exc), maxsplit=1)[0].strip()
    return (head or type(exc).__name__)[:60]


def run_line(item: Item, opts: Options) -> dict:
    """Parse (and with ``opts.out`` animate) one line; never raises for a bad line."""
    from text2anim.limits import check_text
    from text2anim.nlp import analyze

    t0, c0 = time.perf_counter(), time.thread_time()
    rec: dict = {"line": item.line, "text_hash": text_hash(item.text), "options": opts.key,
                 "status": "parsed", "reason": None, "text": item.text, "category": item.category}
    parse, error, refused = None, None, False
    clips: dict[int, str] | None = None
    plan_error = None
    try:
        parse = analyze(check_text(item.text)).to_dict(extra=True)  # a control character: refused, --out or not
        if opts.out and opts.parse_only:
            rec["parse"] = parse
        if opts.animating:
            done, clips = _animate(item, opts)
            rec.update(done)
            rec["status"] = "animated"
        elif wants_clips(item.expect):
            clips, plan_error = _planned_clips(item, opts)
    except Exception as exc:  # noqa: BLE001 - one bad line must not stop the batch
        refused = isinstance(exc, _refusals())
        rec.update(status="refused" if refused else "failed", reason=reason_of(exc),
                   error=f"{type(exc).__name__}: {exc}")
        unknown_verb = refused and parse is not None and getattr(exc, "verb", None) is not None
        error = None if unknown_verb else rec["error"]
    rec["time"] = round(time.perf_counter() - t0, 4)  # s, wall
    rec["cpu"] = round(time.thread_time() - c0, 4)     # s, CPU of the thread that ran the line
    mismatches = check(item.expect, parse, error, clips, plan_error)
    expected_error = bool(item.expect and "error" in item.expect)
    rec["check"] = "failed" if mismatches else "errored" if error and not expected_error else "passed"
    rec["mismatches"] = mismatches
    rec["expected_error"] = expected_error
    return rec


def failure_record(item: Item, opts: Options, exc: BaseException) -> dict:
    """The record of a line whose worker kept dying (or whose task failed outside :func:`run_line`)."""
    kind = type(exc).__name__
    msg = f"{kind}: {exc}".splitlines()[0]
    return {"line": item.line, "text_hash": text_hash(item.text), "options": opts.key, "status": "failed",
            "reason": "worker died" if kind == "KilledWorker" else f"task failed ({kind})", "text": item.text, "category": item.category,
            "error": msg, "time": None, "cpu": None, "check": "errored", "mismatches": []}


def run_chunk(chunk: Iterable[Item], opts: Options, emit: Callable[[dict], None]) -> int:
    """Run the lines of one chunk in order, handing each record to ``emit`` as soon as it is done."""
    n = 0
    for item in chunk:
        emit(run_line(item, opts))
        n += 1
    return n


def _planned_clips(item: Item, opts: Options) -> tuple[dict[int, str] | None, str | None]:
    """Motion id -> the clip it plays, through the real planner (no synthesis), or why it could not be planned."""
    from text2anim import plan

    try:
        table = plan(item.text, db=database(opts.db), fps=opts.fps, max_seconds=opts.max_seconds).table
    except Exception as exc:  # noqa: BLE001 - a line that cannot be planned misses its clips, the batch goes on
        return None, f"{type(exc).__name__}: {exc}"
    return {e.id: e.clip for e in table.elements}, None


def _animate(item: Item, opts: Options) -> tuple[dict, dict[int, str]]:
    from text2anim import animate

    assert opts.out is not None, "animating needs an output folder"
    anim = animate(item.text, db=database(opts.db), fps=opts.fps, max_seconds=opts.max_seconds)
    rel = shard_path(item.line)
    path = os.path.join(opts.out, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    files = anim.save_bvh(path)
    report = anim.report
    return {
        "files": [os.path.join(os.path.dirname(rel), f.name) for f in files],
        "skating_ratio": max(a["skating_ratio"] for a in report["actors"].values()),
        "joins": [join_figures(j) for j in report["joins"]],
        "warnings": list(report["warnings"]),
    }, {e.id: e.clip for e in anim.table.elements}


def join_figures(join: dict) -> dict:
    """One join's quality figures (docs/timetable.md §3): those of its window at 30 fps from the report's
    ``quality`` (GMD skating ratio, root pop m/s², jerk p99 m/s³, floor penetration cm, frozen fraction,
    whether each criterion against its source clips is met), the engine's largest foot slide (cm/s)
    and core fidelity (cm). None where the report has no figure."""
    m = join.get("metrics", {})
    q = join.get("quality") or {}
    window = q.get("join", {})
    core = [v for v in (m.get("core_fidelity_cm") or {}).values() if v is not None]  # None: no core

    def fig(x):
        return None if x is None else round(float(x), ROUND)

    return {"first": join.get("first"), "second": join.get("second"), "method": join.get("method"),
            **{k: fig(window.get(k)) for k in WINDOW_FIGURES},
            "max_slide_cm_s": fig(m.get("max_slide_cm_s")),
            "core_fidelity_cm": fig(max(core)) if core else None,
            "meets": q.get("meets")}


# ------------------------------------------------------------------ expectations
#: A clip's captured variants are named after it with the capture's subject and take: stand_up_14_32.
_VARIANT = re.compile(r"_\d+_\d+")


def wants_clips(expect: dict | None) -> bool:
    """Does the expectation name the clip of some motion (``"clip": "stand_up"``)?"""
    motions = (expect or {}).get("motions")
    return isinstance(motions, list) and any(isinstance(m, dict) and "clip" in m for m in motions)


def same_clip(expected: str, actual: str | None) -> bool:
    """``actual`` is the clip ``expected`` or one of its captured variants (stand_up_14_32 for stand_up)."""
    return actual is not None and (actual == expected or (
        actual.startswith(expected) and _VARIANT.fullmatch(actual[len(expected):]) is not None))


def check(expect: dict | None, parse: dict | None, error: str | None,
          clips: dict[int, str] | None = None, plan_error: str | None = None) -> list[str]:
    """Why the line misses its expectation (empty when it meets it or has none).

    ``clips`` (motion id -> the clip its time-table row plays) is checked against the motions'
    ``clip`` expectations; without it (``plan_error`` says why) those expectations are missed.
    """
    if not expect:
        return []
    if "error" in expect:
        want = expect["error"]
        if error is None:
            return [f"expected an error ({want}), got a parse"]
        if isinstance(want, str) and want not in error:
            return [f"expected an error containing {want!r}, got {error!r}"]
        return []
    if parse is None:
        return []  # errored: reported as such
    if wants_clips(expect):
        if clips is None:
            return [f"$.motions: the clips expected, but the line was not planned ({plan_error})"]
        parse = {**parse, "motions": [{**m, "clip": clips.get(m["id"])} for m in parse["motions"]]}
    return list(compare(expect, parse, "$"))


def compare(expected, actual, path: str):
    """Yield a message for each place where ``actual`` does not match ``expected``."""
    if isinstance(expected, dict):
        if not isinstance(actual, dict):
            yield f"{path}: expected an object, got {actual!r}"
            return
        for key, value in expected.items():
            if key not in actual:
                yield f"{path}.{key}: missing"
            elif key == "clip" and isinstance(value, str):
                if not same_clip(value, actual[key]):
                    yield f"{path}.clip: expected {value!r} (or a captured variant), got {actual[key]!r}"
            else:
                yield from compare(value, actual[key], f"{path}.{key}")
    elif isinstance(expected, list):
        if not isinstance(actual, list) or len(actual) != len(expected):
            n = len(actual) if isinstance(actual, list) else "not a list"
            yield f"{path}: expected {len(expected)} items, got {n}"
            return
        for i, (e, a) in enumerate(zip(expected, actual)):
            yield from compare(e, a, f"{path}[{i}]")
    elif isinstance(expected, float) or (isinstance(expected, int) and isinstance(actual, float)):
        if not isinstance(actual, (int, float)) or isinstance(actual, bool) \
                or abs(actual - expected) > 1e-9:
            yield f"{path}: expected {expected!r}, got {actual!r}"
    elif expected != actual or type(expected) is not type(actual):
        yield f"{path}: expected {expected!r}, got {actual!r}"
