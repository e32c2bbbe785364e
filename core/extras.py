"""Optional dependencies (pip extras): one check and one message naming the extra to install.

A plain ``pip install text2anim`` animates text without any extra; figures need matplotlib
(``[plot]``), batches on several processes or a cluster need Dask (``[cluster]``), a PostgreSQL
database needs psycopg2 (``[postgres]``). What needs one calls :func:`require` before any work,
so a missing extra is one line naming it (``text2anim``: exit 2), never a traceback;
:func:`from_import_error` turns an import that failed anywhere else into the same message.
"""
from __future__ import annotations

import importlib
from types import ModuleType

#: The extra that installs each optional top-level module (``pyproject.toml``'s optional-dependencies).
EXTRAS = {"matplotlib": "plot", "dask": "cluster", "distributed": "cluster",
          "psycopg2": "postgres", "psycopg": "postgres"}


class MissingExtraError(ImportError, ValueError):
    """An optional dependency is not installed; the message names the extra that installs it.

    An :class:`ImportError`, and a :class:`ValueError` as every error of the project is."""

    user_facing = True


def install_command(module: str) -> str:
    """``pip install 'text2anim[plot]'`` for ``matplotlib`` (or any of its submodules)."""
    return f"pip install 'text2anim[{EXTRAS[module.split('.')[0]]}]'"


def missing(module: str, needed_by: str, detail: str = "") -> MissingExtraError:
    """The error for ``needed_by`` (``"db preview"``, ``"--plot"``) lacking the optional ``module``."""
    root = module.split(".")[0]
    why = f" ({detail})" if detail else ""
    return MissingExtraError(f"{needed_by} needs {root}, which is not installed{why}: {install_command(root)}",
                             name=root)


def require(module: str, needed_by: str) -> ModuleType:
    """``module`` imported, or :class:`MissingExtraError` saying which extra ``needed_by`` needs."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        root = module.split(".")[0]
        failed = (exc.name or "").split(".")[0]
        raise missing(root, needed_by, "" if failed in ("", root) else f"it cannot import {exc.name}") from None


def from_import_error(exc: ImportError, needed_by: str) -> MissingExtraError | None:
    """The same error for an optional module that failed to import elsewhere (``None``: not an extra's)."""
    name = exc.name or ""
    return missing(name, needed_by) if name.split(".")[0] in EXTRAS else None
