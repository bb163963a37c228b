"""The meridian.Error hierarchy, mirroring C++'s meridian::Error (core/error.hpp).

Every error of the library reaches Python as one of these classes, with the
context the C++ error carries:

* ``message``: the message without context;
* ``file``: the input file it concerns, or None;
* ``line``: the 1-based line in that file, or None;
* ``field``: the dotted field path (``"determinations[2].crossings[0].times_s"``)
  or, for array arguments, the argument and index (``"lat_deg[3]"``), or None.

``str(e)`` is ``"file:line: field: message"`` with the unknown parts left out,
as the CLI prints it. ``InputError`` is also a ``ValueError`` and ``IoError``
an ``OSError``, so code that catches the built-in classes catches them too.
"""

__all__ = ["Error", "InputError", "ParseError", "NumericalError", "IoError"]


class Error(Exception):
    """Base of all errors raised by Meridian."""

    def __init__(self, message, file=None, line=None, field=None):
        self.message = message
        self.file = file
        self.line = line
        self.field = field
        super().__init__(message)

    def __str__(self):
        where = ""
        if self.file:
            where += self.file + (f":{self.line}" if self.line is not None else "") + ": "
        if self.field:
            where += self.field + ": "
        return where + self.message

    def __reduce__(self):  # picklable, so errors cross dask worker boundaries intact
        return (type(self), (self.message, self.file, self.line, self.field))


class InputError(Error, ValueError):
    """Invalid user input: a missing, contradictory or out-of-range value."""


class ParseError(InputError):
    """A file or string that cannot be parsed (syntax, truncation, bad number)."""


class NumericalError(Error, ArithmeticError):
    """A numerical failure (singular matrix, no convergence, a non-finite value)."""


class IoError(Error, OSError):
    """Operating-system level failure to read or write a file."""

    def __init__(self, message, file=None, line=None, field=None):
        Error.__init__(self, message, file, line, field)
        # OSError.__init__ would set args/errno from positional arguments; keep ours.
        self.args = (message,)
