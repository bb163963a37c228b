"""Gravity models: the deflection of the vertical and the geoid on numpy arrays.

>>> import meridian.gravity as mg
>>> model = mg.synthetic_model(degree=60, seed=3)
>>> d = model.deflection([-33.5, 47.3], [151.25, 8.5], 120.0)
>>> d.xi_arcsec.shape
(2,)

Definitions, frames and sign conventions are the C++ engine's
(include/meridian/gravity/gravity_field.hpp, docs/gravity-field.md), identical
to GeographicLib's GravityModel: ξ = −(1/γ)(1/r)∂T/∂ψ (north–south, positive
when the plumb line points north of the ellipsoid normal), η = −(1/γ)(1/(r cos
ψ))∂T/∂λ (east–west, positive east), N by Bruns' formula at h = 0 (plus the
model's zeta-to-N correction), in arc-seconds and metres. Coordinates are
geodetic on the model's reference ellipsoid (WGS84 for the EGMs): latitude in
[−90, 90] degrees, longitude east positive (any finite value), height above the
ellipsoid in [−12 000, 10 000 000] m.
"""

from typing import NamedTuple as _NamedTuple, Optional as _Optional

import numpy as _np

from . import _core
from ._result import boolean as _boolean, integer as _integer
from .errors import InputError as _InputError

__all__ = ["GravityModel", "Deflection", "synthetic_model", "search_path"]


class Deflection(_NamedTuple):
    """What GravityModel.deflection returns: float64 arrays of the broadcast shape
    of the inputs (numpy float64 scalars for scalar inputs)."""

    xi_arcsec: _np.ndarray   #: north–south deflection ξ (″)
    eta_arcsec: _np.ndarray  #: east–west deflection η (″)
    geoid_m: _Optional[_np.ndarray]  #: geoid height N (m) at (lat, lon); None when geoid=False


def _real_array(name, value):
    """value as a float64 array; InputError (field = name) for any other kind of data."""
    a = _np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise _InputError(
            f"must be real numbers (integer or floating dtype), got dtype {a.dtype}", field=name
        )
    return a.astype(_np.float64, copy=False)


def _own_index(flat, shape, own_shape):
    """The index into an argument of shape own_shape of element `flat` of the broadcast."""
    full = _np.unravel_index(flat, shape) if shape else ()
    full = full[len(full) - len(own_shape):] if own_shape else ()
    return tuple(0 if n == 1 else int(i) for i, n in zip(full, own_shape))


def _relocate(err, names, shapes, shape):
    """Turn the engine's flat index in err.field ("lat_deg[12]") into the argument's own index."""
    field = err.field or ""
    for name, own in zip(names, shapes):
        if field.startswith(name + "["):
            flat = int(field[len(name) + 1 : -1])
            idx = _own_index(flat, shape, own)
            err.field = name + ("[" + ", ".join(map(str, idx)) + "]" if idx else "")
            return
    if field.startswith("points["):
        flat = int(field[len("points[") : -1])
        err.field = "points[" + ", ".join(map(str, _np.unravel_index(flat, shape) if shape else ())) + "]"


class GravityModel:
    """A spherical-harmonic gravity model ready to evaluate (immutable; thread-safe).

    Open one with GravityModel.open(path_or_name) or synthetic_model(degree, seed).
    Pickling a model pickles how to open it (file and degree, or degree and seed),
    so a dask worker opens it again rather than receiving the coefficients.
    """

    #: Threads a batch may use (0: one per core).
    MAX_THREADS = 1024

    def __init__(self, core, recipe):
        self._core = core
        self._recipe = recipe

    @classmethod
    def open(cls, path_or_name, *, max_degree=None, threads=0):
        """Load a model: a `.gfc` (ICGEM) or `.egm` (GeographicLib) file, or a name such
        as ``"egm96"`` looked up as NAME.egm / NAME.gfc in search_path().

        max_degree: truncate while reading, an integer in [0, the file's degree] (None: the
        file's degree); a float (2.9) or a degree above the file's is refused with an
        InputError (field "max_degree") naming the allowed range, where the CLI's
        --max-degree takes the file's degree.
        threads: threads of each batch evaluation, an integer in [0, 1024] (0: one per core).
        Raises InputError (not found: the message lists the directories searched; field
        "max_degree" or "threads" for a bad argument), ParseError (bad file, with file and
        line) or IoError.
        """
        path_or_name = str(path_or_name)
        if max_degree is not None and (isinstance(max_degree, (bool, _np.bool_))
                                       or not isinstance(max_degree, (int, _np.integer))):
            raise _InputError(f"must be an integer in [0, the file's degree] (or None: the file's degree), "
                              f"got {max_degree!r}", field="max_degree")
        md = -1 if max_degree is None else _integer("max_degree", max_degree, 0)
        threads = _integer("threads", threads, 0, cls.MAX_THREADS)
        try:
            core = _core.gravity.open(path_or_name, md, threads)
        except _InputError as e:
            if e.field == "--model":  # the lookup names the CLI's option
                e.field = "path_or_name"
            raise
        file_degree = core.info["file_max_degree"]
        if md > file_degree:
            raise _InputError(f"{md} is outside the allowed range [0, {file_degree}] (the degree of "
                              f"{core.info['name']!r})", field="max_degree")
        return cls(core, ("open", path_or_name, md, threads))

    @property
    def name(self) -> str:
        return self._core.info["name"]

    @property
    def max_degree(self) -> int:
        """The degree evaluated (after any truncation)."""
        return self._core.max_degree

    @property
    def info(self) -> dict:
        """What the file states: name, source_file, max_degree, file_max_degree,
        gm_m3_s2, radius_m, tide_system, normalization, description."""
        return self._core.info

    @property
    def warnings(self) -> list:
        """Warnings about the metadata (e.g. a tide system the file does not state)."""
        return self._core.warnings

    def __repr__(self):
        return f"<meridian.gravity.GravityModel {self.name!r} degree {self.max_degree}>"

    def __reduce__(self):
        return (_reopen, (self._recipe,))

    def deflection(self, lat_deg, lon_deg, h_m=0.0, *, geoid=True) -> Deflection:
        """ξ, η (″) and N (m) at points given by arrays of any broadcast-compatible shapes
        (numpy rules; scalars, lists and integer arrays are accepted).

        lat_deg: geodetic latitude (°), [−90, 90]; lon_deg: longitude (°), east positive;
        h_m: ellipsoidal height (m), [−12 000, 10⁷]. geoid=False skips N (about half the
        cost when h ≠ 0) and returns geoid_m=None.

        The points are evaluated in vectorised multi-threaded batches with the GIL
        released. Raises InputError with field naming the argument and the element
        (``"lat_deg[2, 0]"``) for NaN, infinite or out-of-range values, with field
        ``"lat_deg"`` etc. for a non-numeric dtype, and with field
        ``"lat_deg, lon_deg, h_m"`` when the shapes do not broadcast; NumericalError
        (field ``"points[i]"``) if the model gives a non-finite value.
        """
        names = ("lat_deg", "lon_deg", "h_m")
        arrays = [_real_array(n, v) for n, v in zip(names, (lat_deg, lon_deg, h_m))]
        shapes = [a.shape for a in arrays]
        try:
            shape = _np.broadcast_shapes(*shapes)
        except ValueError:
            raise _InputError(
                "shapes " + ", ".join(map(str, shapes)) + " do not broadcast together",
                field=", ".join(names),
            ) from None
        flat = [_np.ascontiguousarray(_np.broadcast_to(a, shape)).reshape(-1) for a in arrays]
        try:
            xi, eta, n = self._core.evaluate(*flat, _boolean("geoid", geoid))
        except _InputError as e:
            _relocate(e, names, shapes, shape)
            raise
        except Exception as e:  # NumericalError: index into the broadcast shape
            if getattr(e, "field", None):
                _relocate(e, (), (), shape)
            raise

        def shaped(a):
            return None if a is None else a.reshape(shape)[()]

        return Deflection(shaped(xi), shaped(eta), shaped(n))

    def grid(self, lat_deg, lon_deg, h_m=0.0, *, geoid=True) -> Deflection:
        """ξ, η, N on the regular grid of 1-D lat_deg (rows) × 1-D lon_deg (columns):
        arrays of shape (len(lat_deg), len(lon_deg)).

        With a scalar h_m, the parallel path: per row the Legendre sums are formed once
        for its latitude (gravity::GravityCircle) and each longitude then costs O(degree),
        rows spread over the model's threads, the GIL released; the values equal
        deflection()'s on the same points to rounding (≈1e-12″), and do not depend on
        how a grid is split into sub-grids (meridian.dask relies on this). With h_m an
        array broadcastable to the grid's shape, deflection() on the mesh.

        Errors: InputError with field "lat_deg[i]", "lon_deg[j]" or "h_m" for bad values,
        "lat_deg"/"lon_deg" when not 1-D; NumericalError "points[i, j]" for a value that
        is not finite.
        """
        lat = _real_array("lat_deg", lat_deg)
        lon = _real_array("lon_deg", lon_deg)
        h = _real_array("h_m", h_m)
        for name, a in (("lat_deg", lat), ("lon_deg", lon)):
            if a.ndim != 1:
                raise _InputError(f"must be 1-D for grid(), got shape {a.shape}", field=name)
        if h.ndim != 0:
            return self.deflection(lat[:, None], lon[None, :], h, geoid=geoid)
        xi, eta, n = self._core.grid(_np.ascontiguousarray(lat), _np.ascontiguousarray(lon), float(h),
                                     _boolean("geoid", geoid))
        return Deflection(xi, eta, n)


def _reopen(recipe):
    kind, *args = recipe
    if kind == "open":
        path, md, threads = args
        return GravityModel.open(path, max_degree=None if md < 0 else md, threads=threads)
    degree, seed, threads = args
    return synthetic_model(degree, seed, threads=threads)


def synthetic_model(degree=360, seed=1, *, threads=0) -> GravityModel:
    """A random model with Kaula's rule (σ of C̄nm, S̄nm = 1e-5/n²), GM and a of
    EGM96/EGM2008, WGS84 reference; the same seed gives the same coefficients on
    every platform (include/meridian/gravity/synthetic.hpp). degree: an integer in
    [2, 2190]; seed: an integer in [0, 2⁶⁴ − 1]; threads as GravityModel.open (InputError,
    field "degree", "seed" or "threads", naming the range otherwise). `meridian gravity
    synth-model --degree D --seed S` writes the same model to files."""
    degree = _integer("degree", degree, 2, 2190)
    seed = _integer("seed", seed, 0, 2**64 - 1)
    threads = _integer("threads", threads, 0, GravityModel.MAX_THREADS)
    core = _core.gravity.synthetic(degree, seed, threads)
    return GravityModel(core, ("synthetic", degree, seed, threads))


def search_path() -> list:
    """Directories searched for a model given by name ($GEOGRAPHICLIB_GRAVITY_PATH, …)."""
    return _core.gravity.search_path()
