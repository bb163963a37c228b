"""Meridian: true north and the plumb line from instrument data (docs/python.md).

Submodules: meridian.gravity (models, ξ, η, N on numpy arrays), meridian.gyro
(gyro-theodolite reductions), meridian.maglev (maglev gyro: reduce, denoise,
calibrate, simulate), meridian.dov (deflection of the vertical along a line),
meridian.nav (marine navigation post-processing), meridian.angle (DMS parsing
and formatting), meridian.dask (chunked evaluation on a dask cluster; imported
on demand, as it needs dask). Errors: meridian.Error and its subclasses
(meridian.errors).
"""

from . import _core  # noqa: F401  (the compiled library)
from .errors import Error, InputError, IoError, NumericalError, ParseError
from . import angle, dov, errors, gravity, gyro, maglev, nav

__version__ = "0.1.0"
__all__ = ["Error", "InputError", "ParseError", "NumericalError", "IoError",
           "angle", "dov", "errors", "gravity", "gyro", "maglev", "nav"]
