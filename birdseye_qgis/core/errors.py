"""Errors raised for bad user input.

Every message names the file (or layer), and where it applies the row and the field, and says what
was expected, so the Processing log tells a user exactly what to fix.
"""
from __future__ import annotations


class InputError(ValueError):
    """Input a user can fix: a file, row or field that is not what was expected."""

    def __init__(self, message: str, *, source: str | None = None, row: int | None = None,
                 field: str | None = None):
        self.source, self.row, self.field = source, row, field
        where = []
        if source:
            where.append(str(source))
        if row is not None:
            where.append(f"row {row}")
        if field:
            where.append(f"field '{field}'")
        super().__init__(f"{', '.join(where)}: {message}" if where else message)


def detached(error: InputError) -> InputError:
    """``error`` kept for a report of bad input left out, without its traceback and chained exceptions: they
    hold the frames of the reader and of all its callers, and whatever those hold open (an algorithm's output
    file, which QGIS then cannot load), in a reference cycle with the error until the garbage collector runs."""
    error.__traceback__ = error.__context__ = error.__cause__ = None
    return error


class Cancelled(Exception):
    """Raised inside core loops when the caller's cancel callback returns True."""


def check_cancel(is_canceled) -> None:
    """Raise :class:`Cancelled` when the caller's cancel callback (None: never) says so; core loops call
    it once per unit of work."""
    if is_canceled is not None and is_canceled():
        raise Cancelled()
