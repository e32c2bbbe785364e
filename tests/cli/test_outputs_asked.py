"""Only the outputs asked for are written: ``animation.bvh`` only when nothing else is (README's ``--vrma``
example wrote an ``animation.bvh`` nobody asked for)."""
from __future__ import annotations

import argparse
import importlib.util
import itertools

import pytest

from cli_run import text2anim
from text2anim.cli import cmd_animate
from text2anim.core.extras import MissingExtraError

#: Every output option of ``text2anim TEXT`` and a file name for it.
OUTPUTS = {"-o": "walk.bvh", "--html": "walk.html", "--glb": "walk.glb", "--vrma": "walk.vrma",
           "--report": "walk.json", "--plot": "walk.png", "--top-view": "top.png"}


def _asked(tmp_path, flags) -> set[str]:
    parser = argparse.ArgumentParser()
    cmd_animate.add_arguments(parser)
    args = parser.parse_args(["太郎は歩く。", *itertools.chain.from_iterable(
        (f, str(tmp_path / OUTPUTS[f])) for f in flags)])
    return {str(v) for v in cmd_animate.check_outputs(args).values()}


@pytest.mark.parametrize("n", range(len(OUTPUTS) + 1))
def test_every_combination_of_output_options_asks_for_those_files_only(tmp_path, n):
    plots = importlib.util.find_spec("matplotlib") is not None
    for flags in itertools.combinations(OUTPUTS, n):
        if {"--plot", "--top-view"} & set(flags) and not plots:  # without the extra, refused before any work
            with pytest.raises(MissingExtraError):
                _asked(tmp_path, flags)
            continue
        expected = {str(tmp_path / OUTPUTS[f]) for f in flags} or {cmd_animate.DEFAULT_BVH}
        assert _asked(tmp_path, flags) == expected, flags


@pytest.mark.parametrize("args, written", [
    ((), ["animation.bvh"]),
    (("--vrma", "walk.vrma", "--glb", "walk.glb"), ["walk.glb", "walk.vrma"]),
    (("--html", "walk.html"), ["walk.html"]),
    (("--report", "walk.json", "-o", "walk.bvh"), ["walk.bvh", "walk.json"]),
    (("--top-view", "top.png"), ["top.png"]),
])
def test_the_command_writes_what_was_asked_for(tmp_path, library_db, args, written):
    proc = text2anim("太郎は歩く。", *args, "--db", library_db, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == written
