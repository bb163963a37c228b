"""Gyro-theodolite reductions: `meridian gyro reduce`, `gyro campaign` and `gyro stochastic`
from Python.

A determination file (docs/file-formats.md) or the same content as a dict is
read, checked and reduced by the library exactly as the CLI does; the result is
a Result whose attributes are the keys of the CLI's ``--json`` output (angles in
decimal degrees ``*_deg`` or arc-seconds ``*_arcsec``; a σ that cannot be stated
is None), and whose to_dict() gives that JSON as plain Python data.

>>> from meridian import gyro
>>> r = gyro.reduce("determination.yaml")            # doctest: +SKIP
>>> r.determinations[0].north_reading_deg            # doctest: +SKIP
"""

import json as _json

from . import _core
from ._result import Result, run_on_mapping as _run_on_mapping

__all__ = ["Result", "reduce", "campaign", "stochastic"]


def _run(run, source):
    """The JSON result of run(path) on a file, or on a mapping written as JSON to a temporary
    file (_result.run_on_mapping: errors name "<dict>"); the result's "file" is then "<dict>"
    too, not the temporary file's path."""
    text, path = _run_on_mapping(run, source, "meridian_gyro_")
    data = _json.loads(text)
    if path is not None and isinstance(data, dict) and data.get("file") == path:
        data["file"] = "<dict>"
    return data


def reduce(source) -> Result:
    """Reduce the determinations of one station (`meridian gyro reduce FILE --json`).

    source: a path to a YAML/JSON reduce file, or a dict with its content (instrument,
    station, determinations, optional angle_unit and options; docs/file-formats.md), as
    yaml.safe_load gives it or with numpy numbers and arrays, dates, paths in it (written
    as JSON for the reader; docs/python.md "Dicts"); the result's file is then "<dict>".
    Raises ParseError/InputError naming file (or "<dict>"), line and field."""
    return Result(_run(_core.gyro.reduce_file, source))


def campaign(source) -> Result:
    """Process a campaign (`meridian gyro campaign FILE --json`): a path or a dict.
    A gravity_model it names is looked up as by the CLI (relative paths from the
    file's directory; for a dict, from the current directory's view of a temporary
    file, so give absolute paths or names)."""
    return Result(_run(_core.gyro.campaign_file, source))


def stochastic(source) -> Result:
    """Compare the stochastic models of every reversal-point series of a field book
    (`meridian gyro stochastic FILE --json`; docs/gyro-stochastic.md): a path to a reduce or
    campaign file, or a dict with its content. ``result.series[k].models`` lists each model's
    north reading (or zero position), its σ, the ρ and variance components with their σ,
    log-likelihood, AIC and BIC; ``result.series[k].recommended`` names the recommended one.
    Series of fewer than 6 readings are not analysed; a file without any is an InputError."""
    return Result(_run(_core.gyro.stochastic_file, source))
