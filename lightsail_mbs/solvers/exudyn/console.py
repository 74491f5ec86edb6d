"""Exudyn prints to stdout by default; the commands print JSON there. One switch for every Exudyn call."""

from __future__ import annotations

from contextlib import contextmanager


@contextmanager
def silenced():
    """Turn Exudyn's console output off for the duration of the block (restored afterwards)."""
    import exudyn as exu

    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = printing
