"""Cluster-scale evaluation of gravity models with dask (docs/scaling.md).

A grid or a long point table is split into chunks; each chunk is evaluated on a
dask worker by GravityModel.grid (a sub-grid at one height) or
GravityModel.deflection (points). The model travels as the recipe to open
it (path and degree, or degree and seed), never as coefficients, and each worker
process opens it once (a per-process cache), so a degree-2190 model is read once
per worker, not once per chunk. Results are bit-for-bit those of one process:
every point is evaluated by the same code whatever the chunk it falls in.

* deflection(model, lat, lon, h, chunks=...) -> Deflection of dask arrays (lazy);
* grid(model, lat, lon, h, chunks=...) -> the same on a regular grid;
* grid_to_netcdf(path, model, lat, lon, h, ...): a grid written to a NetCDF file
  row block by row block as the workers finish them, so the client holds a few
  blocks, not the grid. NetCDF (CF-1.8, lat/lon coordinate variables) because GMT
  (grdimage, grdinfo) and QGIS (through GDAL) open it as a georeferenced grid, as do
  xarray, Panoply and ncview; .npy chunks would need a script to be read at all.

Needs Debian's python3-dask and python3-distributed (and python3-netcdf4 for
grid_to_netcdf); `import meridian` does not import this module.
"""

import functools as _functools
import os as _os
import threading as _threading

import dask.array as _da
import numpy as _np

from . import gravity as _gravity
from ._result import boolean as _boolean
from .errors import Error as _Error, InputError as _InputError

__all__ = ["deflection", "grid", "grid_to_netcdf", "open_model"]

_lock = _threading.Lock()
_models = {}


def open_model(recipe):
    """The model for `recipe` (GravityModel's pickled form), opened once per process."""
    with _lock:
        m = _models.get(recipe)
        if m is None:
            m = _models[recipe] = _gravity._reopen(recipe)
        return m


def _recipe(model):
    if not isinstance(model, _gravity.GravityModel):
        raise _InputError("must be a meridian.gravity.GravityModel", field="model")
    return model._recipe


def _block(recipe, geoid, lat, lon, h, block_info=None):
    try:
        d = open_model(recipe).deflection(lat, lon, h, geoid=geoid)
    except _Error as e:
        _to_global_index(e, block_info)
        raise
    parts = [d.xi_arcsec, d.eta_arcsec] + ([d.geoid_m] if geoid else [])
    return _np.stack([_np.asarray(p, dtype=_np.float64) for p in parts])


def _to_global_index(err, block_info):
    """The element index in err.field ("lat_deg[2, 3]", relative to the block) made
    relative to the whole broadcast array, from dask's block_info."""
    field = err.field or ""
    if not block_info or not field.endswith("]") or "[" not in field:
        return
    name, _, idx = field[:-1].partition("[")
    try:
        local = [int(x) for x in idx.split(",")]
    except ValueError:
        return
    start = [lo for lo, _ in block_info[0]["array-location"]]
    if len(local) == len(start):
        err.field = name + "[" + ", ".join(str(a + b) for a, b in zip(local, start)) + "]"


def deflection(model, lat_deg, lon_deg, h_m=0.0, *, geoid=True, chunks="auto"):
    """Lazy ξ, η (″) and N (m) at points given by numpy or dask arrays of
    broadcast-compatible shapes (as GravityModel.deflection), evaluated chunk by chunk
    on dask's current scheduler (a distributed Client when one is active).

    chunks: the chunking of the broadcast inputs (dask's notation; "auto" keeps dask
    arrays' own chunks and otherwise picks ~10^5 points a chunk). Returns a
    gravity.Deflection of dask arrays; compute them together
    (``dask.compute(*d)``) so each chunk is evaluated once. Errors as
    GravityModel.deflection, raised when computed, with the element's index in the
    broadcast shape (``"lat_deg[4, 7]"``), except dtype and shape errors, raised here.
    """
    recipe = _recipe(model)
    names = ("lat_deg", "lon_deg", "h_m")
    arrays = []
    for name, v in zip(names, (lat_deg, lon_deg, h_m)):
        a = v if isinstance(v, _da.Array) else _gravity._real_array(name, v)
        if a.dtype.kind not in "iuf":
            raise _InputError(f"must be real numbers, got dtype {a.dtype}", field=name)
        arrays.append(a)
    try:
        shape = _np.broadcast_shapes(*(a.shape for a in arrays))
    except ValueError:
        raise _InputError("shapes " + ", ".join(str(a.shape) for a in arrays) + " do not broadcast together",
                         field=", ".join(names)) from None
    if chunks == "auto":
        given = [a for a in arrays if isinstance(a, _da.Array) and a.shape == shape]
        chunks = given[0].chunks if given else _da.core.normalize_chunks(
            "auto", shape, limit=100_000 * 8, dtype=_np.float64)
    arrays = [_da.broadcast_to(_da.asarray(a).astype(_np.float64), shape).rechunk(chunks) for a in arrays]
    n = 3 if geoid else 2
    stacked = _da.map_blocks(_functools.partial(_block, recipe, _boolean("geoid", geoid)), *arrays, new_axis=0,
                            chunks=((n,),) + arrays[0].chunks, dtype=_np.float64,
                            name="meridian-deflection")
    return _gravity.Deflection(stacked[0], stacked[1], stacked[2] if geoid else None)


def _grid_block(recipe, geoid, h, lat2, lon2, block_info=None):
    try:
        d = open_model(recipe).grid(lat2[:, 0], lon2[0, :], h, geoid=geoid)
    except _Error as e:
        if block_info:
            r0 = block_info[0]["array-location"][0][0]
            c0 = block_info[1]["array-location"][1][0]
            field = e.field or ""
            if field.startswith("lat_deg["):
                e.field = f"lat_deg[{int(field[8:-1]) + r0}]"
            elif field.startswith("lon_deg["):
                e.field = f"lon_deg[{int(field[8:-1]) + c0}]"
            elif field.startswith("points["):
                i, j = (int(x) for x in field[7:-1].split(","))
                e.field = f"points[{i + r0}, {j + c0}]"
        raise
    return _np.stack([d.xi_arcsec, d.eta_arcsec] + ([d.geoid_m] if geoid else []))


def grid(model, lat_deg, lon_deg, h_m=0.0, *, geoid=True, chunks=(256, -1)):
    """GravityModel.grid on the regular grid 1-D lat_deg (rows) × 1-D lon_deg (columns),
    one sub-grid per chunk of the (rows, columns) result (default 256 whole rows).
    With a scalar h_m each chunk runs the parallel path (GravityModel.grid), whose
    values do not depend on the chunking, so the result equals model.grid(...) bit for
    bit; with an array h_m, deflection() on the mesh. Errors: as GravityModel.grid, with
    indices in the whole grid."""
    recipe = _recipe(model)
    lat = _gravity._real_array("lat_deg", lat_deg)
    lon = _gravity._real_array("lon_deg", lon_deg)
    h = _gravity._real_array("h_m", h_m)
    for name, a in (("lat_deg", lat), ("lon_deg", lon)):
        if a.ndim != 1:
            raise _InputError(f"must be 1-D for grid(), got shape {a.shape}", field=name)
    chunks = _da.core.normalize_chunks(chunks, (lat.size, lon.size), dtype=_np.float64)
    if h.ndim != 0:
        return deflection(model, lat[:, None], lon[None, :], h, geoid=geoid, chunks=chunks)
    lat2 = _da.from_array(lat[:, None], chunks=(chunks[0], 1))
    lon2 = _da.from_array(lon[None, :], chunks=(1, chunks[1]))
    n = 3 if geoid else 2
    stacked = _da.map_blocks(_functools.partial(_grid_block, recipe, _boolean("geoid", geoid), float(h)), lat2, lon2,
                            new_axis=0, chunks=((n,),) + chunks, dtype=_np.float64, name="meridian-grid")
    return _gravity.Deflection(stacked[0], stacked[1], stacked[2] if geoid else None)


def grid_to_netcdf(path, model, lat_deg, lon_deg, h_m=0.0, *, rows_per_chunk=256, client=None):
    """Evaluate grid() and write it to the NetCDF-4 file `path` (variables xi, eta in
    arcsec and geoid in m over (lat, lon), CF-1.8 attributes), one row block at a time
    as the blocks finish: with a distributed `client` (or the current one) the blocks
    run on its workers and stream back; without one, on the local scheduler. The file
    is written under a temporary name and renamed when complete (never a partial
    file under `path`). h_m must be a scalar here. Returns `path`.
    """
    import netCDF4

    lat = _gravity._real_array("lat_deg", lat_deg)
    lon = _gravity._real_array("lon_deg", lon_deg)
    h = _gravity._real_array("h_m", h_m)
    if h.ndim != 0:
        raise _InputError("must be a scalar for grid_to_netcdf()", field="h_m")
    d = grid(model, lat, lon, float(h), chunks=(int(rows_per_chunk), -1))
    tmp = f"{_os.fspath(path)}.tmp{_os.getpid()}"
    try:
        with netCDF4.Dataset(tmp, "w", format="NETCDF4") as nc:
            nc.Conventions = "CF-1.8"
            nc.title = f"Deflection of the vertical and geoid of {model.name} (degree {model.max_degree})"
            nc.source = "meridian.dask.grid_to_netcdf (Meridian " + __import__("meridian").__version__ + ")"
            nc.height_m = float(h)
            nc.createDimension("lat", lat.size)
            nc.createDimension("lon", lon.size)
            for name, values, units, std in (("lat", lat, "degrees_north", "latitude"),
                                             ("lon", lon, "degrees_east", "longitude")):
                v = nc.createVariable(name, "f8", (name,))
                v.units, v.standard_name = units, std
                v[:] = values
            out = {}
            for name, units, long_name in (
                    ("xi", "arcsec", "north-south deflection of the vertical xi (positive: plumb line north)"),
                    ("eta", "arcsec", "east-west deflection of the vertical eta (positive: plumb line east)"),
                    ("geoid", "m", "geoid height N above the ellipsoid")):
                v = nc.createVariable(name, "f8", ("lat", "lon"), zlib=True,
                                      chunksizes=(min(int(rows_per_chunk), lat.size), lon.size))
                v.units, v.long_name = units, long_name
                out[name] = v
            blocks = _row_blocks(d)
            for r0, r1, block in _blocks_as_completed(blocks, client):
                out["xi"][r0:r1, :] = block[0]
                out["eta"][r0:r1, :] = block[1]
                out["geoid"][r0:r1, :] = block[2]
        _os.replace(tmp, path)
    finally:
        if _os.path.exists(tmp):
            _os.unlink(tmp)
    return path


def _row_blocks(d):
    """(r0, r1, delayed (3, rows, cols) array) for each row block of a grid() result."""
    stacked = _da.stack([d.xi_arcsec, d.eta_arcsec, d.geoid_m])
    starts = _np.cumsum((0,) + d.xi_arcsec.chunks[0])
    return [(int(starts[i]), int(starts[i + 1]), stacked[:, starts[i]:starts[i + 1], :])
            for i in range(len(starts) - 1)]


def _blocks_as_completed(blocks, client):
    if client is None:
        try:
            from distributed import get_client
            client = get_client()
        except (ImportError, ValueError):
            client = None
    if client is None:
        for r0, r1, b in blocks:
            yield r0, r1, b.compute()
        return
    from distributed import as_completed
    futures = {client.compute(b): (r0, r1) for r0, r1, b in blocks}
    for f in as_completed(futures):
        r0, r1 = futures[f]
        yield r0, r1, f.result()
        f.release()
