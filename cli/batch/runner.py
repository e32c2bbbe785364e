"""The batch driver: corpus → chunks → an executor → records into the manifest and the summary.

There is one way a line is run (:func:`lines.run_chunk`) and one driver; what
differs is only where chunks run. ``jobs=1`` without a scheduler runs them in
this process (the reference path; no Dask needed); anything else runs them on
a Dask cluster, a :class:`~distributed.LocalCluster` of ``jobs`` worker
processes or the one at ``scheduler`` (see :mod:`.cluster`).
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass, replace
from typing import Callable

from text2anim.core.atomic import atomic_write_text

from . import lines
from .corpus import CorpusError, Item, chunks, load_corpus
from .errors import BatchError
from .lines import Options
from .lock import owning
from .manifest import Manifest
from .summary import Summary

DEFAULT_CHUNK = 16  # lines per task: ~5 s of work, small enough to retry, large enough to amortise


@dataclass
class Outcome:
    """What :func:`run_corpus` did: the summary (all lines, earlier runs' too) and this run's counts."""

    summary: Summary
    lines: int          # lines in the corpus
    skipped: int        # already done by an earlier run (same text hash and options)
    ran: int            # run now
    repeated: int = 0   # records that arrived twice (a chunk retried after its worker died), dropped


class InProcess:
    """Runs every chunk here, one after the other: the single-process path."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return None

    def prepare(self, opts: Options) -> Options:
        return opts

    def run(self, work: list[list[Item]], opts: Options, emit: Callable[[dict], None]) -> None:
        for chunk in work:
            lines.run_chunk(chunk, opts, emit)


def run_corpus(corpus: str, opts: Options, *, jobs: int = 1, scheduler: str | None = None,
               chunk: int = DEFAULT_CHUNK,
               on_record: Callable[[dict, int, int], None] | None = None,
               on_start: Callable[[int, int], None] | None = None, wait: bool = False) -> Outcome:
    """Run every line of the corpus file ``corpus`` not already done in ``opts.out``.

    ``opts.out`` is owned for the run (:mod:`.lock`): another run on it is a :class:`BatchError`,
    or, with ``wait``, waited for.

    Args:
        opts: the outputs' options; ``opts.db`` as the user gave it (None: the default database).
        jobs: local worker processes when there is no ``scheduler`` (1: this process).
        scheduler: address of a running Dask scheduler (``tcp://host:8786``).
        chunk: lines per task.
        on_record: called with each new record, the number done so far and the number to do.
        on_start: called once with the number of lines to run and the number already done.
        wait: wait for another run that owns ``opts.out`` instead of refusing.
    """
    if jobs < 1:
        raise BatchError("--jobs must be at least 1")
    if chunk < 1:
        raise BatchError("--chunk must be at least 1")
    items = load_corpus(corpus)
    if not items:
        raise CorpusError(f"{corpus}: no lines to run")
    opts = _resolve(opts)
    executor = InProcess() if jobs == 1 and not scheduler else _cluster(jobs, scheduler)
    if not opts.out:
        return _run(items, opts, executor, chunk, None, on_record, on_start)
    os.makedirs(opts.out, exist_ok=True)
    with owning(opts.out, wait):
        return _run(items, opts, executor, chunk, Manifest.open(opts.out, items, opts.key), on_record, on_start)


def _run(items: list[Item], opts: Options, executor, chunk: int, manifest: Manifest | None,
         on_record: Callable[[dict, int, int], None] | None,
         on_start: Callable[[int, int], None] | None) -> Outcome:
    """The lines not yet in ``manifest`` run on ``executor``, ``chunk`` lines a task; the manifest and
    summary written as they come."""
    summary = Summary()
    if manifest is not None:
        for rec in manifest.kept:
            summary.add(rec)
    todo = [it for it in items if manifest is None or not manifest.done(it)]
    outcome = Outcome(summary, len(items), len(items) - len(todo), 0)
    if on_start:
        on_start(len(todo), outcome.skipped)
    seen: set[int] = set()

    def emit(rec: dict) -> None:
        if rec["line"] in seen:
            outcome.repeated += 1
            return
        seen.add(rec["line"])
        if manifest is not None:
            manifest.write(rec)
        summary.add(rec)
        outcome.ran += 1
        if on_record:
            on_record(rec, outcome.ran, len(todo))

    try:
        if todo:
            with executor:
                executor.run(chunks(todo, chunk), executor.prepare(opts), emit)
    finally:
        if manifest is not None and opts.out:
            manifest.close()
            atomic_write_text(os.path.join(opts.out, "summary.json"),
                              json.dumps(summary.to_dict(), ensure_ascii=False, indent=2) + "\n")
    return outcome


def _resolve(opts: Options) -> Options:
    """Absolute output folder; the database opened once here (created and seeded if new, or a clear error)."""
    out = os.path.abspath(opts.out) if opts.out else None
    if not (out and not opts.parse_only):
        return replace(opts, out=out, db=None, db_label="")
    from text2anim.motiondb import MotionDB
    from text2anim.motiondb.location import resolve_url

    url, _ = resolve_url(opts.db)
    with MotionDB.open(url) as db:
        label = db.url
    return replace(opts, out=out, db=url, db_label=label)


def _cluster(jobs: int, scheduler: str | None):
    from text2anim.core import extras

    extras.require("distributed", "--jobs above 1 or --scheduler (Dask)")
    from .cluster import DaskExecutor

    return DaskExecutor(jobs, scheduler)
