"""What a skipped test is missing, and how to get it: the groups of the summary that ends ``pytest -q``.

Each skip's reason is matched against :data:`GROUPS` in order; the first whose pattern is found names
what is missing. A reason no group matches is listed as it is under "other" (a new kind of skip
should get its group here: tests/test_skip_summary.py checks the suite's own reasons).
"""
from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass


@dataclass(frozen=True)
class Group:
    """``what`` is missing (the summary's heading), ``pattern`` finds it in a skip's reason, ``how`` gets it."""

    what: str
    pattern: str
    how: str


GROUPS = (
    Group("real motion capture (../shared/mocap/)", r"Real capture for the tests|shared (CMU|everyday) ",
          "README.md: Real capture for the tests"),
    Group("PostgreSQL", r"PostgreSQL|psycopg2",
          "pip install '.[postgres]', then a server named by TEXT2ANIM_TEST_PG_URL (.ci/run starts one)"),
    Group("Chromium", r"chromium not installed|apt-get install chromium", "apt-get install chromium chromium-driver"),
    Group("Playwright", r"Playwright is not installed|playwright", "pip install '.[test]'"),
    Group("Node.js and the npm packages of tests/browser", r"\bnode not installed|Node\.js|npm package",
          "apt-get install nodejs npm && npm ci --prefix tests/browser"),
    Group("matplotlib", r"matplotlib", "pip install '.[plot]'"),
    Group("Blender (bpy)", r"T2A_BLENDER_PYTHON", "pip install bpy in a Python 3.11 venv; T2A_BLENDER_PYTHON=its python"),
    Group("an x86-64 CPU with AVX2", r"AVX2", "the byte-identity check runs only on such a CPU"),
    Group("the built-in motion library", r"built-?in library|builtin_clips", "pip install . (it ships the library)"),
)
OTHER = Group("other", "", "see the reasons")


def group_of(reason: str) -> Group:
    """The :class:`Group` of one skip ``reason`` (:data:`OTHER` when none matches)."""
    return next((g for g in GROUPS if re.search(g.pattern, reason, re.I)), OTHER)


def summary(reasons: list[str]) -> list[str]:
    """The summary's lines for the ``reasons`` of a run's skips: a heading, then per group (most skips
    first) how many, what is missing and how to get it; under "other", the reasons themselves."""
    if not reasons:
        return []
    by_group = Counter(group_of(r) for r in reasons)
    lines = [f"{len(reasons)} skipped, for want of:"]
    for g, n in sorted(by_group.items(), key=lambda kv: (kv[0] is OTHER, -kv[1], kv[0].what)):
        lines.append(f"  {n:4d}  {g.what}: {g.how}")
        if g is OTHER:
            lines += [f"          {r}" for r in sorted({r for r in reasons if group_of(r) is OTHER})]
    return lines
