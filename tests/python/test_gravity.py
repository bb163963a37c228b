"""meridian.gravity against the CLI and GeographicLib's Gravity tool; broadcasting,
dtypes, bad input, the GIL."""

import shutil
import subprocess
import threading
import time

import numpy as np
import pytest

import meridian
import meridian.gravity as mg


def scattered_points(n=200, seed=7):
    """Points over the whole globe, poles and the date line included, heights -500 m .. 30 km."""
    rng = np.random.default_rng(seed)
    lat = np.concatenate([rng.uniform(-90, 90, n - 6), [90.0, -90.0, 89.999, -0.0, 0.0, 45.0]])
    lon = np.concatenate([rng.uniform(-180, 360, n - 6), [0.0, 123.0, 180.0, -180.0, 0.0, 540.0]])
    h = np.concatenate([rng.uniform(-500, 30000, n - 6), [0.0, 100.0, 0.0, 0.0, 0.0, 12.5]])
    return lat, lon, h


def test_arrays_match_the_cli_on_the_same_points(synth_files, cli, tmp_path):
    lat, lon, h = scattered_points()
    pts = tmp_path / "pts.csv"
    pts.write_text("".join(f"{a!r},{b!r},{c!r}\n" for a, b, c in zip(lat, lon, h)))
    out = tmp_path / "out.csv"
    cli("gravity", "points", "--model", synth_files / "m.egm", "--input", pts, "-o", out, "-q")
    ref = np.loadtxt(out, delimiter=",", skiprows=1)
    assert ref.shape == (len(lat), 6)
    # The file and the generator give the same model; the CLI prints 9 decimals.
    for model in (mg.GravityModel.open(synth_files / "m.egm"), mg.synthetic_model(60, 3)):
        d = model.deflection(lat, lon, h)
        np.testing.assert_allclose(d.xi_arcsec, ref[:, 3], rtol=0, atol=6e-10)
        np.testing.assert_allclose(d.eta_arcsec, ref[:, 4], rtol=0, atol=6e-10)
        np.testing.assert_allclose(d.geoid_m, ref[:, 5], rtol=0, atol=6e-10)


def test_arrays_match_geographiclib_gravity_tool(synth_files):
    gravity = shutil.which("Gravity")
    assert gravity, "GeographicLib's Gravity tool is needed (Debian geographiclib-tools; scripts/setup.sh)"
    lat, lon, h = scattered_points(120, seed=11)
    lon = np.where(lon > 180, lon - 360, lon)  # Gravity reads longitudes in [-180, 180]... and 540 is not
    model = mg.GravityModel.open(synth_files / "m.gfc")
    d = model.deflection(lat, lon, h)

    def run(flag, rows):
        r = subprocess.run([gravity, "-n", "m", "-d", str(synth_files), flag, "-p", "10"],
                           input=rows, capture_output=True, text=True, check=True)
        return np.loadtxt(r.stdout.splitlines(), ndmin=2)

    # -A: Dg01 (mGal), xi, eta (arcsec) at (lat, lon, h); -H: geoid height N (m) at (lat, lon).
    a = run("-A", "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in zip(lat, lon, h)))
    n = run("-H", "".join(f"{x!r} {y!r}\n" for x, y in zip(lat, lon)))
    np.testing.assert_allclose(d.xi_arcsec, a[:, 1], rtol=0, atol=1e-7)
    np.testing.assert_allclose(d.eta_arcsec, a[:, 2], rtol=0, atol=1e-7)
    np.testing.assert_allclose(d.geoid_m, n[:, 0], rtol=0, atol=1e-7)
    assert np.abs(d.xi_arcsec).max() > 0.5  # the model is not trivially zero


@pytest.fixture(scope="module")
def model():
    return mg.synthetic_model(40, 5)


def test_broadcasting_follows_numpy(model):
    lat = np.array([[-60.0], [0.5], [33.3]])  # (3, 1)
    lon = np.array([10.0, 20.0, 200.0, -5.0])  # (4,)
    d = model.deflection(lat, lon, 250.0)
    assert d.xi_arcsec.shape == d.eta_arcsec.shape == d.geoid_m.shape == (3, 4)
    la, lo = np.broadcast_arrays(lat, lon)
    flat = model.deflection(la.ravel(), lo.ravel(), np.full(12, 250.0))
    for got, ref in zip(d, flat):
        np.testing.assert_array_equal(got, ref.reshape(3, 4))
    # A point on its own gives the same bits as inside a batch.
    one = model.deflection(33.3, 200.0, 250.0)
    assert isinstance(one.xi_arcsec, np.float64) and np.ndim(one.xi_arcsec) == 0
    assert one.xi_arcsec == d.xi_arcsec[2, 2] and one.geoid_m == d.geoid_m[2, 2]
    # Heights broadcast too; empty arrays give empty results.
    dh = model.deflection(10.0, 20.0, [0.0, 1000.0, 20000.0])
    assert dh.xi_arcsec.shape == (3,) and dh.geoid_m[0] == dh.geoid_m[2]  # N ignores h
    assert dh.xi_arcsec[0] != dh.xi_arcsec[2]
    e = model.deflection(np.zeros((0, 3)), 0.0)
    assert e.xi_arcsec.shape == (0, 3)


def test_dtypes_and_layouts(model):
    lat64 = np.linspace(-80, 80, 17)
    ref = model.deflection(lat64, 30.0)
    assert ref.xi_arcsec.dtype == np.float64
    # Integer and float32 inputs are converted exactly (they are exact in float64).
    ints = model.deflection(np.arange(-80, 81, 10, dtype=np.int32), np.int64(30))
    np.testing.assert_array_equal(ints.xi_arcsec, ref.xi_arcsec)
    f32 = np.linspace(-80, 80, 17, dtype=np.float32)
    np.testing.assert_array_equal(model.deflection(f32, 30.0).xi_arcsec,
                                  model.deflection(f32.astype(np.float64), 30.0).xi_arcsec)
    # Lists, strided and Fortran-ordered views give the same values.
    np.testing.assert_array_equal(model.deflection(list(lat64), 30).eta_arcsec, ref.eta_arcsec)
    wide = np.repeat(lat64, 2)[::2]
    assert not wide.flags.c_contiguous or wide.base is not None
    np.testing.assert_array_equal(model.deflection(wide, 30.0).xi_arcsec, ref.xi_arcsec)
    grid = np.asfortranarray(np.stack([lat64, lat64[::-1]], axis=1))
    g = model.deflection(grid, 30.0)
    np.testing.assert_array_equal(g.xi_arcsec[:, 0], ref.xi_arcsec)
    np.testing.assert_array_equal(g.xi_arcsec[:, 1], ref.xi_arcsec[::-1])
    # geoid=False: no N, the same deflections.
    nog = model.deflection(lat64, 30.0, 500.0, geoid=False)
    assert nog.geoid_m is None
    np.testing.assert_array_equal(nog.xi_arcsec, model.deflection(lat64, 30.0, 500.0).xi_arcsec)


def test_grid_is_the_deflection_on_the_mesh(model):
    lat = np.linspace(-89.5, 89.5, 7)
    lon = np.linspace(-180, 179, 9)
    g = model.grid(lat, lon, 100.0)  # the parallel path: one GravityCircle per row
    assert g.xi_arcsec.shape == g.geoid_m.shape == (7, 9) and g.xi_arcsec.dtype == np.float64
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    d = model.deflection(la, lo, 100.0)
    for got, ref in zip(g, d):  # the same quantities to rounding (gravity_circle.hpp)
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-10)
    # Sub-grids give the same bits as the whole (meridian.dask relies on it).
    part = model.grid(lat[2:5], lon[3:8], 100.0)
    np.testing.assert_array_equal(part.xi_arcsec, g.xi_arcsec[2:5, 3:8])
    np.testing.assert_array_equal(part.geoid_m, g.geoid_m[2:5, 3:8])
    assert model.grid(lat, lon, 100.0, geoid=False).geoid_m is None
    # Heights per node: the batch path on the mesh.
    hh = np.full((7, 9), 100.0)
    np.testing.assert_array_equal(model.grid(lat, lon, hh).xi_arcsec, d.xi_arcsec)
    with pytest.raises(meridian.InputError) as e:
        model.grid(la, lon)
    assert e.value.field == "lat_deg"
    for args, field in [((np.array([0.0, 90.5]), lon), "lat_deg[1]"), ((lat, np.array([0.0, np.nan])), "lon_deg[1]"),
                        ((lat, lon, -1e5), "h_m")]:
        with pytest.raises(meridian.InputError) as e:
            model.grid(*args)
        assert e.value.field == field


@pytest.mark.parametrize(
    "args, cls, field",
    [
        ((np.nan, 0.0, 0.0), meridian.InputError, "lat_deg"),
        (([0.0, 90.0000001], 0.0, 0.0), meridian.InputError, "lat_deg[1]"),
        (([[0.0, 1.0], [2.0, -91.0]], 0.0, 0.0), meridian.InputError, "lat_deg[1, 1]"),
        ((0.0, [1.0, np.inf], 0.0), meridian.InputError, "lon_deg[1]"),
        # lat (3, 1) against lon (4,): the bad height's own index in h (4,)
        ((np.zeros((3, 1)), np.zeros(4), [0.0, 0.0, -20000.0, 0.0]), meridian.InputError, "h_m[2]"),
        ((0.0, 0.0, 2e7), meridian.InputError, "h_m"),
        ((np.zeros(3), np.zeros(4), 0.0), meridian.InputError, "lat_deg, lon_deg, h_m"),
        ((np.array(["45"]), 0.0, 0.0), meridian.InputError, "lat_deg"),
        ((0.0, np.array([1 + 2j]), 0.0), meridian.InputError, "lon_deg"),
        ((0.0, 0.0, None), meridian.InputError, "h_m"),
    ],
)
def test_bad_input_raises_with_the_field(model, args, cls, field):
    with pytest.raises(cls) as e:
        model.deflection(*args)
    assert e.value.field == field
    assert isinstance(e.value, ValueError) and isinstance(e.value, meridian.Error)
    assert e.value.file is None and e.value.line is None
    assert str(e.value).startswith(field + ": ")


def test_model_errors_carry_file_line_field(tmp_path):
    with pytest.raises(meridian.InputError) as e:
        mg.GravityModel.open("no_such_model_anywhere")
    assert e.value.field == "path_or_name" and "not found" in e.value.message
    bad = tmp_path / "bad.gfc"
    bad.write_text("modelname x\nearth_gravity_constant 3.986004415E+14\nradius 6378136.3\n"
                   "max_degree 2\nerrors no\nnorm fully_normalized\nend_of_head\n"
                   "gfc 0 0 1.0 0.0\ngfc 2 0 abc 0.0\n")
    with pytest.raises(meridian.ParseError) as e:
        mg.GravityModel.open(bad)
    assert e.value.file == str(bad) and e.value.line == 9
    with pytest.raises(meridian.InputError) as e:
        mg.synthetic_model(1, 1)
    assert e.value.field == "degree"


def test_model_metadata(synth_files):
    m = mg.GravityModel.open(synth_files / "m.egm", max_degree=20)
    assert m.max_degree == 20 and m.info["file_max_degree"] == 60
    assert m.info["gm_m3_s2"] == 3.986004415e14 and m.info["radius_m"] == 6378136.3
    # A GeographicLib .egm never states its tide system: the package passes the warning on.
    assert m.info["tide_system"] == "" and any("tide" in w for w in m.warnings)


def test_gil_is_released_during_a_batch():
    # One thread evaluates a batch (0.2-1 s here); this thread sleeps 10 ms, which
    # it can only finish by taking the GIL back. Released: it finishes long before the batch
    # ends. Held: not before the batch's C++ call returns.
    model = mg.synthetic_model(360, 2, threads=1)
    lat = np.linspace(-80, 80, 8000)
    started, t = threading.Event(), {}

    def batch():
        started.set()
        t["begin"] = time.perf_counter()
        model.deflection(lat, 10.0, geoid=False)
        t["end"] = time.perf_counter()

    worker = threading.Thread(target=batch)
    worker.start()
    started.wait()
    time.sleep(0.01)
    t["main"] = time.perf_counter()
    worker.join()
    duration = t["end"] - t["begin"]
    assert duration > 0.05, "the batch is too short to tell"
    assert t["main"] < t["end"] - duration / 2, "this thread waited for the batch: the GIL was held"
