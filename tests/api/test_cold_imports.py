"""What a cold process loads: the time table needs no synthesis, scipy, numpy or keyframe generator (it reads
clip metadata only); seeding a new database generates no keyframed clip (it reads the shipped arrays)."""
from __future__ import annotations

import json
import subprocess
import sys

TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"
HEAVY = ("text2anim.synthesis", "scipy", "matplotlib", "text2anim.motiondb.library",
         "numpy")  # ~0.1 s of a 0.3 s budget: frames and skeletons are decoded only when a clip is loaded
GENERATOR = ("text2anim.motiondb.library.keyframe_curves", "text2anim.motiondb.library.plant",
             "text2anim.motiondb.library.reach", "scipy")  # nor forward kinematics: the contacts are shipped


def _loaded(code: str, *args: str) -> list[str]:
    """The modules a fresh interpreter has loaded after running ``code`` (``sys.argv[1:]`` = ``args``)."""
    out = subprocess.run([sys.executable, "-c", code + "\nimport json, sys; print(json.dumps(sorted(sys.modules)))",
                          *args], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def test_a_time_table_loads_no_synthesis_scipy_numpy_or_library(library_db):
    code = "import sys, text2anim\nplanned = text2anim.plan(sys.argv[1], db=sys.argv[2])\nassert planned.table.elements"
    loaded = _loaded(code, TEXT, library_db)
    assert [m for m in loaded if m.startswith(HEAVY)] == []


def test_the_plan_command_loads_no_synthesis_scipy_numpy_or_library(library_db):
    code = ("import runpy, sys\nsys.argv = ['text2anim', 'plan', sys.argv[1], '--db', sys.argv[2]]\n"
            "try:\n    runpy.run_module('text2anim.cli.main', run_name='__main__')\n"
            "except SystemExit as exc:\n    assert not exc.code, exc.code")
    loaded = _loaded(code, TEXT, library_db)
    assert "text2anim.scheduler.table" in loaded  # it did make the time table
    assert [m for m in loaded if m.startswith(HEAVY)] == []


def test_seeding_a_new_database_runs_no_keyframe_generator_nor_scipy(tmp_path):
    code = ("import sys\nfrom text2anim.motiondb import MotionDB\n"
            "with MotionDB.open(sys.argv[1]) as db:\n    assert db.search('お辞儀する')")
    loaded = _loaded(code, str(tmp_path / "new.sqlite"))
    assert "text2anim.motiondb.library.keyframed" in loaded  # the built-in library was seeded from the arrays
    assert [m for m in loaded if m.startswith(GENERATOR)] == []
