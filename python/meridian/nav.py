"""Marine navigation post-processing (docs/navigation.md): `meridian nav` from Python.

* process(config): the configuration and the files it names (DR/stations/LOP/fix
  CSVs, or NMEA 0183 logs in an ``nmea:`` block) as `meridian nav process CONFIG
  --json` runs them. The Result's attributes are the keys of the CLI's --json
  summary (epochs, method_order, methods[name].rms_m, rejected, …; to_dict() gives
  it), and ``tracks`` maps each method's name ("dead-reckoning", …, "ekf", "rts")
  to a Table named like the columns of `nav process -o TRACK --method NAME`:
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

import json
import os

from . import _core
from ._result import Result, Table, renamed
from .errors import Error, InputError

__all__ = ["inspect", "process", "simulate", "METHODS", "SCENARIOS"]

#: The methods in the order of the result (fix-closure only with fixes).
METHODS = ("dead-reckoning", "sequential-no-bias", "sequential-bias-I", "sequential-bias-II", "backward",
           "fix-closure", "ekf", "rts")
SCENARIOS = ("A", "B", "C", "D")


def inspect(*files, accept_missing_checksum=False) -> Result:
    """Inspect NMEA 0183 logs (`nav inspect FILE... --json`): per file the sentences by type,
    the bad, missing-checksum, duplicated and rolled-over ones with their first line numbers,
    and the time span. ``result.files[k]`` is the k-th file's summary. Every file is read
    before anything is returned: an unreadable one raises (meridian.Error naming it)."""
    if not files:
        raise InputError("give at least one NMEA file", field="files")
    return Result(json.loads(_core.nav.inspect_files([os.fspath(f) for f in files],
                                                     bool(accept_missing_checksum))))


def process(config) -> Result:
    """Process a survey line (`nav process CONFIG --json`) and return every method's track.
    Errors name the file, line and column (or the configuration's key)."""
    text, tracks = _core.nav.process_file(os.fspath(config))
    return Result(json.loads(text), {"tracks": {name: Table(cols) for name, cols in tracks}})


def simulate(out, scenario="A", *, seed=1, stations=3, duration_s=1800.0, fixes_every_s=0.0) -> Result:
    """Simulate the validation line (`nav simulate --out DIR`, the same settings give the same
    files) into the directory `out` (created when missing). Returns a Result with config (the
    path of DIR/nav.yaml, ready for process()), files (the names written), blunders (indices
    of the LOPs with an injected blunder) and settings."""
    if str(scenario).upper() not in SCENARIOS:
        raise InputError(f"{scenario!r} is not a scenario (A, B, C, D)", field="scenario")
    if int(seed) < 0:
        raise InputError(f"must be >= 0, is {seed}", field="seed")
    out = os.fspath(out)
    try:
        files, blunders, settings = _core.nav.simulate(out, str(scenario), int(seed), int(stations),
                                                       float(duration_s), float(fixes_every_s))
    except Error as e:
        raise renamed(e, {"simulation.stations": "stations", "simulation.duration_s": "duration_s",
                          "simulation.fix_interval_s": "fixes_every_s"})
    return Result({"config": os.path.join(out, "nav.yaml"), "files": list(files), "blunders": list(blunders),
                   "settings": settings})
