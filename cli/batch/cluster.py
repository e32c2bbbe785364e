"""Chunks on a Dask cluster: a running one (``--scheduler``) or a local one of ``--jobs`` processes.

Each chunk is one task. Its worker opens the motion database once (a
PostgreSQL URL is shared; an SQLite database is copied, read-only, to every
worker by a worker plugin, so a worker started later gets it too) and puts the
record of every finished line on a :class:`distributed.Queue` at once; the
scheduler holds it from then on, so a worker that dies loses no finished line.
Dask runs the dead worker's chunk again elsewhere; its lines already recorded
come back a second time and are dropped. A chunk that keeps killing its
workers (Dask gives up after ``distributed.scheduler.allowed-failures``) is
split into single lines, and only the line that kills is recorded as failed.
"""
from __future__ import annotations

import logging
import os
import sqlite3
import tempfile
import time
import uuid
from dataclasses import replace
from typing import Any, Callable

from distributed import Client, LocalCluster, Queue, WorkerPlugin, wait
from text2anim.core.atomic import write_all

from . import lines
from .corpus import Item
from .errors import BatchError
from .lines import Options

CONNECT_TIMEOUT = 30  # s to reach a scheduler
POLL = 0.2            # s between looks at the queue while no task ends


class ShipDatabase(WorkerPlugin):
    """Writes a read-only copy of an SQLite motion database into each worker's local folder."""

    idempotent = True

    def __init__(self, key: str, data: bytes):
        self.key, self.data = key, data
        self.name = f"text2anim-db-{key}"

    def setup(self, worker):
        path = os.path.join(worker.local_directory, f"motions-{self.key}.sqlite")
        if not os.path.exists(path):
            write_all({path: self.data})  # our atomic write: a killed worker's temporary is cleaned next time
            os.chmod(path, 0o444)
        lines.register_copy(self.key, path)


def _task(chunk: list[Item], opts: Options, queue_name: str) -> int:
    """A chunk on a worker: each line's record goes on the queue as soon as the line is done."""
    queue = Queue(queue_name)
    return lines.run_chunk(chunk, opts, queue.put)


class DaskExecutor:
    """Runs chunks on a Dask cluster and hands their records, as they arrive, to the driver."""

    def __init__(self, jobs: int, scheduler: str | None):
        self.jobs, self.scheduler = jobs, scheduler
        self.client: Any = None    # a distributed.Client once entered
        self._cluster: Any = None  # the LocalCluster this executor started, if any

    def __enter__(self):
        if self.scheduler:
            try:
                self.client = Client(self.scheduler, timeout=CONNECT_TIMEOUT)
            except (OSError, TimeoutError, ValueError) as exc:
                raise BatchError(f"cannot reach the Dask scheduler at {self.scheduler}: {exc}") from None
        else:
            self._cluster = LocalCluster(n_workers=self.jobs, threads_per_worker=1, processes=True,
                                         dashboard_address=":0", silence_logs=logging.ERROR)
            self.client = Client(self._cluster)
        return self

    def __exit__(self, *exc):
        if self.client is not None:
            self.client.close()
        if self._cluster is not None:
            self._cluster.close()

    def prepare(self, opts: Options) -> Options:
        """Check the workers see the output folder; ship an SQLite database to them."""
        from text2anim import __version__

        try:
            versions = self.client.run(_version)
        except Exception as exc:  # noqa: BLE001 - a worker without text2anim cannot even load _version
            raise BatchError(f"the Dask workers cannot run text2anim ({type(exc).__name__}: {exc}); install "
                             "it on them (pip install 'text2anim[cluster]')") from None
        other = sorted({str(v) for v in versions.values()} - {__version__})
        if other:
            raise BatchError(f"the Dask workers run text2anim {', '.join(other)}, this is {__version__}: install "
                             "the same version on the workers (pip install 'text2anim[cluster]')")
        if opts.out:
            seen = self.client.run(os.path.isdir, opts.out)
            blind = sorted(w for w, ok in seen.items() if not ok)
            if blind:
                raise BatchError(f"the workers {', '.join(blind[:3])} do not see the output folder {opts.out}: "
                                 "give --out a folder on storage every worker shares")
        if opts.db and opts.db.startswith("sqlite:"):
            key, data = _snapshot(opts.db)
            self.client.register_plugin(ShipDatabase(key, data))
            opts = replace(opts, db=lines.SHIPPED + key)
        return opts

    def run(self, work: list[list[Item]], opts: Options, emit: Callable[[dict], None]) -> None:
        client = self.client
        queue = Queue(f"text2anim-batch-{uuid.uuid4().hex}", client=client)
        todo = list(reversed(work))
        pending: dict = {}
        recorded: set[int] = set()

        def deliver(recs):
            for rec in recs:
                recorded.add(rec["line"])
                emit(rec)

        window, checked = 2, 0.0
        while todo or pending:
            if time.monotonic() - checked > 2.0:  # follow a cluster that grows or shrinks
                window, checked = max(2, 2 * sum(client.nthreads().values())), time.monotonic()
            while todo and len(pending) < window:
                chunk = todo.pop()
                pending[client.submit(_task, chunk, opts, queue.name, pure=False)] = chunk
            recs = queue.get(batch=True)
            if not recs:  # nothing yet: sleep until a task ends or POLL s pass
                try:
                    wait(list(pending), timeout=POLL, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    pass
            deliver(recs)
            ended = [f for f in pending if f.done()]
            deliver(queue.get(batch=True))  # after seeing a task end: its records are all on the queue
            for fut in ended:
                chunk = pending.pop(fut)
                if fut.status == "finished":
                    continue
                left = [it for it in chunk if it.line not in recorded]
                exc = _exception(fut)
                if len(left) > 1 and type(exc).__name__ == "KilledWorker":
                    todo.extend([it] for it in reversed(left))  # one line may be killing its workers: try each alone
                else:
                    deliver([lines.failure_record(it, opts, exc) for it in left])
        deliver(queue.get(batch=True))


def _version() -> str | None:
    """The text2anim version a worker has (None: not installed)."""
    try:
        from text2anim import __version__
    except ImportError:
        return None
    return __version__


def _exception(fut) -> BaseException:
    try:
        return fut.exception(timeout=5) or RuntimeError(fut.status)
    except BaseException as exc:  # noqa: BLE001 - a cancelled future raises instead of returning
        return exc


def _snapshot(url: str) -> tuple[str, bytes]:
    """A consistent copy of the SQLite database at ``url`` as bytes, and a key naming its contents."""
    import hashlib

    from sqlalchemy.engine import make_url

    path = make_url(url).database
    with tempfile.TemporaryDirectory(prefix="t2a-ship-") as tmp:
        copy = os.path.join(tmp, "motions.sqlite")
        src, dst = sqlite3.connect(f"file:{path}?mode=ro", uri=True), sqlite3.connect(copy)
        try:
            src.backup(dst)  # a consistent copy even while another process writes
        finally:
            src.close()
            dst.close()
        with open(copy, "rb") as fh:
            data = fh.read()
    return hashlib.sha256(data).hexdigest()[:16], data
