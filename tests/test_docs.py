"""The documents that ``--help``, the docstrings and the README cite are in the repository, where they say."""
from __future__ import annotations

import argparse
import importlib
import re
from pathlib import Path

from text2anim.cli.main import COMMAND_MODULES, build_parser

REPO = Path(__file__).resolve().parents[1]
#: The specifications the code follows (docs/README.md), cited by file and section.
SPECS = ("language.md", "timetable.md", "unidic-notes.md")
#: The folders of the installed package, the tests and the benchmarks.
SOURCES = ("api", "cli", "core", "motiondb", "nlp", "scheduler", "synthesis", "tests", "benchmarks")


def _helps(parser: argparse.ArgumentParser):
    """``--help`` of ``parser`` and of every sub-command under it, as printed."""
    yield parser.prog, parser.format_help()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in dict.fromkeys(action.choices.values()):
                yield from _helps(sub)


def test_every_document_a_help_text_cites_exists():
    commands = {}
    for name in COMMAND_MODULES:
        mod = importlib.import_module(name)
        commands[mod.NAME] = mod
    cited = {}
    for prog, text in _helps(build_parser(commands)):
        for path in re.findall(r"[\w./-]+\.md\b", " ".join(text.split())):
            cited.setdefault(path, prog)
    assert {"docs/language.md", "docs/timetable.md"} <= set(cited), cited
    assert [(p, prog) for p, prog in cited.items() if not (REPO / p).is_file()] == []


def test_the_sources_cite_the_specifications_in_docs():
    pattern = re.compile(r"(?<![\w.-])([\w/.-]*?)(" + "|".join(map(re.escape, SPECS)) + r")")
    wrong = []
    for folder in SOURCES:
        for path in sorted((REPO / folder).rglob("*")):
            if path.suffix not in (".py", ".md") or "node_modules" in path.parts or path == Path(__file__):
                continue
            for m in pattern.finditer(path.read_text(encoding="utf-8")):
                if m.group(1) not in ("docs/", "../docs/"):
                    wrong.append(f"{path.relative_to(REPO)}: {m.group(0)}")
    assert wrong == []
    assert all((REPO / "docs" / name).is_file() for name in SPECS)


def test_the_readme_links_resolve():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    links = re.findall(r"\]\(([^)#\s]+)\)", readme)
    local = [link for link in links if "://" not in link]
    assert {f"docs/{name}" for name in SPECS} <= set(local)
    assert [link for link in local if not (REPO / link).exists()] == []


def test_the_readme_says_where_the_tests_capture_comes_from():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Real capture for the tests", 1)[-1].split("\n## ", 1)[0]
    asked = set()
    for folder in ("tests", "benchmarks"):
        for path in (REPO / folder).rglob("*.py"):
            asked |= set(re.findall(r"[\"'](\d{2,3}_\d{2}_[a-z]+)(?:\.bvh)?[\"']", path.read_text(encoding="utf-8")))
    assert len(asked) > 10
    assert sorted(stem for stem in asked if stem not in section) == []
    for folder in ("cmu/", "cmu_everyday/", "cmu_repro/"):
        assert f"`{folder}" in section
    acknowledgement = ("The data used in this project was obtained from mocap.cs.cmu.edu. The database was "
                       "created with funding from NSF EIA-0196217.")
    assert acknowledgement in " ".join(section.split())
