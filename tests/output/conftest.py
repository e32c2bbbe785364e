"""Fixtures of the output tests."""
from __future__ import annotations

import logging
import warnings

import pytest


@pytest.fixture
def strict(caplog):
    """No Python warnings and no matplotlib log warnings (missing glyphs, font fallbacks, fixed limits) while a
    figure is drawn."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with caplog.at_level(logging.WARNING, logger="matplotlib"):
            yield
    assert [r.getMessage() for r in caplog.records if r.name.startswith("matplotlib")] == []
