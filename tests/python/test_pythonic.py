"""The package as Python code expects it (issue 37): results that are mappings with identifier
attribute names and a repr that shows the numbers; integer arguments checked as integers and
degrees against their range, every refusal a meridian.Error; module namespaces holding their
__all__ only; dict inputs for nav as for gyro, with YAML's and numpy's types. Each test fails
on the behaviour before (noted in its comment). References: the CLI's --json output of the
same file, the file given by path, and the values written in the test."""

import collections.abc
import datetime
import json
import math
import types

import numpy as np
import pytest
import yaml

import meridian
import meridian.dask
import meridian.gravity as mg
from meridian import dov, gyro, maglev, nav
from meridian._result import Result

NAV = "examples/nav-scenario-c/nav.yaml"


@pytest.fixture(scope="module")
def nav_run(source_dir, cli):
    """(the Result of nav.process, the CLI's --json of the same configuration)."""
    config = source_dir / NAV
    return nav.process(config), json.loads(cli("nav", "process", config, "--json", "-q").stdout)


# --- results as mappings (before: `'rts' in n.methods` and list(n.methods) raised KeyError: 0) ---

def test_results_are_mappings(nav_run):
    n, ref = nav_run
    assert isinstance(n, collections.abc.Mapping) and isinstance(n.methods, collections.abc.Mapping)
    assert "rts" in n.methods and "nope" not in n.methods
    assert list(n.methods) == list(ref["methods"]) and len(n.methods) == len(ref["methods"]) == 7
    assert list(n.methods.keys()) == list(ref["methods"])
    assert [name for name in n.methods] == list(ref["methods"])
    rms = {name: m.rms_m for name, m in n.methods.items()}
    assert rms == {name: m["rms_m"] for name, m in ref["methods"].items()}
    assert [m["rms_m"] for m in n.methods.values()] == [m["rms_m"] for m in ref["methods"].values()]
    assert n.methods.get("nope") is None and n.methods.get("rts").epochs == 361
    assert n == ref and n.methods["rts"] == ref["methods"]["rts"]   # Mapping equality, recursively
    assert dict(n)["epochs"] == ref["epochs"] == 361
    with pytest.raises(KeyError):
        n.methods["nope"]


def test_tracks_and_tables_iterate_over_their_names(nav_run):
    n, ref = nav_run
    assert "rts" in n.tracks and list(n.tracks) == ref["method_order"]
    t = n.tracks["rts"]
    assert list(t) == list(t.keys()) and list(t)[:3] == ["time_s", "x_m", "y_m"]
    assert "x_m" in t and "nope" not in t
    assert len(t) == 361                                   # rows, as a DataFrame's len
    assert dict(t)["x_m"] is t.x_m and dict(t.items()).keys() == t.keys()
    assert n.tracks.to_dict()["rts"]["x_m"].tolist() == t.x_m.tolist()


def test_attribute_names_are_identifiers(nav_run):
    # before: "dead-reckoning" could not be an attribute (AttributeError for dead_reckoning)
    n, ref = nav_run
    assert n.methods.dead_reckoning.rms_m == ref["methods"]["dead-reckoning"]["rms_m"]
    assert n.methods.sequential_bias_I.rms_m == ref["methods"]["sequential-bias-I"]["rms_m"]
    assert n.tracks.dead_reckoning is n.tracks["dead-reckoning"]
    assert {"dead_reckoning", "sequential_no_bias", "rts"} <= set(dir(n.methods))
    assert "dead-reckoning" not in dir(n.methods)
    with pytest.raises(AttributeError):
        n.methods.dead_reckoning_
    from meridian._result import identifier

    assert [identifier(k) for k in ("dead-reckoning", "from", "2C", "x_m", "a b")] == \
        ["dead_reckoning", "from_", "_2C", "x_m", "a_b"]
    r = Result({"from": 1, "2C": 2, "values": [3], "keys": 4})
    assert (r.from_, r._2C, r.values, r.keys) == (1, 2, [3], 4)   # keys win over the methods
    assert list(Result.keys(r)) == ["from", "2C", "values", "keys"]
    # two keys with one identifier: neither by attribute (ambiguous), both by key
    both = Result({"a-b": 1, "a b": 2})
    with pytest.raises(AttributeError):
        both.a_b
    assert (both["a-b"], both["a b"]) == (1, 2)
    assert "a_b" not in dir(both) and Result({"a-b": 1, "a_b": 2}).a_b == 2   # the identifier key wins


def test_maglev_denoise_values_still_an_attribute():
    x = np.sin(np.linspace(0, 20, 512)) + 1e-3 * np.cos(np.arange(512) * 2.1)
    full = maglev.denoise(x, level=4, full=True)
    assert isinstance(full.values, np.ndarray) and full.values.shape == (512,)
    np.testing.assert_array_equal(full.values, maglev.denoise(x, level=4))


def test_repr_shows_the_numbers(nav_run):
    # before: Result(bias_east_m_s, bias_north_m_s, ...): the names only
    n, ref = nav_run
    rts = ref["methods"]["rts"]
    text = repr(n.methods["rts"])
    assert f"rms_m={rts['rms_m']!r}" in text and f"epochs={rts['epochs']!r}" in text
    assert f"final_position=Result(cov_xy_m2={rts['final_position']['cov_xy_m2']!r}" in text
    assert "'dead-reckoning': Result(" in repr(n.methods)   # a key that is not an identifier
    long = repr(Result({"a": list(range(100)), "b": {"c": {"d": {"e": 1}}}, "s": "x" * 200}))
    assert long.startswith("Result(a=[0, 1, 2, 3, … 96 more], b=Result(c=Result(d={…1 keys})), s='")
    assert len(long) < 150
    assert repr(Result({f"k{i}": i for i in range(20)})).endswith("k18=18, k19=19)")   # every key at the top
    assert repr(Result({"w": {f"k{i}": i for i in range(20)}})).endswith("k7=7, … 12 more))")
    t = repr(n.tracks["rts"])
    assert t.startswith("Table(361 rows × 11 columns\n  time_s ")
    assert "1800." in t and "x_m" in t                      # the first and last values of a column
    assert "tracks=Result('dead-reckoning': Table(361 rows × 11 columns)" in repr(n)


# --- strict arguments ---

def test_max_degree_is_an_integer_within_the_file(synth_files):
    path = synth_files / "m.gfc"
    assert mg.GravityModel.open(path, max_degree=np.int64(30)).max_degree == 30
    assert mg.GravityModel.open(path, max_degree=60).max_degree == 60
    assert mg.GravityModel.open(path, max_degree=0).max_degree == 0
    for bad in (2.9, 3.0, "3", True):   # before: 2.9 silently gave degree 2
        with pytest.raises(meridian.InputError) as e:
            mg.GravityModel.open(path, max_degree=bad)
        assert e.value.field == "max_degree" and "must be an integer" in e.value.message
    for bad in (999, 61, -1):          # before: 999 silently gave the file's degree 60
        with pytest.raises(meridian.InputError) as e:
            mg.GravityModel.open(path, max_degree=bad)
        assert e.value.field == "max_degree" and ("[0, 60]" in e.value.message or "≥ 0" in e.value.message)


def test_threads_and_synthetic_arguments_give_a_meridian_error():
    # before: threads=-1 raised pybind11's TypeError with the C++ signatures
    for call in (lambda: mg.GravityModel.open("egm96", threads=-1), lambda: mg.synthetic_model(4, 1, threads=-1),
                 lambda: mg.synthetic_model(4, 1, threads=1.5), lambda: mg.synthetic_model(4, 1, threads=10**6)):
        with pytest.raises(meridian.InputError) as e:
            call()
        assert e.value.field == "threads" and "[0, 1024]" in e.value.message
        assert "incompatible function arguments" not in str(e.value)
    with pytest.raises(meridian.InputError, match=r"\[2, 2190\]"):
        mg.synthetic_model(2.9, 1)   # before: degree 2
    with pytest.raises(meridian.InputError, match=r"\[2, 2190\]"):
        mg.synthetic_model(2191, 1)
    with pytest.raises(meridian.InputError) as e:
        mg.synthetic_model(4, -1)    # before: pybind11's TypeError
    assert e.value.field == "seed"
    assert mg.synthetic_model(np.int32(4), np.uint64(7)).max_degree == 4
    for call, field in ((lambda: dov.simulate(hours=0.01, seed=1.5), "seed"),
                        (lambda: nav.simulate("/nonexistent", seed=2.5), "seed"),
                        (lambda: nav.simulate("/nonexistent", stations=3.5), "stations"),
                        (lambda: maglev.simulate(samples=100, seed=-1), "seed")):
        with pytest.raises(meridian.InputError) as e:
            call()
        assert e.value.field == field


def test_numbers_and_flags_give_a_meridian_error():
    # before: ValueError ("could not convert string to float"), pybind11's TypeError or cast
    # RuntimeError, or silently: bool("no") is True, format_dms(second_decimals=2.5) gave 2 decimals
    from meridian import angle

    model = mg.synthetic_model(4, 1)
    p1, p2 = maglev.simulate(samples=400, rate_hz=20, seed=3)
    for call, field in ((lambda: angle.parse_deg("10", 5), "unit"),
                        (lambda: angle.format_dms(1.0, 2.5), "second_decimals"),
                        (lambda: angle.format_dms(1.0, 99), "second_decimals"),
                        (lambda: angle.format_ddd_mmss(1.0, 7), "second_decimals"),
                        (lambda: angle.format_direction_dms("x"), "deg"),
                        (lambda: maglev.reduce(p1, p2, scale_A_s_per_rad="x", latitude_deg=35), "scale_A_s_per_rad"),
                        (lambda: maglev.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=True), "latitude_deg"),
                        (lambda: maglev.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=35, lags=2.5), "lags"),
                        (lambda: maglev.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=35, denoise="no"),
                         "denoise"),
                        (lambda: maglev.simulate(rate_hz="x"), "rate_hz"),
                        (lambda: maglev.calibrate("examples/maglev-calibration.csv", latitude_deg=35, alpha="x"),
                         "alpha"),
                        (lambda: dov.simulate(hours="x"), "hours"),
                        (lambda: nav.simulate("/nonexistent", duration_s="x"), "duration_s"),
                        (lambda: nav.process(5), "config"),
                        (lambda: gyro.reduce(5), "source"),
                        (lambda: model.deflection(1.0, 2.0, geoid="no"), "geoid"),
                        (lambda: model.grid([1.0], [2.0], geoid=None), "geoid")):
        with pytest.raises(meridian.InputError) as e:
            call()
        assert e.value.field == field, (field, str(e.value))
    assert angle.format_dms(1.0, np.int64(2)) == angle.format_dms(1.0, 2) == "1°00'00.00\""
    assert angle.format_dms(np.float32(0.5)) == "0°30'00.0\"" and angle.format_dms(np.array(0.5)) == "0°30'00.0\""


def test_dov_latitude_error_in_degrees(source_dir, cli, tmp_path):
    # before: "latitude 1.6580627893946132 rad is beyond ±π/2" for a line given in lat_deg
    line = dov.simulate(hours=0.01, seed=2).to_dict()
    line["lat_deg"][3] = 95.0
    with pytest.raises(meridian.InputError) as e:
        dov.process(line)
    assert e.value.field == "lat_deg[3]"
    # the CLI's reader of a line file says the same of the same value
    cli("dov", "simulate", "--hours", 0.01, "--seed", 2, "--out", tmp_path / "l.csv", "--config", tmp_path / "c.yaml")
    rows = (tmp_path / "l.csv").read_text().splitlines(keepends=True)
    first = next(i for i, r in enumerate(rows) if not r.startswith("#")) + 1
    cells = rows[first + 3].split(",")
    cells[1] = "95"
    rows[first + 3] = ",".join(cells)
    (tmp_path / "l.csv").write_text("".join(rows))
    ref = cli("dov", "process", tmp_path / "c.yaml", "-q", check=False)
    assert ref.returncode != 0
    assert e.value.message == "latitude 95° is beyond ±90°" and e.value.message in ref.stderr
    assert "rad" not in str(e.value)
    line["lat_deg"][3] = -90.5
    with pytest.raises(meridian.InputError, match=r"^lat_deg\[3\]: latitude -90.5° is beyond ±90°$"):
        dov.process(line)


def test_module_namespaces_hold_their_all_only():
    # before: meridian.gravity.np, meridian.nav.os, meridian.dov.json, meridian.maglev.Table, …
    modules = [meridian, meridian.angle, meridian.dov, meridian.errors, meridian.gravity, meridian.gyro,
               meridian.maglev, meridian.nav, meridian.dask]
    for m in modules:
        public = {k for k, v in vars(m).items() if not k.startswith("_")}
        if m is meridian:  # a submodule becomes an attribute of the package once imported
            public = {k for k in public if not (isinstance(vars(m)[k], types.ModuleType)
                                                and vars(m)[k].__name__ == f"meridian.{k}")}
        assert public <= set(m.__all__), f"{m.__name__} leaks {sorted(public - set(m.__all__))}"
        assert all(hasattr(m, k) for k in m.__all__), m.__name__


# --- dict inputs ---

def nav_dict(source_dir, relative_to=None):
    """The scenario's configuration as yaml.safe_load reads it, its files relative to
    `relative_to` (absolute when None), with numpy numbers in it."""
    config = yaml.safe_load((source_dir / NAV).read_text())
    for key in ("dr", "stations", "lops", "truth"):
        p = (source_dir / NAV).parent / config[key]
        config[key] = str(p.relative_to(relative_to)) if relative_to else p
    config["threshold_m"] = np.int64(config["threshold_m"])
    config["initial"] = {k: np.float64(v) for k, v in config["initial"].items()}
    config["bias_sigma_m_s"] = np.array(config["bias_sigma_m_s"])     # a 0-d array
    return config


def test_nav_process_takes_a_dict(source_dir, nav_run, monkeypatch):
    # before: os.fspath(dict) raised TypeError
    _, ref = nav_run
    r = nav.process(nav_dict(source_dir))
    assert r.to_dict() == ref
    monkeypatch.chdir(source_dir)   # relative file names from the current directory
    r = nav.process(nav_dict(source_dir, relative_to=source_dir))
    assert r.to_dict() == ref and r.tracks.rts.x_m.shape == (361,)
    bad = nav_dict(source_dir)
    bad["thresold_m"] = 100
    with pytest.raises(meridian.InputError) as e:
        nav.process(bad)
    assert e.value.file == "<dict>" and e.value.field == "thresold_m"
    with pytest.raises(meridian.InputError) as e:
        nav.process({"dr": "missing.csv", "stations": 3 + 4j})
    assert e.value.field == "stations" and "complex" in e.value.message


def test_gyro_dict_with_numpy_values(source_dir):
    # before: TypeError (np.int64, arrays not JSON serialisable); .file a deleted temporary path
    path = source_dir / "examples/nontracking-noisy.yaml"
    ref = gyro.reduce(path).to_dict()
    book = yaml.safe_load(path.read_text())
    book["instrument"]["accuracy_class_arcsec"] = np.int64(book["instrument"]["accuracy_class_arcsec"])
    converted = 0
    for d in book["determinations"]:
        d["period_s"] = np.int32(d["period_s"])
        d["reversals_div"] = np.asarray(d["reversals_div"])
        for c in d["crossings"]:
            c["times_s"], c["level_div"] = np.asarray(c["times_s"]), np.int64(c["level_div"])
            converted += 1
    assert converted > 0
    r = gyro.reduce(book)
    assert r.file == "<dict>"
    got = r.to_dict()
    got.pop("file"), ref.pop("file")
    assert got == ref


def test_gyro_dict_with_a_yaml_date(source_dir):
    # before: TypeError: Object of type date is not JSON serializable
    text = (source_dir / "examples/campaign.yaml").read_text()
    dated = yaml.safe_load(text + "\nrecord: {observer: Wang, date: 2026-11-28}\n")
    assert dated["record"]["date"] == datetime.date(2026, 11, 28)
    quoted = yaml.safe_load(text + "\nrecord: {observer: Wang, date: \"2026-11-28\"}\n")
    a, b = gyro.campaign(dated).to_dict(), gyro.campaign(quoted).to_dict()
    assert a == b and json.dumps(a).count("2026-11-28") >= 1


def test_dov_options_take_numpy_numbers():
    line = dov.simulate(hours=0.02, seed=2)
    a = dov.process(line, sigma_model_arcsec=np.int64(3), sigma_obs_arcsec=np.float32(0.5))
    b = dov.process(line, sigma_model_arcsec=3, sigma_obs_arcsec=0.5)
    assert a.to_dict() == b.to_dict() and math.isfinite(a.rms_arcsec.smoothed.xi)
