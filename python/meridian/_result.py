"""Result objects shared by the modules of meridian (not a public module).

* Result: a read-only mapping (collections.abc.Mapping) of a JSON object (the CLI's
  ``--json`` output): ``key in r``, ``iter(r)``, ``len(r)``, ``keys()``, ``values()``,
  ``items()``, ``get()``, ``r[key]`` and ``r.key``; nested objects are Results, arrays
  lists; to_dict() gives the plain data (a copy). A key that is not a Python identifier
  is also an attribute under its identifier name (``"dead-reckoning"`` →
  ``dead_reckoning``; see identifier()). Arrays that the JSON does not hold (a profile,
  tracks, series) may ride along as extra attributes; they are listed by dir() but are
  neither keys of the mapping nor part of to_dict(). repr() shows the values.
* Table: columns of one length as read-only numpy arrays by attribute or key; like a
  pandas DataFrame, ``len(t)`` is the number of rows and iteration and ``in`` go over
  the column names; to_dict() gives {name: array copy}.
* Argument checks shared by the modules: real_array, degrees, integer, plain_data.
"""

import collections.abc as _abc
import copy as _copy
import datetime as _datetime
import keyword as _keyword
import os as _os
import re as _re

import numpy as _np

__all__ = ["Result", "Table"]

_MISSING = object()


def identifier(key: str) -> str:
    """The attribute name of a key: every character that cannot be in a Python identifier
    becomes "_" ("dead-reckoning" → "dead_reckoning"), a leading digit gets a "_" before
    it, a keyword a "_" after it ("from" → "from_"). Identifiers are their own name."""
    name = _re.sub(r"\W", "_", str(key))
    if not name or name[0].isdigit():
        name = "_" + name
    if _keyword.iskeyword(name):
        name += "_"
    return name


def _attribute(keys, name):
    """The key reached by attribute `name`: the key itself, or the one key whose
    identifier() is `name`; _MISSING when none (or two keys would share the name)."""
    if name in keys:
        return name
    found = [k for k in keys if isinstance(k, str) and identifier(k) == name]
    return found[0] if len(found) == 1 else _MISSING


def _attribute_names(keys):
    """The names by which the keys are attributes (for dir()): ambiguous ones left out."""
    names = [k if k.isidentifier() and not _keyword.iskeyword(k) else identifier(k) for k in keys]
    return [n for n in dict.fromkeys(names) if _attribute(keys, n) is not _MISSING]


# repr: every key at the top, at most this many keys (items) of a nested mapping (list), this
# many levels, this long a string.
_REPR_KEYS, _REPR_ITEMS, _REPR_DEPTH, _REPR_STRING = 8, 4, 3, 48


def _short(value, depth):
    if isinstance(value, (Result, dict)):
        if depth >= _REPR_DEPTH:
            return f"{{…{len(value)} keys}}"
        return _mapping_repr("Result", value.items(), len(value), depth + 1)
    if isinstance(value, (list, tuple)):
        parts = [_short(v, depth + 1) for v in value[:_REPR_ITEMS]]
        if len(value) > _REPR_ITEMS:
            parts.append(f"… {len(value) - _REPR_ITEMS} more")
        return "[" + ", ".join(parts) + "]"
    if isinstance(value, str) and len(value) > _REPR_STRING:
        return repr(value[:_REPR_STRING - 1] + "…")
    if isinstance(value, Table):
        return f"Table({len(value)} rows × {len(value._columns)} columns)"
    if isinstance(value, _np.ndarray):
        with _np.printoptions(threshold=6, edgeitems=2):
            return _np.array2string(value, separator=", ").replace("\n", "")
    return repr(value)


def _mapping_repr(kind, items, count, depth):
    parts = []
    for i, (k, v) in enumerate(items):
        if depth > 1 and i == _REPR_KEYS:
            parts.append(f"… {count - _REPR_KEYS} more")
            break
        name = k if isinstance(k, str) and k.isidentifier() else repr(k)
        parts.append(f"{name}={_short(v, depth)}" if name == k else f"{name}: {_short(v, depth)}")
    return kind + "(" + ", ".join(parts) + ")"


def _plain(value):
    """A deep copy with Results and Tables turned into dicts (of lists, numbers, arrays)."""
    if isinstance(value, Result):
        return _plain(object.__getattribute__(value, "_data"))
    if isinstance(value, Table):
        return value.to_dict()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return _copy.deepcopy(value)


class Result(_abc.Mapping):
    """A JSON object as a read-only mapping with attribute access: nested objects are
    Results, arrays lists. to_dict() returns the plain data (a copy). An attribute is
    looked up in the extra attributes, then among the keys (by identifier name), before
    the methods, so a key named like a method (``values``) is reached by attribute; the
    method then stays reachable as ``Result.values(r)``."""

    __slots__ = ("_data", "_extra")

    def __init__(self, data: dict, extra: dict = None):
        object.__setattr__(self, "_data", data)
        object.__setattr__(self, "_extra", dict(extra or {}))

    def __getattribute__(self, name):
        if not name.startswith("__"):
            extra = object.__getattribute__(self, "_extra")
            if name in extra:
                return extra[name]
            data = object.__getattribute__(self, "_data")
            key = _attribute(data, name)
            if key is not _MISSING:
                return _wrap(data[key])
        return object.__getattribute__(self, name)

    def __getattr__(self, name):  # neither a key, an extra nor a method
        raise AttributeError(f"no key or attribute {name!r} (keys: {', '.join(self.keys())})")

    def __setattr__(self, name, value):
        raise AttributeError("results are read-only")

    def __getitem__(self, key):
        return _wrap(object.__getattribute__(self, "_data")[key])

    def __iter__(self):
        return iter(object.__getattribute__(self, "_data"))

    def __len__(self):
        return len(object.__getattribute__(self, "_data"))

    def __contains__(self, key):
        return key in object.__getattribute__(self, "_data")

    def __dir__(self):
        return (_attribute_names(object.__getattribute__(self, "_data"))
                + list(object.__getattribute__(self, "_extra"))
                + ["get", "items", "keys", "to_dict", "values"])

    def to_dict(self) -> dict:
        return _plain(object.__getattribute__(self, "_data"))

    def __reduce__(self):  # picklable (attributes cannot be set one by one)
        return (Result, (object.__getattribute__(self, "_data"), object.__getattribute__(self, "_extra")))

    def __repr__(self):
        data = object.__getattribute__(self, "_data")
        extra = object.__getattribute__(self, "_extra")
        items = list(data.items()) + list(extra.items())
        return _mapping_repr("Result", items, len(items), 1)


def _wrap(v):
    if isinstance(v, dict):
        return Result(v)
    if isinstance(v, list):
        return [_wrap(x) for x in v]
    return v


class Table:
    """Columns of one length as read-only numpy arrays, by attribute or by key. len() is
    the number of rows; iteration, ``in`` and keys() go over the column names (as a pandas
    DataFrame's), so ``dict(table)`` is {name: array}."""

    __slots__ = ("_columns",)

    def __init__(self, columns):
        cols = {}
        for name, value in dict(columns).items():
            a = _np.asarray(value)
            a.setflags(write=False)
            cols[name] = a
        object.__setattr__(self, "_columns", cols)

    def __getattr__(self, name):
        cols = object.__getattribute__(self, "_columns")
        key = _attribute(cols, name)
        if key is _MISSING:
            raise AttributeError(f"no column {name!r} (columns: {', '.join(cols)})")
        return cols[key]

    def __setattr__(self, name, value):
        raise AttributeError("tables are read-only")

    def __getitem__(self, key):
        return self._columns[key]

    def __contains__(self, key):
        return key in self._columns

    def __iter__(self):
        return iter(self._columns)

    def __dir__(self):
        return _attribute_names(self._columns) + ["items", "keys", "to_dict", "values"]

    def __len__(self):
        return len(next(iter(self._columns.values()))) if self._columns else 0

    def keys(self):
        return self._columns.keys()

    def values(self):
        return self._columns.values()

    def items(self):
        return self._columns.items()

    def to_dict(self) -> dict:
        return {k: v.copy() for k, v in self._columns.items()}

    def __reduce__(self):
        return (Table, (self._columns,))

    def __repr__(self):
        cols = self._columns
        if not cols:
            return "Table(0 rows)"
        width = max(len(k) for k in cols)
        lines = [f"Table({len(self)} rows × {len(cols)} columns"]
        with _np.printoptions(threshold=6, edgeitems=3, linewidth=10**6):
            for k, v in cols.items():
                lines.append(f"  {k:<{width}}  " + _np.array2string(v, separator=", ").replace("\n", ""))
        return "\n".join(lines) + ")"


def real_array(name, value, ndim=1):
    """value as a C-contiguous float64 array of `ndim` dimensions; InputError naming
    the argument for another kind of data or shape (NaN is left to the engine, which
    names the element)."""
    from .errors import InputError

    a = _np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise InputError(f"must be real numbers (integer or floating dtype), got dtype {a.dtype}", field=name)
    if a.ndim != ndim:
        raise InputError(f"must have {ndim} dimension{'s' if ndim != 1 else ''}, has shape {a.shape}", field=name)
    return _np.ascontiguousarray(a, dtype=_np.float64)


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
        return number(name, value)
    except InputError:
        raise InputError(f"must be an angle in degrees (a number or text), got {value!r}", field=name) from None


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


def integer(name, value, low, high=None):
    """value as an int in [low, high] (high None: no upper bound): an int or a numpy integer,
    not a bool and not a float (2.9 is refused, not truncated to 2; so is 3.0). InputError
    naming the argument and the allowed range otherwise."""
    from .errors import InputError

    if isinstance(value, (bool, _np.bool_)) or not isinstance(value, (int, _np.integer)):
        within = f"in [{low}, {high}]" if high is not None else f"≥ {low}"
        raise InputError(f"must be an integer {within}, got {value!r}", field=name)
    v = int(value)
    if high is None and v < low:
        raise InputError(f"must be ≥ {low}, is {v}", field=name)
    if high is not None and not low <= v <= high:
        raise InputError(f"{v} is outside the allowed range [{low}, {high}]", field=name)
    return v


def number(name, value, optional=False):
    """value as a float: an int, a float or a numpy integer/floating scalar (or 0-d array), not
    a bool and not text (None when `optional` and value is None). InputError naming the
    argument otherwise, never Python's ValueError or pybind11's cast errors. Ranges are the
    engine's to check (it names them in the argument's units)."""
    from .errors import InputError

    if value is None and optional:
        return None
    v = value
    if isinstance(v, _np.ndarray) and v.ndim == 0:
        v = v[()]
    if isinstance(v, (bool, _np.bool_)) or not isinstance(v, (int, float, _np.integer, _np.floating)):
        raise InputError(f"must be a number, got {value!r}", field=name)
    return float(v)


def boolean(name, value):
    """value as a bool: True/False or a numpy bool, nothing else (the string "no" is not
    False). InputError naming the argument otherwise."""
    from .errors import InputError

    if not isinstance(value, (bool, _np.bool_)):
        raise InputError(f"must be True or False, got {value!r}", field=name)
    return bool(value)


def _json_value(value):
    """json.dump's default= for what YAML and numpy put in a dict: dates and times as ISO
    8601 text (as a YAML file books them), numpy scalars as numbers, arrays as lists, paths
    as text."""
    if isinstance(value, _datetime.datetime):
        return value.isoformat(sep=" ")
    if isinstance(value, (_datetime.date, _datetime.time)):
        return value.isoformat()
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, _np.ndarray):
        return value.tolist()
    if isinstance(value, _os.PathLike):
        return _os.fspath(value)
    if isinstance(value, (set, frozenset, tuple)):
        return list(value)
    raise TypeError(f"{type(value).__name__} {value!r}")


def write_json(source, f, what="<dict>"):
    """Write the mapping `source` as JSON text to the file `f` (for the library's readers):
    nested mappings and sequences, numbers (numpy's too), bools, None, text, dates
    (_json_value). InputError naming the key path for anything else, or a key that is not
    text."""
    import json

    from .errors import InputError

    def plain(v, path):
        if isinstance(v, _abc.Mapping):
            out = {}
            for k, x in v.items():
                if not isinstance(k, str):
                    raise InputError(f"keys must be text, got {k!r}", field=f"{path}" if path else None)
                out[k] = plain(x, f"{path}.{k}" if path else k)
            return out
        if isinstance(v, (list, tuple)) or (isinstance(v, _np.ndarray) and v.ndim > 0):
            return [plain(x, f"{path}[{i}]") for i, x in enumerate(list(v))]
        if v is None or isinstance(v, (str, bool, int, float)):
            return v
        try:
            return _json_value(v)
        except TypeError:
            raise InputError(f"cannot be given in {what}: {type(v).__name__} {v!r}", field=path or None) from None

    json.dump(plain(source, ""), f)


def run_on_mapping(run, source, prefix, paths=(), argument="source"):
    """run(path) on a file (a str or os.PathLike), or on a mapping written by write_json to a
    temporary file (removed afterwards). `paths`: the key paths ("dr", "nmea.heading") of
    the mapping that name files: relative ones are made absolute from the current directory
    first (the reader would take them from the temporary file's directory). Errors about the
    mapping name file "<dict>" (and the field) instead of the temporary file and its line.
    Returns (run's result, the temporary path or None)."""
    import tempfile

    from .errors import Error

    if not isinstance(source, _abc.Mapping):
        if not isinstance(source, (str, _os.PathLike)):
            from .errors import InputError
            raise InputError(f"must be a path or a dict, got {type(source).__name__}", field=argument)
        return run(_os.fspath(source)), None
    source = _absolute_paths(source, paths)
    fd, path = tempfile.mkstemp(suffix=".json", prefix=prefix)
    try:
        with _os.fdopen(fd, "w", encoding="utf-8") as f:
            write_json(source, f)
        try:
            return run(path), path
        except Error as e:
            if e.file == path:
                e.file, e.line = "<dict>", None
            raise
    finally:
        _os.unlink(path)


def _absolute_paths(source, paths):
    if not paths:
        return source
    out = dict(source)
    for key in paths:
        head, _, rest = key.partition(".")
        if head not in out:
            continue
        if rest:
            if isinstance(out[head], _abc.Mapping):
                out[head] = _absolute_paths(out[head], [rest])
        elif isinstance(out[head], (str, _os.PathLike)) and not _os.path.isabs(_os.fspath(out[head])):
            out[head] = _os.path.abspath(_os.fspath(out[head]))
    return out
