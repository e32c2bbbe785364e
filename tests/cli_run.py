"""Run the real ``text2anim`` command in a subprocess, as a user would."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def text2anim(*args: str, input: str | None = None, cwd=None, env=None) -> subprocess.CompletedProcess:
    """``text2anim ARGS`` in ``cwd`` (the repo by default), this checkout's code first on the path."""
    env = {**os.environ, **(env or {})}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(REPO), env.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, "-m", "text2anim.cli.main", *map(str, args)], capture_output=True, text=True,
                          input=input, cwd=cwd or REPO, env=env, timeout=300)


def assert_clean_error(proc: subprocess.CompletedProcess, *fragments: str) -> None:
    """One message on stderr, exit code 2, no traceback."""
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    assert "Traceback" not in proc.stderr, proc.stderr
    for f in fragments:
        assert f in proc.stderr, (f, proc.stderr)
