"""A write killed half-way leaves no lasting litter: its hidden temporary is removed by the next write."""
from __future__ import annotations

import os
import signal
import subprocess
import sys

from cli_run import REPO
from text2anim.core.atomic import remove_stale_parts, write_all

WRITER = """
import sys, time
from pathlib import Path
from text2anim.core.atomic import write_all

def slow(tmp: Path) -> None:
    tmp.write_bytes(b"half")
    print("writing", flush=True)
    time.sleep(60)

write_all({sys.argv[1]: slow})
"""


def _killed_writer(out) -> None:
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    proc = subprocess.Popen([sys.executable, "-c", WRITER, str(out)], stdout=subprocess.PIPE, text=True, env=env)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "writing"
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)


def test_a_temporary_left_by_a_killed_writer_is_removed_by_the_next_write(tmp_path):
    out = tmp_path / "anim.bvh"
    out.write_bytes(b"before")
    _killed_writer(out)
    left = [p for p in tmp_path.iterdir() if p.name.endswith(".part")]
    assert len(left) == 1 and left[0].name.startswith(".anim.bvh.")  # kill -9: the temporary stays, hidden
    assert out.read_bytes() == b"before"  # and the file it would have replaced is untouched
    other = tmp_path / ".anim.bvh.notes.part"  # not one of ours (no pid): left alone
    other.write_bytes(b"x")
    write_all({out: b"after"})
    assert out.read_bytes() == b"after"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([".anim.bvh.notes.part", "anim.bvh"])


def test_a_live_writers_temporary_is_not_touched(tmp_path):
    out = tmp_path / "anim.bvh"
    mine = tmp_path / f".anim.bvh.{os.getppid()}.abcd_123.part"  # our parent process: alive
    mine.write_bytes(b"in progress")
    assert remove_stale_parts(out) == []
    assert mine.exists()
