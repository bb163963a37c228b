"""Angles as surveyors write them (include/meridian/core/dms.hpp), in decimal degrees.

>>> from meridian import angle
>>> angle.parse_deg("157°21'00\\"")
157.35
>>> angle.format_dms(-0.0045)
'-0°00\\'16.2"'
"""

from . import _core
from ._result import boolean as _boolean, integer as _integer, number as _number
from .errors import InputError as _InputError

__all__ = ["parse_deg", "format_dms", "format_direction_dms", "format_ddd_mmss", "UNITS"]

#: Units a field book may book its angles in (docs/file-formats.md `angle_unit:`).
UNITS = ("dms", "deg", "gon", "ddd.mmss")


def parse_deg(text: str, unit: str = "dms") -> float:
    """Decimal degrees of an angle written in `unit`: "dms" (the default) accepts
    157°21'00", 157d21m00s, 157:21:00, "157 21 00", 157.35, 174.8333g, 2.746 rad,
    93.6"; "deg", "gon" and "ddd.mmss" (calculator notation, 123.4530 = 123°45′30″)
    accept only their own notation. Raises ParseError naming the text otherwise
    (NaN, infinity, minutes or seconds ≥ 60, trailing text) and for an unknown unit."""
    if not isinstance(unit, str):
        raise _InputError(f"must be one of {', '.join(UNITS)}, got {unit!r}", field="unit")
    return _core.angle.parse_deg(str(text), unit)


def format_dms(deg: float, second_decimals: int = 1, symbols: bool = True, force_sign: bool = False) -> str:
    """Signed D°M'S" (or "D M S" without symbols), rounding carried into minutes and
    degrees; non-finite values give "nan"/"inf"."""
    return _core.angle.format_dms(_number("deg", deg), _integer("second_decimals", second_decimals, 0, 9),
                                  _boolean("symbols", symbols), _boolean("force_sign", force_sign))


def format_direction_dms(deg: float, second_decimals: int = 1, symbols: bool = True) -> str:
    """A direction normalised to [0°, 360°) as D°M'S"."""
    return _core.angle.format_direction_dms(_number("deg", deg), _integer("second_decimals", second_decimals, 0, 9),
                                            _boolean("symbols", symbols))


def format_ddd_mmss(deg: float, second_decimals: int = 1) -> str:
    """Calculator notation DDD.MMSS (123°45′30.5″ → "123.45305" with 1 decimal)."""
    return _core.angle.format_ddd_mmss(_number("deg", deg), _integer("second_decimals", second_decimals, 0, 6))
