"""One command of the real CLI run as a user would, measured against the bounds every input has (issue 41):
no traceback, at most 10 s and 1 GB (its own peak resident memory, from ``wait4``), no raw control
character reaching the terminal. Shared by the fuzzers (``fuzz_bvh.py``, ``fuzz_rig.py``, ``fuzz_text.py``).
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
LIMIT_S = 10.0
LIMIT_MB = 1024.0
#: What a terminal would act on: C0 but tab and line feed, DEL, C1, text-direction overrides.
RAW_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


@dataclass(frozen=True)
class Run:
    """One command: its exit code, wall and CPU seconds, peak resident MB and what it printed. The time bound
    is on CPU seconds (user + system): four engineers share this machine's two cores, so wall time
    measures the neighbours as much as the command."""

    case: str
    code: int
    wall: float
    cpu: float
    mb: float
    out: str

    @property
    def traceback(self) -> bool:
        return "Traceback" in self.out or self.code not in (0, 1, 2)

    @property
    def raw_control(self) -> bool:
        return bool(RAW_CONTROL.search(self.out))

    @property
    def failures(self) -> list[str]:
        why = []
        if self.traceback:
            why.append(f"exit {self.code} / traceback")
        if self.cpu > LIMIT_S:
            why.append(f"{self.cpu:.1f} s CPU")
        if self.mb > LIMIT_MB:
            why.append(f"{self.mb:.0f} MB")
        if self.raw_control:
            why.append("raw control character printed")
        return why

    def row(self) -> str:
        last = RAW_CONTROL.sub(lambda m: repr(m.group())[1:-1], (self.out.strip().splitlines() or [""])[-1][:70])
        return f"| {self.case} | {self.code} | {self.wall:.2f} | {self.cpu:.2f} | {self.mb:.0f} | {'; '.join(self.failures) or 'clean'} | {last} |"


def text2anim(case: str, *args: str, cwd: Path | None = None, timeout: float = 60.0) -> Run:
    """``text2anim ARGS`` in a child process (this checkout's code), stdout and stderr together; the child
    is measured by GNU time for its own peak memory, and killed after ``timeout`` seconds."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO), os.environ.get("PYTHONPATH")]))}
    t0 = time.perf_counter()
    peak = tempfile.NamedTemporaryFile(suffix=".maxrss")
    # GNU time reports the command's own peak (a child forked from this process would count this one's)
    command = ["/usr/bin/time", "-f", "%U %S %M", "-o", peak.name, sys.executable, "-m", "text2anim.cli.main"]
    with open(os.devnull, "rb") as stdin:
        proc = subprocess.Popen([*command, *map(str, args)], stdin=stdin,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, cwd=cwd or REPO, env=env)
    chunks: list[bytes] = []
    reader = threading.Thread(target=lambda: chunks.extend(iter(lambda: proc.stdout.read(65536), b"")))
    reader.start()
    killer = threading.Timer(timeout, proc.kill)
    killer.start()
    code = proc.wait()
    wall = time.perf_counter() - t0
    killer.cancel()
    reader.join()
    proc.stdout.close()
    text = b"".join(chunks).decode("utf-8", "replace")
    if text.startswith("Command exited with non-zero status") or "\nCommand exited with non-zero status" in text:
        text = re.sub(r"(^|\n)Command (exited with non-zero status|terminated by signal) \d+\n?", r"\1", text)
    with peak:
        lines = Path(peak.name).read_text().split()
    cpu = float(lines[-3]) + float(lines[-2]) if len(lines) >= 3 else float("nan")
    mb = float(lines[-1]) / 1024 if lines else float("nan")
    return Run(case, code, wall, cpu, mb, text)


def table(runs: list[Run]) -> str:
    """A Markdown table of the runs and a last line counting the failures."""
    lines = ["| case | exit | wall s | CPU s | peak MB | result | last line printed |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    lines += [r.row() for r in runs]
    bad = [r for r in runs if r.failures]
    lines.append(f"\n{len(runs)} runs: {sum(r.traceback for r in runs)} tracebacks, "
                 f"{sum(r.cpu > LIMIT_S for r in runs)} over {LIMIT_S:g} s CPU, {sum(r.mb > LIMIT_MB for r in runs)} over "
                 f"{LIMIT_MB:g} MB, {sum(r.raw_control for r in runs)} with raw control characters; "
                 f"{'clean' if not bad else f'{len(bad)} failing'}")
    return "\n".join(lines)
