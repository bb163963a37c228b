"""meridian.dask on a LocalCluster of 2 worker processes: bit for bit the single-process
result, each worker opening the model once, the NetCDF writer."""

import dask
import dask.array as da
import numpy as np
import pytest
from distributed import Client, LocalCluster

import meridian
import meridian.dask as mdask
import meridian.gravity as mg


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as c:
            yield c


@pytest.fixture(scope="module")
def model():
    return mg.synthetic_model(90, 4, threads=1)


def test_grid_on_two_workers_equals_one_process_bit_for_bit(client, model):
    lat = np.linspace(-89.75, 89.75, 72)
    lon = np.linspace(-180, 177.5, 48)
    d = mdask.grid(model, lat, lon, 300.0, chunks=(10, 24))
    assert isinstance(d.xi_arcsec, da.Array) and d.xi_arcsec.numblocks == (8, 2)
    xi, eta, n = dask.compute(*d)
    ref = model.grid(lat, lon, 300.0)
    np.testing.assert_array_equal(xi, ref.xi_arcsec)
    np.testing.assert_array_equal(eta, ref.eta_arcsec)
    np.testing.assert_array_equal(n, ref.geoid_m)
    # Both workers took part, and each opened the model once for its 8 chunks.
    opened = client.run(lambda: len(__import__("meridian.dask").dask._models))
    assert len(opened) == 2 and all(v == 1 for v in opened.values())


def test_point_table_as_dask_arrays(client, model):
    rng = np.random.default_rng(1)
    lat = da.from_array(rng.uniform(-90, 90, 5000), chunks=700)
    lon = da.from_array(rng.uniform(-180, 180, 5000), chunks=700)
    d = mdask.deflection(model, lat, lon, 50.0, geoid=False)
    assert d.geoid_m is None
    xi, eta = dask.compute(d.xi_arcsec, d.eta_arcsec)
    ref = model.deflection(lat.compute(), lon.compute(), 50.0, geoid=False)
    np.testing.assert_array_equal(xi, ref.xi_arcsec)
    np.testing.assert_array_equal(eta, ref.eta_arcsec)


def test_errors_cross_the_worker_boundary(client, model):
    lat = np.zeros((6, 5))
    lat[4, 3] = 95.0
    d = mdask.deflection(model, lat, np.arange(5.0), chunks=(2, 2))
    with pytest.raises(meridian.InputError) as e:
        dask.compute(*d)
    assert e.value.field == "lat_deg[4, 3]"  # the index in the whole array, not in its chunk
    lat = np.linspace(-80, 80, 20)
    lat[13] = np.nan
    with pytest.raises(meridian.InputError) as e:
        dask.compute(*mdask.grid(model, lat, np.arange(0.0, 360.0, 30.0), chunks=(5, 4)))
    assert e.value.field == "lat_deg[13]"
    with pytest.raises(meridian.InputError) as e:
        mdask.deflection(model, np.zeros(3), np.zeros(4))
    assert e.value.field == "lat_deg, lon_deg, h_m"


def test_grid_to_netcdf_streams_blocks_from_the_workers(client, model, tmp_path):
    import netCDF4

    lat = np.linspace(-60, 60, 25)
    lon = np.linspace(0, 350, 36)
    path = tmp_path / "dov.nc"
    assert mdask.grid_to_netcdf(path, model, lat, lon, 0.0, rows_per_chunk=4, client=client) == path
    ref = model.grid(lat, lon, 0.0)
    with netCDF4.Dataset(path) as nc:
        np.testing.assert_array_equal(nc["lat"][:], lat)
        np.testing.assert_array_equal(nc["lon"][:], lon)
        np.testing.assert_array_equal(nc["xi"][:], ref.xi_arcsec)
        np.testing.assert_array_equal(nc["eta"][:], ref.eta_arcsec)
        np.testing.assert_array_equal(nc["geoid"][:], ref.geoid_m)
        assert nc["xi"].units == "arcsec" and nc.Conventions == "CF-1.8"
    assert [p.name for p in tmp_path.iterdir()] == ["dov.nc"]
