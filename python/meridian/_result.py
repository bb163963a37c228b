"""Result objects shared by the modules of meridian (not a public module).

* Result: a JSON object (the CLI's ``--json`` output) with attribute access;
  nested objects are Results, arrays lists; to_dict() gives the plain data (a copy).
  Arrays that the JSON does not hold (a profile, tracks, series) may ride along
  as extra attributes; they are listed by dir() but are not part of to_dict().
* Table: columns of one length as numpy arrays (a profile, a track, a series),
  with attribute access; to_dict() gives {name: array copy}.
"""

import copy

import numpy as np

__all__ = ["Result", "Table"]


class Result:
    """A JSON object with attribute access: nested objects are Results, arrays lists.
    to_dict() returns the plain data (a copy)."""

    __slots__ = ("_data", "_extra")

    def __init__(self, data: dict, extra: dict = None):
        object.__setattr__(self, "_data", data)
        object.__setattr__(self, "_extra", dict(extra or {}))

    def __getattr__(self, name):
        extra = object.__getattribute__(self, "_extra")
        if name in extra:
            return extra[name]
        try:
            return _wrap(self._data[name])
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name, value):
        raise AttributeError("results are read-only")

    def __getitem__(self, key):
        return _wrap(self._data[key])

    def __dir__(self):
        return list(self._data) + list(self._extra)

    def keys(self):
        return self._data.keys()

    def to_dict(self) -> dict:
        return copy.deepcopy(self._data)

    def __reduce__(self):  # picklable (attributes cannot be set one by one)
        return (Result, (self._data, self._extra))

    def __repr__(self):
        return "Result(" + ", ".join(list(self._data) + list(self._extra)) + ")"


def _wrap(v):
    if isinstance(v, dict):
        return Result(v)
    if isinstance(v, list):
        return [_wrap(x) for x in v]
    return v


class Table:
    """Columns of one length as read-only numpy arrays, by attribute or by key."""

    __slots__ = ("_columns",)

    def __init__(self, columns: dict):
        cols = {}
        for name, value in columns.items():
            a = np.asarray(value)
            a.setflags(write=False)
            cols[name] = a
        object.__setattr__(self, "_columns", cols)

    def __getattr__(self, name):
        try:
            return object.__getattribute__(self, "_columns")[name]
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name, value):
        raise AttributeError("tables are read-only")

    def __getitem__(self, key):
        return self._columns[key]

    def __contains__(self, key):
        return key in self._columns

    def __dir__(self):
        return list(self._columns)

    def __len__(self):
        return len(next(iter(self._columns.values()))) if self._columns else 0

    def keys(self):
        return self._columns.keys()

    def to_dict(self) -> dict:
        return {k: v.copy() for k, v in self._columns.items()}

    def __reduce__(self):
        return (Table, (self._columns,))

    def __repr__(self):
        return f"Table({len(self)} rows: " + ", ".join(self._columns) + ")"


def real_array(name, value, ndim=1):
    """value as a C-contiguous float64 array of `ndim` dimensions; InputError naming
    the argument for another kind of data or shape (NaN is left to the engine, which
    names the element)."""
    from .errors import InputError

    a = np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise InputError(f"must be real numbers (integer or floating dtype), got dtype {a.dtype}", field=name)
    if a.ndim != ndim:
        raise InputError(f"must have {ndim} dimension{'s' if ndim != 1 else ''}, has shape {a.shape}", field=name)
    return np.ascontiguousarray(a, dtype=np.float64)


def degrees(name, value):
    """An angle in decimal degrees: a number, or a string in any notation of
    meridian.angle.parse_deg (DMS, gon, …)."""
    from . import angle
    from .errors import InputError

    if value is None:
        return None
    if isinstance(value, str):
        try:
            return angle.parse_deg(value)
        except InputError as e:
            e.field = name
            raise
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"must be an angle in degrees, got {value!r}", field=name) from None


def renamed(error, names):
    """Rename the engine's field of `error` (its C++ member or option, e.g. "latitude",
    "setups[2].mean1", "simulation.stations") to the Python argument it came from: `names`
    maps a field, or the part of it before "[" or ".", to the argument's name."""
    field = error.field or ""
    for engine, argument in names.items():
        if field == engine or field.startswith(engine + "[") or field.startswith(engine + "."):
            error.field = argument + field[len(engine):]
            return error
    return error
