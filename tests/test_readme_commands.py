"""The README's first screen is what a newcomer types, and ``.ci/run`` runs the same steps.

The first command must work on Debian's and Ubuntu's own Python, which refuses ``pip install`` outside a
virtual environment (PEP 668): it makes one and works in it. CI makes a fresh virtual environment the
same way and ends with the README's test command; this test fails when the two drift apart.
"""
from __future__ import annotations

import re
import shlex
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _first_screen() -> list[list[str]]:
    """The README's first ``sh`` block: each line's commands (split at ``&&``), each a list of words."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = re.search(r"```sh\n(.*?)```", text, re.S).group(1)
    return [[shlex.split(c) for c in line.split(" && ")] for line in block.strip().splitlines()]


def _ci_commands() -> list[list[str]]:
    """.ci/run's commands, one per line (comments and shell structure aside), each a list of words."""
    out = []
    for line in (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            try:
                out.append(shlex.split(line))
            except ValueError:  # a line of a multi-line command
                continue
    return out


def test_the_first_command_makes_and_uses_a_virtual_environment_as_ci_does():
    install, test = _first_screen()
    venv, activate, pip, run = install
    assert venv[:3] == ["python3", "-m", "venv"] and activate == [".", f"{venv[3]}/bin/activate"]
    assert pip == ["pip", "install", "."] and run[0] == "text2anim"
    ci = _ci_commands()
    made = next(c for c in ci if c[:3] == ["python3", "-m", "venv"])
    assert [".", f"{made[3]}/bin/activate"] in ci  # CI works in the environment it made, as the README does
    assert any(c[:4] == ["python", "-m", "pip", "install"] and c[-1].startswith(".[") for c in ci)
    assert test[0][:2] == ["pip", "install"] and test[0][2].startswith(".[test")


def test_ci_ends_with_the_readmes_test_command():
    _, test = _first_screen()
    command = test[-1]
    assert command == ["python", "-m", "pytest", "-q"]
    ci = _ci_commands()
    assert ci.index(command) > max(k for k, c in enumerate(ci) if c[:2] == ["python", "-m"] and c != command)
