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
import gc
import importlib
import os
import sys

#: One OpenBLAS thread, set before numpy is first imported (this module imports none): every matrix of a
#: command is small (a join's IK rows, a region's hips), and OpenBLAS's pool of one thread a core only spun:
#: 0.26 s of CPU of a 0.75 s `TEXT -o x.bvh` on 2 cores, at its start, the same bytes. A caller's own
#: setting is kept. The Python API leaves its host process's threads as they are.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _large_blocks_given_back() -> None:
    """Have glibc's malloc map every block of 1 MB or more on its own, and unmap it when freed (``mallopt``'s
    ``M_MMAP_THRESHOLD``, which also stops the threshold rising). By default it rises to a freed block's size,
    up to 32 MB: a long text's frames, made and dropped join after join, then come from the heap, where what
    the process keeps (its kept joins) holds the freed space around it. The 32-motion text peaked at 681 MB
    so, 460 MB with the threshold held, and took 0.4 s less CPU. No-op without glibc."""
    try:
        import ctypes

        ctypes.CDLL(None).mallopt(-3, 1 << 20)  # M_MMAP_THRESHOLD (glibc's malloc.h)
    except (OSError, AttributeError):
        pass


_large_blocks_given_back()

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
    "text2anim.cli.cmd_studio",
]

#: Commands whose imports are frozen out of Python's cyclic garbage collector: one text, one animation,
#: bounded by :mod:`text2anim.limits` (32 motions). Their process imports ~1,000 modules and makes ~2 MB of
#: objects that live to the end; the collector traversed them over and over as they grew (~0.03-0.09 s of
#: CPU of a 0.3-1 s run). They are imported with the collector paused, then frozen (``gc.freeze``: never
#: traversed again) and the collector runs for the work itself: paused for the whole run, the cyclic garbage
#: of a long text's joins (motions and their poses) was never freed, 2.35 GB for 32 motions.
#: Other commands (batch, db import: unbounded work) collect as usual. A command module's ``LOADS`` names the
#: modules its every run imports (the API's stages): they load with the command, before the freeze. Imported
#: later, by the run, they were not frozen: the collector went over them ~20 times (0.02 s of `plan`, 0.06 s of
#: an animation's CPU).
PAUSED_GC = ("animate", "plan")

EXIT_USER_ERROR = 2
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell shows for a writer its reader left


def _name(modname: str) -> str:
    """The sub-command a module defines: ``text2anim.cli.cmd_plan`` -> ``plan`` (each module's ``NAME``)."""
    return modname.rsplit(".cmd_", 1)[1]


def _load_commands(argv: list[str] | None = None):
    """The sub-command modules by name: only the one ``argv`` runs when it names one (or is a text to
    animate), so a run imports no other command's dependencies; every module for ``--help`` and the rest."""
    names = [_name(m) for m in COMMAND_MODULES]
    wanted = COMMAND_MODULES
    if argv and argv[0] not in TOP_LEVEL_OPTIONS:
        first = argv[0] if argv[0] in names else "animate"
        wanted = [m for m in COMMAND_MODULES if _name(m) == first]
    commands = {}
    for modname in wanted:
        try:
            mod = importlib.import_module(modname)
        except ModuleNotFoundError as exc:  # a command still being written
            if exc.name == modname:
                continue
            raise
        assert mod.NAME == _name(modname), modname
        commands[mod.NAME] = mod
    return commands


class _Parser(argparse.ArgumentParser):
    """argparse whose "unrecognized arguments" error names the closest valid option (difflib)."""

    def error(self, message: str):  # noqa: D401 - argparse's hook
        from text2anim.limits import printable

        if message.startswith("unrecognized arguments:"):
            message += _suggestion(self, message.split(":", 1)[1].split())
        super().error(printable(message))


def _suggestion(parser: argparse.ArgumentParser, unknown: list[str]) -> str:
    """``"; did you mean --fps?"`` for the first unknown option that is close to a valid one."""
    import difflib

    options = [s for a in parser._actions for s in a.option_strings if s.startswith("--")]
    for word in unknown:
        if not word.startswith("--"):
            continue
        close = difflib.get_close_matches(word.split("=", 1)[0], options, n=1, cutoff=0.6)
        if close:
            return f"; did you mean {close[0]}?"
    return ""


def build_parser(commands) -> argparse.ArgumentParser:
    from text2anim import __version__

    parser = _Parser(
        prog="text2anim",
        description="Turn Japanese text into character animation (BVH).",
    )
    parser.add_argument("--version", action="version", version=f"text2anim {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, mod in commands.items():
        p = sub.add_parser(name, help=mod.HELP, description=mod.HELP)
        mod.add_arguments(p)
        p.set_defaults(_run=mod.run)
    return parser


def _parse(parser: argparse.ArgumentParser, argv: list[str]) -> argparse.Namespace:
    """``parse_args``, but an unknown option is reported by the sub-command's parser, with a suggestion."""
    args, extra = parser.parse_known_args(argv)
    if extra:
        sub = _subparser(parser, getattr(args, "command", None)) or parser
        sub.error("unrecognized arguments: " + " ".join(extra))
    return args


def _subparser(parser: argparse.ArgumentParser, name: str | None):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) and name in action.choices:
            return action.choices[name]
    return None


TOP_LEVEL_OPTIONS = ("-h", "--help", "--version")


def _route_default(argv: list[str], commands) -> list[str]:
    """``text2anim "文"`` means ``text2anim animate "文"``."""
    if "animate" in commands and argv and argv[0] not in commands and argv[0] not in TOP_LEVEL_OPTIONS:
        return ["animate", *argv]
    return argv


def is_user_error(exc: BaseException) -> bool:
    return bool(getattr(type(exc), "user_facing", False)) or isinstance(
        exc, (FileNotFoundError, PermissionError, IsADirectoryError, NotADirectoryError)
    )


def _missing_extra(exc: Exception, command: str) -> Exception | None:
    """An optional dependency that a check missed, as the message every check gives (:mod:`core.extras`)."""
    if not isinstance(exc, ImportError):
        return None
    from text2anim.core.extras import from_import_error

    return from_import_error(exc, f"text2anim {command}")


def _quiet_broken_pipe() -> int:
    """The reader went away (``text2anim info big.bvh | head -2``): stop without a word.

    Standard output is pointed at /dev/null so that Python's flush at exit does
    not raise again (the recipe of the ``signal`` module's documentation).
    """
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass
    return EXIT_BROKEN_PIPE


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    collecting = gc.isenabled()
    gc.disable()  # the imports below: see PAUSED_GC
    frozen = False
    try:
        commands = _load_commands(argv)
        if collecting and len(commands) == 1 and next(iter(commands)) in PAUSED_GC:
            for name in getattr(next(iter(commands.values())), "LOADS", ()):
                importlib.import_module(name)
            gc.freeze()
            frozen = True
        if collecting:
            gc.enable()
        return _main(argv, commands)
    finally:
        if frozen:
            gc.unfreeze()
        if collecting:
            gc.enable()


def command() -> int:
    """The ``text2anim`` program: :func:`main` of the process's own arguments, for a process that ends with it.

    The collector is frozen once the command is done: the interpreter's end ran the cyclic collector several
    times over every object the command left (50,000-80,000, 15-35 ms a pass), 0.06-0.08 s of `plan`'s 0.3 s
    CPU and 0.14-0.17 s of an animation's 1 s, to free what the process's exit frees anyway. Frozen, those
    last passes skip them; the atexit handlers (the databases closed) and the flush of standard output run
    as before. A program calling :func:`main` keeps its collector as it was.
    """
    status = main()
    gc.freeze()
    return status


def _main(argv: list[str], commands: dict) -> int:
    parser = build_parser(commands)
    args = _parse(parser, _route_default(argv, commands))
    if not getattr(args, "_run", None):
        parser.print_help()
        return EXIT_USER_ERROR
    try:
        status = int(args._run(args) or 0)
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        return _quiet_broken_pipe()
    except KeyboardInterrupt:
        print("text2anim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:  # noqa: BLE001 - the one place errors become messages
        if not is_user_error(exc):
            exc = _missing_extra(exc, args.command) or exc
        if not is_user_error(exc):
            raise
        from .terminal import message

        print(f"text2anim: error: {message(str(exc))}", file=sys.stderr)
        return EXIT_USER_ERROR


if __name__ == "__main__":  # pragma: no cover
    sys.exit(command())
