"""Entry point of the ``text2anim`` command.

Every sub-command lives in its own module ``cli/cmd_<name>.py`` exposing
``NAME``, ``HELP`` and ``add_arguments(parser)`` / ``run(args) -> int``.

Errors that are the user's to fix (bad input, a missing file, an unknown
verb) are exceptions whose class carries ``user_facing = True``; every stage
defines its own, so this module needs none of their internals. They are
printed as one line on stderr with exit code 2, never as a traceback.
"""
from __future__ import annotations

import argparse
import importlib
import sys

#: Sub-command modules, in the order ``--help`` lists them.
COMMAND_MODULES = [
    "text2anim.cli.cmd_animate",
    "text2anim.cli.cmd_compare",
    "text2anim.cli.cmd_info",
    "text2anim.cli.cmd_metrics",
    "text2anim.cli.cmd_convert",
    "text2anim.cli.cmd_db",
    "text2anim.cli.cmd_parse",
    "text2anim.cli.cmd_plan",
    "text2anim.cli.cmd_batch",
]

EXIT_USER_ERROR = 2
EXIT_INTERRUPTED = 130


def _load_commands():
    commands = {}
    for modname in COMMAND_MODULES:
        try:
            mod = importlib.import_module(modname)
        except ModuleNotFoundError as exc:  # a command still being written
            if exc.name == modname:
                continue
            raise
        commands[mod.NAME] = mod
    return commands


def build_parser(commands) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="text2anim",
        description="Turn Japanese text into character animation (BVH).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, mod in commands.items():
        p = sub.add_parser(name, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run)
    return parser


def _route_default(argv: list[str], commands) -> list[str]:
    """``text2anim "文"`` means ``text2anim animate "文"``."""
    if "animate" in commands and argv and argv[0] not in commands and argv[0] not in ("-h", "--help"):
        return ["animate", *argv]
    return argv


def is_user_error(exc: BaseException) -> bool:
    return bool(getattr(type(exc), "user_facing", False)) or isinstance(
        exc, (FileNotFoundError, PermissionError, IsADirectoryError, NotADirectoryError)
    )


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    commands = _load_commands()
    parser = build_parser(commands)
    args = parser.parse_args(_route_default(argv, commands))
    if not getattr(args, "_run", None):
        parser.print_help()
        return EXIT_USER_ERROR
    try:
        return int(args._run(args) or 0)
    except KeyboardInterrupt:
        print("text2anim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:  # noqa: BLE001 - the one place errors become messages
        if not is_user_error(exc):
            raise
        print(f"text2anim: error: {exc}", file=sys.stderr)
        return EXIT_USER_ERROR


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
