"""Marine navigation post-processing (docs/navigation.md): `meridian nav` from Python.

* process(config): the configuration (a path, or a dict with its content) and the
  files it names (DR/stations/LOP/fix CSVs, or NMEA 0183 logs in an ``nmea:`` block)
  as `meridian nav process CONFIG --json` runs them. The Result's attributes are the keys of the CLI's --json
  summary (epochs, method_order, methods[name].rms_m, rejected, …; to_dict() gives
  it; a mapping, ``"rts" in r.methods``, names that are not identifiers also as
  attributes: ``r.methods.dead_reckoning``), and ``tracks`` maps each method's name
  ("dead-reckoning", …, "ekf", "rts"; ``tracks.dead_reckoning``) to a Table named
  like the columns of `nav process -o TRACK --method NAME`:
  time_s, x_m (north), y_m (east), lat_deg, lon_deg (with a projection),
  sigma_x_m, sigma_y_m, cov_xy_m2, bias_north_m_s, bias_east_m_s,
  sigma_bias_north_m_s, sigma_bias_east_m_s (NaN where the method states no σ,
  as the JSON's null) and flags (1 LOP used, 2 LOP rejected, 4 fix combined,
  8 fix flagged).
* simulate(out, scenario="A", ...): the validation line of `meridian nav
  simulate --out DIR`, written to DIR with its nav.yaml.

>>> from meridian import nav
>>> sim = nav.simulate("/tmp/line", scenario="C")     # doctest: +SKIP
>>> r = nav.process(sim.config)                        # doctest: +SKIP
>>> r.methods["rts"].rms_m, r.tracks["rts"].x_m        # doctest: +SKIP
"""

import json as _json
import os as _os

from . import _core
from ._result import (Result as _Result, Table as _Table, boolean as _boolean, integer as _integer,
                      number as _number, renamed as _renamed, run_on_mapping as _run_on_mapping)
from .errors import Error as _Error, InputError as _InputError

__all__ = ["inspect", "process", "simulate", "METHODS", "SCENARIOS"]

#: The methods in the order of the result (fix-closure only with fixes).
METHODS = ("dead-reckoning", "sequential-no-bias", "sequential-bias-I", "sequential-bias-II", "backward",
           "fix-closure", "ekf", "rts")
SCENARIOS = ("A", "B", "C", "D")


def inspect(*files, accept_missing_checksum=False) -> _Result:
    """Inspect NMEA 0183 logs (`nav inspect FILE... --json`): per file the sentences by type,
    the bad, missing-checksum, duplicated and rolled-over ones with their first line numbers,
    and the time span. ``result.files[k]`` is the k-th file's summary. Every file is read
    before anything is returned: an unreadable one raises (meridian.Error naming it)."""
    if not files:
        raise _InputError("give at least one NMEA file", field="files")
    return _Result(_json.loads(_core.nav.inspect_files([_os.fspath(f) for f in files],
                                                     _boolean("accept_missing_checksum", accept_missing_checksum))))


#: The keys of a configuration that name files (relative ones, in a dict, are from the
#: current directory).
_PATH_KEYS = ("dr", "stations", "lops", "fixes", "truth", "nmea.heading", "nmea.speed", "nmea.positions")


def process(config) -> _Result:
    """Process a survey line (`nav process CONFIG --json`) and return every method's track.

    config: the path of a YAML/JSON configuration (its files relative to it), or a dict
    with the same content (e.g. yaml.safe_load of one; numpy numbers and arrays, dates and
    paths accepted), whose relative file names are taken from the current directory.
    ``tracks`` is a Result mapping each method's name to its Table (``tracks["rts"]``,
    ``tracks.dead_reckoning``). Errors name the file, line and column (or the
    configuration's key; for a dict the file "<dict>")."""
    (text, tracks), _ = _run_on_mapping(_core.nav.process_file, config, "meridian_nav_", _PATH_KEYS, "config")
    return _Result(_json.loads(text), {"tracks": _Result({name: _Table(cols) for name, cols in tracks})})


def simulate(out, scenario="A", *, seed=1, stations=3, duration_s=1800.0, fixes_every_s=0.0) -> _Result:
    """Simulate the validation line (`nav simulate --out DIR`, the same settings give the same
    files) into the directory `out` (created when missing). Returns a Result with config (the
    path of DIR/nav.yaml, ready for process()), files (the names written), blunders (indices
    of the LOPs with an injected blunder) and settings."""
    if str(scenario).upper() not in SCENARIOS:
        raise _InputError(f"{scenario!r} is not a scenario (A, B, C, D)", field="scenario")
    seed = _integer("seed", seed, 0, 2**64 - 1)
    stations = _integer("stations", stations, -2**31, 2**31 - 1)  # the simulator checks its range
    out = _os.fspath(out)
    try:
        files, blunders, settings = _core.nav.simulate(out, str(scenario), seed, stations,
                                                       _number("duration_s", duration_s),
                                                       _number("fixes_every_s", fixes_every_s))
    except _Error as e:
        raise _renamed(e, {"simulation.stations": "stations", "simulation.duration_s": "duration_s",
                          "simulation.fix_interval_s": "fixes_every_s"})
    return _Result({"config": _os.path.join(out, "nav.yaml"), "files": list(files), "blunders": list(blunders),
                   "settings": settings})
