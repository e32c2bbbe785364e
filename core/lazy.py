"""Names a package exports without importing their modules until first use (PEP 562)."""
from __future__ import annotations

import importlib
import sys
from collections.abc import Mapping
from typing import Any


def lazy_attribute(package: str, names: Mapping[str, str], name: str) -> Any:
    """The value of ``name`` for ``package``'s module ``__getattr__``: imported from the submodule
    ``names[name]`` and kept in the package (so it is looked up once); ``AttributeError`` otherwise."""
    if name not in names:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{package}.{names[name]}"), name)
    setattr(sys.modules[package], name, value)
    return value
