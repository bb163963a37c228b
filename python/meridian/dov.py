"""Dynamic deflection of the vertical (docs/deflection.md): `meridian dov` from Python.

* process(config): the configuration and its line (CSV or binary) as
  `meridian dov process CONFIG --json -o profile.csv` runs them.
* process(line, **options): a line given as arrays (a simulate() result, or a
  mapping of the arrays below) with the configuration's options as keywords.
* simulate(...): `meridian dov simulate` as arrays.

The Result's attributes are the keys of the CLI's --json summary (epochs,
rms_arcsec, mean_sigma_arcsec, nis, eps_u_deg_per_h, …; to_dict() gives it), and
``profile`` is a Table of one row per epoch named like the columns of the CLI's
profile CSV: time_s, lat_deg, lon_deg, model_eta_arcsec, model_xi_arcsec,
filtered_eta_arcsec, filtered_xi_arcsec, filtered_sigma_eta_arcsec,
filtered_sigma_xi_arcsec, smoothed_eta_arcsec, smoothed_xi_arcsec,
smoothed_sigma_eta_arcsec, smoothed_sigma_xi_arcsec, filtered_eps_u_deg_per_h,
innovation_east_arcsec, innovation_north_arcsec, nis, accepted (1.0/0.0) and,
for a line with truth, truth_eta_arcsec, truth_xi_arcsec. Signs as
geodesy/frames.hpp: ξ positive when the plumb line points north of the normal,
η positive east.

A line as arrays (n samples): time_s, lat_deg, lon_deg, height_m, speed_m_s,
lgu_body_to_nav and ins_body_to_nav (n, 3, 3) rotation matrices C_b^n and
C_b^n′ (rows E, N, U), model_eta_arcsec, model_xi_arcsec, and optionally
truth_eta_arcsec, truth_xi_arcsec.

>>> from meridian import dov
>>> line = dov.simulate(hours=0.1, seed=2)
>>> r = dov.process(line, sigma_model_arcsec=3)      # doctest: +SKIP
>>> r.profile.smoothed_xi_arcsec                      # doctest: +SKIP
"""

import json as _json
import re as _re
import os as _os
import tempfile as _tempfile
import warnings as _warnings

from . import _core
from ._result import (number as _number, Result as _Result, Table as _Table, degrees as _degrees,
                      real_array as _real_array,
                      integer as _integer, write_json as _write_json)
from .errors import Error as _Error, InputError as _InputError

__all__ = ["process", "read_line", "simulate", "LINE_COLUMNS"]

#: The arrays of a line (the truth columns are optional).
LINE_COLUMNS = ("time_s", "lat_deg", "lon_deg", "height_m", "speed_m_s", "lgu_body_to_nav", "ins_body_to_nav",
                "model_eta_arcsec", "model_xi_arcsec", "truth_eta_arcsec", "truth_xi_arcsec")


def _result(out):
    text, profile = out
    return _Result(_json.loads(text), {"profile": _Table(profile)})


def _line(line):
    cols = {}
    for name in LINE_COLUMNS:
        try:
            value = line[name]
        except (KeyError, TypeError):
            if name.startswith("truth_"):
                continue
            raise _InputError(f"the line needs the array {name}", field=name) from None
        ndim = 3 if name.endswith("_body_to_nav") else 1
        cols[name] = _real_array(name, value, ndim)
    if ("truth_eta_arcsec" in cols) != ("truth_xi_arcsec" in cols):
        raise _InputError("give both truth_eta_arcsec and truth_xi_arcsec, or neither", field="truth_eta_arcsec")
    return cols


_LATITUDE_IN_RADIANS = _re.compile(r"latitude \S+ rad is beyond ±π/2")


def _in_degrees(error, cols):
    """The engine's check of a sample's latitude speaks radians (dov/deflection.hpp works in
    them); a line given in lat_deg hears it in degrees, as a line file's reader says it."""
    field = error.field or ""
    if field.startswith("lat_deg[") and _LATITUDE_IN_RADIANS.fullmatch(error.message or ""):
        value = cols["lat_deg"][int(field[len("lat_deg["):-1])]
        error.message = f"latitude {value:.15g}° is beyond ±90°"
        error.args = (error.message,)


def process(source, **options) -> _Result:
    """Filter and smooth a line (`dov process --json`), from a configuration file or arrays.

    source: the path of a YAML/JSON configuration (its line file, CSV or binary,
    relative to it; a gravity_model it names is looked up as by the CLI) — or a
    line as arrays (see the module comment). With arrays, the options are keyword
    arguments with the configuration's keys (zeta, sigma_model_arcsec,
    correlation_length_m, stationary_speed_m_s, sigma_obs_arcsec or
    sigma_obs_east_arcsec/sigma_obs_north_arcsec, initial={…}, discretisation,
    extraction, max_step_s, gate_alpha, statistics_start_s, transport_rate,
    transport_rate_baseline_s, speed_sigma_m_s, stationary_sigma_factor,
    stationary_min_duration_s, whiteness_alpha).
    Errors: the file, line and column for files; for arrays the array and element
    ("lat_deg[3]"), or "<options>" and the key."""
    if isinstance(source, (str, _os.PathLike)):
        if options:
            raise TypeError("options are the configuration's keys: give them with a line of arrays")
        return _result(_core.dov.process_file(_os.fspath(source)))
    cols = _line(source)
    if "line" in options or "gravity_model" in options:
        raise _InputError("not an option of a line given as arrays", field="line" if "line" in options else
                         "gravity_model")
    fd, path = _tempfile.mkstemp(suffix=".json", prefix="meridian_dov_")
    try:
        with _os.fdopen(fd, "w", encoding="utf-8") as f:
            _write_json({"line": "<arrays>", **options}, f, "<options>")
        try:  # an error about a sample names its array and element ("lat_deg[3]"): the runner's
            return _result(_core.dov.process_arrays(cols, path))
        except _Error as e:
            if e.file == path:
                e.file, e.line = "<options>", None
            _in_degrees(e, cols)
            raise
    finally:
        _os.unlink(path)


def read_line(path) -> _Table:
    """A line file, CSV or the binary format (told apart by content, as `dov process` does),
    read whole into the arrays simulate() gives (and process() takes): the model columns only
    when the file has them, the truth columns only when it has them. Errors name the file,
    line (CSV) or sample index (binary) and column, as the CLI's."""
    columns, ignored = _core.dov.read_line(_os.fspath(path))
    if ignored:  # as the CLI warns: a misspelt optional column would otherwise vanish
        _warnings.warn(f"{_os.fspath(path)}: column{'s' if len(ignored) > 1 else ''} {', '.join(ignored)} "
                      f"not used (a misspelt optional column such as model_eta_arcsec or truth_eta_arcsec "
                      f"is not read; docs/file-formats.md lists the names)", stacklevel=2)
    return _Table(columns)


def simulate(*, latitude_deg=30.0, longitude_deg=114.0, heading_deg=60.0, height_m=0.0, speed_m_s=5.0,
             rate_hz=1.0, hours=4.0, sigma_model_arcsec=3.0, sigma_ins_arcsec=0.5, eps_u_deg_per_h=0.003,
             phi_e_arcsec=0.0, phi_n_arcsec=0.0, phi_u_arcsec=0.0, seed=1, transport_rate=False) -> _Table:
    """Simulate a line (`meridian dov simulate`, the same defaults; the same seed gives the
    same line): a Table of the line's arrays, with truth. Angles in degrees (numbers or
    any notation of meridian.angle) and arc-seconds. transport_rate=True: the true attitude
    error also turns with the transport rate (`--transport-rate`; process it with
    transport_rate=True)."""
    o = {"latitude_deg": _degrees("latitude_deg", latitude_deg),
         "longitude_deg": _degrees("longitude_deg", longitude_deg),
         "heading_deg": _degrees("heading_deg", heading_deg)}
    for key, value in [("height_m", height_m), ("speed_m_s", speed_m_s), ("rate_hz", rate_hz), ("hours", hours),
                       ("sigma_model_arcsec", sigma_model_arcsec), ("sigma_ins_arcsec", sigma_ins_arcsec),
                       ("eps_u_deg_per_h", eps_u_deg_per_h), ("phi_e_arcsec", phi_e_arcsec),
                       ("phi_n_arcsec", phi_n_arcsec), ("phi_u_arcsec", phi_u_arcsec)]:
        o[key] = _number(key, value)
    o["seed"] = _integer("seed", seed, 0, 2**64 - 1)
    if not isinstance(transport_rate, bool):
        raise _InputError(f"must be True or False, is {transport_rate!r}", field="transport_rate")
    o["transport_rate"] = bool(transport_rate)
    # The simulator's own checks name its members in radians; say it in these arguments' terms.
    if not abs(o["latitude_deg"]) < 89.0:
        raise _InputError(f"must be strictly between -89° and 89°, is {o['latitude_deg']:.6g}°",
                         field="latitude_deg")
    if not o["rate_hz"] > 0.0 or o["rate_hz"] == float("inf"):
        raise _InputError(f"must be > 0 (samples per second), is {o['rate_hz']}", field="rate_hz")
    if not o["hours"] * 3600.0 * o["rate_hz"] >= 1.0:
        raise _InputError(f"{o['hours']} h at {o['rate_hz']} Hz gives less than one step", field="hours")
    try:
        return _Table(_core.dov.simulate(o))
    except _InputError as e:
        if e.field == "simulation.duration_s":
            e.field = "hours"
            e.message = f"the track leaves ±89° of latitude within {o['hours']} h ({e.message})"
        raise
