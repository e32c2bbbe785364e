"""``text2anim batch``: run a corpus through the pipeline, check expectations.

A corpus line is either plain text or a JSON object::

    {"text": "...", "category": "te", "expect": {...}}

``expect`` is a subset of the parse JSON (language.md §5, plus ``hold``,
``reading`` and ``cue``): every key given must match, lists element by
element and of the same length; ``{"error": "words"}`` expects the line to be
refused with a message containing the words.  Blank lines and lines starting
with ``#`` are skipped.

Every line is parsed; with ``--out DIR`` it is also planned and animated
with clips from the motion database (``--db``): ``DIR/line_NNNN.bvh`` per
line, its time table and per-join figures in ``DIR/results.jsonl``. A line
whose verbs the database lacks is recorded as skipped for animation, not as
an error.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from functools import partial

from text2anim.limits import MAX_SECONDS

from .bvh_options import add_budget_option, fps_type

NAME = "batch"
HELP = ("run every line of a corpus through parse (and plan + animation with --out), print a "
        "summary and, with --check, fail when an expectation is not met")

EXIT_FAILED = 1


class CorpusError(ValueError):
    """A corpus file that cannot be read as text lines or JSON lines."""

    user_facing = True


@dataclass(frozen=True)
class Item:
    line: int
    text: str
    category: str | None = None
    expect: dict | None = None


@dataclass
class Result:
    line: int
    text: str
    category: str | None
    status: str  # passed | failed | errored
    stages: dict = field(default_factory=dict)
    mismatches: list = field(default_factory=list)
    error: str | None = None

    def to_dict(self) -> dict:
        return {"line": self.line, "text": self.text, "category": self.category,
                "status": self.status, "mismatches": self.mismatches, "error": self.error,
                **self.stages}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("corpus", metavar="CORPUS",
                        help="file of text lines or JSON lines with expected parses")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when any line fails its expectation or errors")
    parser.add_argument("--jobs", type=int, default=1, metavar="N",
                        help="worker processes (results identical to serial; default 1)")
    parser.add_argument("--out", metavar="DIR",
                        help="also plan and animate every line: DIR/line_NNNN.bvh, per-line results in "
                             "DIR/results.jsonl and DIR/summary.json")
    parser.add_argument("--parse-only", action="store_true",
                        help="with --out: write the parse results only, do not plan or animate")
    parser.add_argument("--db", metavar="URL", help="motion database for --out (default: $TEXT2ANIM_DB "
                        "or the user's data directory)")
    parser.add_argument("--fps", type=fps_type, default=30.0, help="frame rate of the animations, 1 to 240 (default 30)")
    add_budget_option(parser)


@dataclass(frozen=True)
class Config:
    """What the stages after parse need: where to write, which database, which frame rate."""

    out: str | None = None
    db: str | None = None
    fps: float = 30.0
    max_seconds: float = MAX_SECONDS


# ---------------------------------------------------------------- corpus


def load_corpus(path: str) -> list[Item]:
    items = []
    with open(path, encoding="utf-8") as fh:
        for n, raw in enumerate(fh, 1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            items.append(_parse_line(line, n, path))
    return items


def _parse_line(line: str, n: int, path: str) -> Item:
    if not line.startswith("{"):
        return Item(n, line)
    try:
        obj = json.loads(line)
    except json.JSONDecodeError as exc:
        raise CorpusError(f"{path}:{n}: not valid JSON: {exc.msg}") from None
    if not isinstance(obj, dict) or not isinstance(obj.get("text"), str):
        raise CorpusError(f'{path}:{n}: a JSON line needs a "text" string')
    expect = obj.get("expect")
    if expect is not None and not isinstance(expect, dict):
        raise CorpusError(f'{path}:{n}: "expect" must be an object')
    return Item(n, obj["text"], obj.get("category"), expect)


# ---------------------------------------------------------------- stages


def stage_parse(text: str) -> dict:
    """The parse JSON of ``text`` with the extended fields."""
    from text2anim.nlp import analyze

    return analyze(text).to_dict(extra=True)


_DB = {}  # one open database per process and URL


def _database(url: str | None):
    from text2anim.motiondb import MotionDB

    if url not in _DB:
        _DB[url] = MotionDB.open(url)
    return _DB[url]


def stage_animate(item: Item, cfg: Config) -> dict:
    """Plan and animate one line; its BVH goes to ``cfg.out``. Unknown verbs: ``{"skipped": ...}``."""
    from text2anim.motiondb import UnknownVerbError
    from text2anim.animation import animate

    try:
        anim = animate(item.text, db=_database(cfg.db), fps=cfg.fps, max_seconds=cfg.max_seconds)
    except UnknownVerbError as exc:
        return {"skipped": str(exc)}
    files = anim.save_bvh(os.path.join(cfg.out, f"line_{item.line:04d}.bvh"))
    report = anim.report
    joins = report["joins"]
    return {
        "plan": [{k: e[k] for k in ("id", "actor", "verb", "clip", "method", "prev", "start", "end")}
                 for e in report["time_table"]],
        "files": [os.path.basename(f) for f in files],
        "skating_ratio": max(a["skating_ratio"] for a in report["actors"].values()),
        "join_skating_ratio": max((j["metrics"].get("skating_ratio", 0.0) for j in joins), default=0.0),
        "joins": len(joins),
        "warnings": report["warnings"],
    }


def run_item(item: Item, cfg: Config = Config()) -> Result:
    """Run one corpus line through the stages and check its expectation."""
    stages: dict = {}
    error = None
    try:
        stages["parse"] = stage_parse(item.text)
        if cfg.out:
            stages["animate"] = stage_animate(item, cfg)
    except Exception as exc:  # noqa: BLE001 - one bad line must not stop the batch
        error = f"{type(exc).__name__}: {exc}"
    mismatches = _check(item.expect, stages.get("parse"), error)
    if mismatches:
        status = "failed"
    elif error and not (item.expect and "error" in item.expect):
        status = "errored"
    else:
        status = "passed"
    return Result(item.line, item.text, item.category, status, stages, mismatches, error)


def _check(expect: dict | None, parse: dict | None, error: str | None) -> list[str]:
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


# ---------------------------------------------------------------- running


def run_all(items: list[Item], jobs: int = 1, progress=None, cfg: Config = Config()) -> list[Result]:
    """Results in corpus order, serially or on ``jobs`` processes."""
    progress = progress or (lambda done, total: None)
    results: list[Result] = []
    run_one = partial(run_item, cfg=cfg)
    if jobs <= 1 or len(items) < 2:
        iterator = map(run_one, items)
        for r in iterator:
            results.append(r)
            progress(len(results), len(items))
        return results
    chunksize = max(1, len(items) // (jobs * 8))
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        for r in pool.map(run_one, items, chunksize=chunksize):
            results.append(r)
            progress(len(results), len(items))
    return results


def make_progress(stream=None):
    """A bar redrawn in place on a terminal; otherwise about ten counter lines."""
    stream = stream or sys.stderr
    tty = stream.isatty()

    def show(done: int, total: int) -> None:
        if tty:
            width = 30
            filled = width * done // total
            stream.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total}")
            if done == total:
                stream.write("\n")
            stream.flush()
        elif done == total or done % max(1, total // 10) == 0:
            stream.write(f"batch: {done}/{total}\n")

    return show


def summarize(results: list[Result]) -> dict:
    def counts(rs):
        c = {"passed": 0, "failed": 0, "errored": 0}
        for r in rs:
            c[r.status] += 1
        c["total"] = len(rs)
        return c

    cats = sorted({r.category for r in results if r.category})
    summary = {
        **counts(results),
        "categories": {c: counts([r for r in results if r.category == c]) for c in cats},
    }
    animated = [r.stages["animate"] for r in results if "animate" in r.stages]
    if animated:
        done = [a for a in animated if "skipped" not in a]
        summary["animation"] = {
            "rendered": len(done), "skipped_unknown_verb": len(animated) - len(done),
            "joins": sum(a["joins"] for a in done),
            "max_skating_ratio": max((a["skating_ratio"] for a in done), default=0.0),
            "max_join_skating_ratio": max((a["join_skating_ratio"] for a in done), default=0.0),
        }
    return summary


def format_summary(summary: dict, results: list[Result], max_listed: int = 20) -> str:
    lines = []
    bad = [r for r in results if r.status != "passed"]
    for r in bad[:max_listed]:
        lines.append(f"{r.status.upper()} line {r.line}: {r.text}")
        for m in r.mismatches:
            lines.append(f"    {m}")
        if r.status == "errored":
            lines.append(f"    {r.error}")
    if len(bad) > max_listed:
        lines.append(f"... and {len(bad) - max_listed} more")
    if summary["categories"]:
        width = max(len(c) for c in summary["categories"])
        for cat, c in summary["categories"].items():
            lines.append(f"  {cat:<{width}}  passed {c['passed']:>3}  failed {c['failed']:>3}"
                         f"  errored {c['errored']:>3}")
    if "animation" in summary:
        a = summary["animation"]
        lines.append(f"animation: {a['rendered']} rendered, {a['skipped_unknown_verb']} skipped (unknown verb), "
                     f"{a['joins']} joins, max foot-skating ratio {a['max_skating_ratio']:.4f} "
                     f"(in joins {a['max_join_skating_ratio']:.4f})")
    lines.append(f"passed {summary['passed']}, failed {summary['failed']}, "
                 f"errored {summary['errored']} (of {summary['total']})")
    return "\n".join(lines) + "\n"


def write_out(out_dir: str, results: list[Result], summary: dict) -> None:
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "results.jsonl"), "w", encoding="utf-8") as fh:
        for r in results:
            fh.write(json.dumps(r.to_dict(), ensure_ascii=False) + "\n")
    with open(os.path.join(out_dir, "summary.json"), "w", encoding="utf-8") as fh:
        json.dump(summary, fh, ensure_ascii=False, indent=2)
        fh.write("\n")


def run(args: argparse.Namespace) -> int:
    if args.jobs < 1:
        raise CorpusError("--jobs must be at least 1")
    items = load_corpus(args.corpus)
    if not items:
        raise CorpusError(f"{args.corpus}: no lines to run")
    if args.out:
        os.makedirs(args.out, exist_ok=True)
    cfg = Config(None if args.parse_only else args.out, args.db, args.fps, args.max_seconds)
    results = run_all(items, args.jobs, make_progress(), cfg)
    summary = summarize(results)
    if args.out:
        write_out(args.out, results, summary)
    sys.stdout.write(format_summary(summary, results))
    if args.check and (summary["failed"] or summary["errored"]):
        return EXIT_FAILED
    return 0
