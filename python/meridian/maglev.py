"""Magnetically suspended gyro (docs/maglev-gyro.md): `meridian maglev` from Python.

* reduce(position1, position2, scale_A_s_per_rad=…, latitude_deg=…): a two-position
  determination from numpy arrays; reduce_files(file1[, file2], config=…): from the
  files the CLI reads. Both give a Result whose attributes are the keys of
  `meridian maglev reduce --json` (result.north_deg, result.alpha1_arcsec, …) and
  series1, series2: Tables of time_s, current_A, cleaned_A, kept per sample.
* denoise(series, wavelet="db4", level=None, mode, threshold, rule): a numpy array
  (pywt.wavedec → pywt.threshold → pywt.waverec for the universal rule).
* calibrate(table, latitude_deg=…): the multi-angle calibration, from a table file
  or arrays; the Result is `maglev calibrate --json` (the stored calibration).
* simulate(...), simulate_calibration(...): `maglev simulate` as arrays.

Angles in degrees (`_deg`, numbers or strings in any notation of meridian.angle)
or arc-seconds (`_arcsec`); currents in A, K in A·s/rad.

>>> from meridian import maglev
>>> p1, p2 = maglev.simulate(alpha1_deg=1.0, samples=2000, seed=3)
>>> r = maglev.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=35)   # doctest: +SKIP
"""

import json as _json
import os as _os

import numpy as _np

from . import _core
from ._result import (boolean as _boolean, number as _number, Result as _Result, Table as _Table,
                      degrees as _degrees, integer as _integer,
                      real_array as _real_array, renamed as _renamed)
from .errors import Error as _Error, InputError as _InputError

__all__ = ["reduce", "reduce_files", "denoise", "calibrate", "simulate", "simulate_calibration",
           "WAVELETS", "MODES", "THRESHOLDS", "RULES"]

WAVELETS = tuple(f"db{n}" for n in range(2, 11))
MODES = ("symmetric", "periodization")
THRESHOLDS = ("soft", "hard")
RULES = ("universal", "sure")


def _denoise_options(wavelet, level, mode, threshold, rule):
    if not isinstance(level, (int, _np.integer)) or isinstance(level, bool) or level < 0:
        raise _InputError(f"must be a positive integer (or None), got {level!r}", field="level")
    for name, value, accepted in [("wavelet", wavelet, WAVELETS), ("mode", mode, MODES),
                                  ("threshold", threshold, THRESHOLDS), ("rule", rule, RULES)]:
        if value not in accepted:
            raise _InputError(f"{value!r} is not one of {', '.join(accepted)}", field=name)
    return {"wavelet": str(wavelet), "level": int(level), "mode": str(mode), "threshold": str(threshold),
            "rule": str(rule)}


def _reduce_options(kw):
    o = {
        "scale_A_s_per_rad": None, "scale_sigma_A_s_per_rad": 0.0, "latitude_deg": None,
        "reading1_deg": None, "reading1_sigma_arcsec": 0.0, "prior_bias_A": None, "prior_bias_sigma_A": 0.0,
        "target_deg": None, "target_sigma_arcsec": 0.0, "instrument_constant_deg": 0.0,
        "instrument_constant_sigma_arcsec": 0.0, "eta_arcsec": None, "eta_sigma_arcsec": 0.0,
        "convergence_deg": 0.0, "process": True, "denoise": True, "segment": 0, "alpha": 0.05, "lags": 10,
        "drift": "linear",
    }
    denoising = {"wavelet": "db4", "level": 6, "mode": "symmetric", "threshold": "soft", "rule": "universal"}
    for key, value in kw.items():
        if key in denoising:
            denoising[key] = value
        elif key in o:
            o[key] = value
        else:
            raise TypeError(f"unexpected keyword argument {key!r}")
    for key in ("latitude_deg", "reading1_deg", "target_deg", "instrument_constant_deg"):
        o[key] = _degrees(key, o[key])
    for key in ("process", "denoise"):
        o[key] = _boolean(key, o[key])
    for key in _NUMBERS:
        o[key] = _number(key, o[key], optional=True)
    o["segment"] = _integer("segment", o["segment"], 0, 2**31 - 1)
    o["lags"] = _integer("lags", o["lags"], 1, 2**31 - 1)
    if o["segment"] != 0 and o["segment"] < 32:
        raise _InputError(f"{o['segment']} is not 0 (automatic) or at least 32", field="segment")
    if not 0.0 < o["alpha"] < 1.0:
        raise _InputError(f"{o['alpha']} is not in (0, 1)", field="alpha")
    if o["lags"] < 1:
        raise _InputError(f"{o['lags']} is not a positive number", field="lags")
    o.update(_denoise_options(**denoising))
    if o["level"] < 1:
        raise _InputError("must be at least 1", field="level")
    return o


# The options that are numbers (None: not given, where the option's default is None).
_NUMBERS = ("scale_A_s_per_rad", "scale_sigma_A_s_per_rad", "reading1_sigma_arcsec", "prior_bias_A",
            "prior_bias_sigma_A", "target_sigma_arcsec", "instrument_constant_sigma_arcsec", "eta_arcsec",
            "eta_sigma_arcsec", "convergence_deg", "alpha")

# The engine's names of the constants (maglev/model.hpp) as the keyword arguments call them.
_CONSTANTS = {"latitude": "latitude_deg", "scale": "scale_A_s_per_rad"}


def _series(name, value):
    """(time_s, current_A) of a position: a pair, a mapping or a Table with those keys."""
    if isinstance(value, _Table) or hasattr(value, "keys"):
        try:
            t, c = value["time_s"], value["current_A"]
        except KeyError:
            raise _InputError("needs time_s and current_A", field=name) from None
    else:
        try:
            t, c = value
        except (TypeError, ValueError):
            raise _InputError("must be (time_s, current_A) or a mapping with those keys", field=name) from None
    return _real_array(f"{name}.time_s", t), _real_array(f"{name}.current_A", c)


def _result(out):
    text, series1, series2 = out
    return _Result(_json.loads(text), {"series1": _Table(series1), "series2": _Table(series2)})


def reduce(position1, position2, **options) -> _Result:
    """Reduce one two-position determination (`maglev reduce --json`) from arrays.

    position1, position2: (time_s, current_A) pairs of 1-D arrays, or mappings/Tables
    with those keys (a simulate() result). Keyword options (the CLI's, with units):
    scale_A_s_per_rad (K, needed), scale_sigma_A_s_per_rad, latitude_deg (needed),
    reading1_deg, reading1_sigma_arcsec, prior_bias_A, prior_bias_sigma_A (symmetry
    check), target_deg, target_sigma_arcsec, instrument_constant_deg,
    instrument_constant_sigma_arcsec, eta_arcsec, eta_sigma_arcsec, convergence_deg
    (azimuth chain), process, denoise, segment, alpha, lags, drift ("linear", the
    common drift on the positions' clock fitted with the levels; "quadratic"; "none"),
    and the denoising's
    wavelet, level (6), mode, threshold, rule.
    Errors: InputError naming the argument and sample ("position1.time_s[17]")."""
    t1, c1 = _series("position1", position1)
    t2, c2 = _series("position2", position2)
    try:
        out = _core.maglev.reduce_arrays(t1, c1, t2, c2, _reduce_options(options))
    except _Error as e:
        raise _renamed(e, _CONSTANTS)
    return _result(out)


def reduce_files(file1, file2=None, *, config=None, calibration=None, **options) -> _Result:
    """`maglev reduce FILE [FILE2] --json`: one CSV with a position column, or one per
    position; config: the YAML/JSON constants (K, latitude, circle_reading1, …);
    calibration: a stored calibration (`maglev calibrate --json`); keyword options as
    reduce(), overriding the files. Errors name the file, line and column."""
    files = [_os.fspath(file1)] + ([_os.fspath(file2)] if file2 is not None else [])
    try:
        out = _core.maglev.reduce_files(files, _os.fspath(config) if config else "",
                                        _os.fspath(calibration) if calibration else "", _reduce_options(options))
    except _Error as e:
        raise _renamed(e, _CONSTANTS) if not e.file else e
    return _result(out)


def denoise(series, wavelet="db4", level=None, mode="symmetric", threshold="soft", rule="universal",
            full=False):
    """Wavelet-denoise a 1-D series (`maglev denoise`): a float64 array of its length.

    wavelet db2 … db10; level p ≥ 1 (None: 6, lowered to the deepest the series
    allows, as the CLI's default); mode "symmetric" | "periodization"; threshold
    "soft" | "hard"; rule "universal" (σ·sqrt(2 ln n)) | "sure". With the universal
    rule the result equals pywt.wavedec → pywt.threshold on every detail level →
    pywt.waverec, trimmed to n. full=True returns a Result with values and
    noise_sigma, thresholds (level 1 first), zeroed, coefficients, level.
    Errors: InputError (field "series", or the option) for an empty or non-finite
    series, a level too deep for its length, an unknown name."""
    x = _real_array("series", series)
    if level is not None and (not isinstance(level, (int, _np.integer)) or isinstance(level, bool) or level < 1):
        raise _InputError(f"must be a positive integer (or None), got {level!r}", field="level")
    o = _denoise_options(wavelet, 0 if level is None else level, mode, threshold, rule)
    values, sigma, thresholds, zeroed, coefficients, used = _core.maglev.denoise(x, o)
    if not full:
        return values
    info = {"noise_sigma": sigma, "thresholds": thresholds, "zeroed": zeroed, "coefficients": coefficients,
            "level": used, "wavelet": o["wavelet"], "mode": o["mode"], "threshold": o["threshold"],
            "rule": o["rule"]}
    return _Result(info, {"values": values})


_TABLE = ("azimuth_deg", "mean1_A", "sigma1_A", "mean2_A", "sigma2_A")


def calibrate(table, *, latitude_deg, alpha=0.05, nominal_scale_A_s_per_rad=None) -> _Result:
    """Multi-angle calibration (`maglev calibrate TABLE --json`): the exact model
    I_k = k_k·sin(α − α*) + I* fitted jointly (curves per position, model check `fit`),
    trend deviation, the instrument constant α* (`instrument_constant_arcsec`, also
    `best_azimuth_arcsec`), constant deviation I*, K from the slopes, `plausibility`
    (a unit slip against nominal_scale_A_s_per_rad). The table file's header units are
    applied (azimuth deg, dms, gon, rad, mrad; currents A, mA, uA).

    table: the CSV the CLI reads (path), or a mapping/Table with the arrays
    azimuth_deg, mean1_A, sigma1_A, mean2_A, sigma2_A (a simulate_calibration()
    result). The Result's to_dict() is also the stored calibration that
    reduce_files(calibration=…) reads, once written as JSON."""
    lat = _degrees("latitude_deg", latitude_deg)
    alpha = _number("alpha", alpha)
    if not 0.0 < alpha < 1.0:
        raise _InputError(f"{alpha} is not in (0, 1)", field="alpha")
    nominal = _number("nominal_scale_A_s_per_rad", nominal_scale_A_s_per_rad, optional=True)
    if isinstance(table, (str, _os.PathLike)):
        text = _core.maglev.calibrate_file(_os.fspath(table), lat, alpha, nominal)
    else:
        try:
            cols = [_real_array(k, table[k]) for k in _TABLE]
        except KeyError as e:
            raise _InputError(f"needs the columns {', '.join(_TABLE)}", field=f"table[{e.args[0]!r}]") from None
        try:
            text = _core.maglev.calibrate_arrays(*cols, lat, alpha, nominal)
        except _Error as e:
            raise _renamed(e, {"setups": "table", "latitude": "latitude_deg"})
    return _Result(_json.loads(text))


def _noise(samples, rate_hz, white_A, ar1_phi, ar1_sigma_A, drift_A_per_s):
    if not (isinstance(samples, (int, _np.integer)) and samples > 0):
        raise _InputError(f"must be a positive integer, got {samples!r}", field="samples")
    if not 0.0 < _number("rate_hz", rate_hz) < float("inf"):
        raise _InputError(f"must be > 0 (samples per second), is {rate_hz}", field="rate_hz")
    return {"samples": int(samples), "rate_hz": _number("rate_hz", rate_hz), "white_A": _number("white_A", white_A),
            "ar1_phi": _number("ar1_phi", ar1_phi), "ar1_sigma_A": _number("ar1_sigma_A", ar1_sigma_A),
            "drift_A_per_s": _number("drift_A_per_s", drift_A_per_s)}


def simulate(*, alpha1_deg=0.5, scale_A_s_per_rad=8000.0, bias_A=2e-4, latitude_deg=35.0, reading1_deg=0.0,
             samples=20000, rate_hz=100.0, white_A=1e-5, ar1_phi=0.0, ar1_sigma_A=0.0, drift_A_per_s=0.0,
             bursts=(), seed=1):
    """Simulate a determination (`maglev simulate`, same defaults and seed → same series):
    two Tables (time_s, current_A), position 2 starting 30 s after position 1 ends.
    bursts: (position, begin_s, end_s, amplitude_A, offset_A, f0_hz, f1_hz) tuples,
    times from the start of that position's series (the CLI's --burst)."""
    truth = {"alpha1_deg": _degrees("alpha1_deg", alpha1_deg),
             "scale_A_s_per_rad": _number("scale_A_s_per_rad", scale_A_s_per_rad),
             "bias_A": _number("bias_A", bias_A), "latitude_deg": _degrees("latitude_deg", latitude_deg),
             "reading1_deg": _degrees("reading1_deg", reading1_deg)}
    b = []
    for i, burst in enumerate(bursts):
        v = [_number(f"bursts[{i}]", x) for x in burst]
        if len(v) != 7 or v[0] not in (1.0, 2.0):
            raise _InputError("expected (position 1 or 2, begin_s, end_s, amplitude_A, offset_A, f0_hz, f1_hz)",
                             field=f"bursts[{i}]")
        b.append(v)
    p1, p2 = _core.maglev.simulate(truth, _noise(samples, rate_hz, white_A, ar1_phi, ar1_sigma_A, drift_A_per_s),
                                   b, _integer("seed", seed, 0, 2**64 - 1))
    return _Table(p1), _Table(p2)


def simulate_calibration(azimuths_deg, *, scale_A_s_per_rad=8000.0, latitude_deg=35.0, slope_ratio1=1.0,
                         slope_ratio2=1.0, best_azimuth_deg=0.0, constant_deviation_A=0.0, samples=20000,
                         rate_hz=100.0, white_A=1e-5, ar1_phi=0.0, ar1_sigma_A=0.0, drift_A_per_s=0.0, seed=1):
    """Simulate a calibration table (`maglev simulate --calibration-azimuths`): a Table of
    azimuth_deg, mean1_A, sigma1_A, mean2_A, sigma2_A for calibrate()."""
    az = _real_array("azimuths_deg", [_degrees("azimuths_deg", a) for a in azimuths_deg])
    truth = {"scale_A_s_per_rad": _number("scale_A_s_per_rad", scale_A_s_per_rad),
             "latitude_deg": _degrees("latitude_deg", latitude_deg),
             "slope_ratio1": _number("slope_ratio1", slope_ratio1),
             "slope_ratio2": _number("slope_ratio2", slope_ratio2),
             "best_azimuth_deg": _degrees("best_azimuth_deg", best_azimuth_deg),
             "constant_deviation_A": _number("constant_deviation_A", constant_deviation_A)}
    return _Table(_core.maglev.simulate_calibration(
        az, truth, _noise(samples, rate_hz, white_A, ar1_phi, ar1_sigma_A, drift_A_per_s),
        _integer("seed", seed, 0, 2**64 - 1)))
