"""Without the extras (a plain ``pip install .``): each command that needs one says which, exit 2, no traceback.

The commands run in a real subprocess whose Python cannot import matplotlib, Dask or the PostgreSQL
drivers: a ``sitecustomize`` on ``PYTHONPATH`` wraps every import finder so that it finds nothing
of those packages, as on a machine where they were never installed (``importlib.util.find_spec``
answers ``None``, an import raises ``ModuleNotFoundError``). Nothing of ours is replaced.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

from cli_run import REPO, assert_clean_error, text2anim

#: The optional top-level packages (pyproject's extras plot, cluster, postgres) hidden from the subprocess.
HIDDEN = ("matplotlib", "dask", "distributed", "psycopg2", "psycopg")

SITECUSTOMIZE = f'''
import sys

HIDDEN = {HIDDEN!r}


class _Without:
    """An import finder that finds nothing of HIDDEN and otherwise does what the finder it wraps does."""

    def __init__(self, finder):
        self.finder = finder

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in HIDDEN or not hasattr(self.finder, "find_spec"):
            return None
        return self.finder.find_spec(name, path, target)

    def __getattr__(self, attr):
        return getattr(self.finder, attr)


sys.meta_path[:] = [_Without(f) for f in sys.meta_path]
'''


@pytest.fixture(scope="module")
def without_extras(tmp_path_factory) -> dict:
    """The environment of a Python on which none of the extras is installed."""
    folder = tmp_path_factory.mktemp("no-extras")
    (folder / "sitecustomize.py").write_text(SITECUSTOMIZE, encoding="utf-8")
    return {"PYTHONPATH": str(folder)}


def test_the_environment_has_no_extras(without_extras):
    import os

    env = {**os.environ, "PYTHONPATH": os.pathsep.join([without_extras["PYTHONPATH"], str(REPO)])}
    code = ("import importlib.util as u, sys; import text2anim, numpy; "
            f"sys.exit(any(u.find_spec(m) for m in {HIDDEN!r}))")
    assert subprocess.run([sys.executable, "-c", code], env=env).returncode == 0
    proc = subprocess.run([sys.executable, "-c", "import matplotlib"], env=env, capture_output=True, text=True)
    assert "No module named 'matplotlib'" in proc.stderr


def test_the_first_command_of_the_readme_needs_no_extra(tmp_path, library_db, without_extras):
    proc = text2anim("太郎は走って、ボールを蹴る。そして喜ぶ。", "-o", "taro.bvh", "--html", "taro.html",
                     "--db", library_db, cwd=tmp_path, env=without_extras)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taro.bvh", "taro.html"]


#: Every command that needs an extra, and the extra its message must name.
NEEDS_AN_EXTRA = [
    (("太郎は走る。", "-o", "a.bvh", "--plot", "speeds.png"), "plot"),
    (("compare", "太郎は歩いて、走る。", "--plot", "fig5.png"), "plot"),
    (("db", "preview", "kick", "-o", "kick.png"), "plot"),
    (("db", "preview", str(REPO / "tests" / "data" / "walk_tiny.bvh"), "-o", "walk.png"), "plot"),
    (("batch", "{corpus}", "--out", "anims", "--jobs", "2"), "cluster"),
    (("batch", "{corpus}", "--out", "anims", "--scheduler", "tcp://127.0.0.1:1"), "cluster"),
    (("db", "list", "--db", "postgresql://nobody@127.0.0.1:1/none"), "postgres"),
    (("太郎は走る。", "-o", "a.bvh", "--db", "postgresql+psycopg2://nobody@127.0.0.1:1/none"), "postgres"),
]


@pytest.mark.parametrize("args, extra", NEEDS_AN_EXTRA, ids=[" ".join(a[:2]) + f" [{e}]" for a, e in NEEDS_AN_EXTRA])
def test_a_command_that_needs_an_extra_names_it(tmp_path, library_db, without_extras, args, extra):
    corpus = tmp_path.parent / f"{tmp_path.name}-corpus.txt"
    corpus.write_text("太郎は走る。\n太郎は歩く。\n", encoding="utf-8")
    args = tuple(a.format(corpus=corpus) for a in args)
    db = () if "--db" in args else ("--db", library_db)
    proc = text2anim(*args, *db, cwd=tmp_path, env=without_extras)
    assert_clean_error(proc, f"pip install 'text2anim[{extra}]'")
    lines = proc.stderr.strip().splitlines()
    assert [ln for ln in lines if ln.startswith("text2anim: error:")] == lines[-1:], proc.stderr
    if extra != "postgres":  # checked before any work (the database is the first thing opened anyway)
        assert len(lines) == 1, proc.stderr
    assert list(tmp_path.iterdir()) == []  # nothing written
