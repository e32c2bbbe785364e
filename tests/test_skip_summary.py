"""Why tests skip, said once at the end of ``pytest -q``: grouped by what is missing and how to get it."""
from __future__ import annotations

import ast
import os
import re
import subprocess
import sys
from pathlib import Path

from skip_groups import OTHER, group_of

TESTS = Path(__file__).resolve().parent


def test_the_summary_groups_the_skips_by_what_is_missing_and_how_to_get_it():
    """A plain run of two files with PostgreSQL and Blender left out: the last lines before pytest's own
    count say how many skipped for each and how to get it, and add up to pytest's count."""
    env = {k: v for k, v in os.environ.items() if k not in ("TEXT2ANIM_TEST_PG_URL", "T2A_BLENDER_PYTHON")}
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           "tests/cli/test_db_cli.py::test_preview_draws_a_contact_sheet",
                           "tests/output/test_gltf.py", "-k", "preview or blender"],
                          cwd=TESTS.parent, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:]
    lines = proc.stdout.strip().splitlines()
    total = int(re.search(r"(\d+) skipped", lines[-1]).group(1))
    head = next(k for k, ln in enumerate(lines) if ln.endswith("skipped, for want of:"))
    assert lines[head] == f"{total} skipped, for want of:"
    groups = {m.group(2): int(m.group(1)) for ln in lines[head + 1:-1] if (m := re.match(r"\s+(\d+)  ([^:]+):", ln))}
    assert groups == {"PostgreSQL": 1, "Blender (bpy)": total - 1}
    assert "pip install '.[postgres]'" in proc.stdout and "T2A_BLENDER_PYTHON=" in proc.stdout


def _reasons(tree: ast.AST) -> list[str]:
    """The skip reasons written in a test file: ``reason=`` of skipif/importorskip, ``pytest.skip``'s message
    (an f-string's fixed parts), and an importorskip's module name when it gives no reason."""
    def text(node) -> str:
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return node.value
        if isinstance(node, ast.JoinedStr):
            return "".join(text(v) if not isinstance(v, ast.FormattedValue) else " ... " for v in node.values)
        return ""

    out = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Attribute):
            continue
        name = node.func.attr
        reason = next((text(k.value) for k in node.keywords if k.arg == "reason"), "")
        if name == "skip" and node.args:
            reason = text(node.args[0])
        elif name == "importorskip" and not reason and node.args:
            reason = f"could not import {text(node.args[0])!r}"
        elif name != "skipif":
            continue
        if reason:
            out.append(reason)
    return out


def test_every_skip_in_the_suite_says_what_it_misses():
    reasons = {f"{p.relative_to(TESTS)}: {r}": r for p in TESTS.rglob("*.py") for r in _reasons(ast.parse(p.read_text()))}
    assert len(reasons) > 20
    assert {where for where, r in reasons.items() if group_of(r) is OTHER} == set()
