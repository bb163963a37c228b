"""meridian.nav against the CLI: `nav simulate`'s files, the summary of `nav process --json`
and the tracks of its -o CSV, from CSV files and from NMEA 0183 logs; bad input."""

import functools
import json
import math

import numpy as np
import pytest

import meridian
from meridian import nav


@pytest.fixture(scope="module")
def simulated(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("nav")
    cli("nav", "simulate", "--scenario", "C", "--seed", 4, "--duration-s", 600, "--fixes-every-s", 120,
        "--out", d / "cli")
    return d


def compare_tracks(cli, read_csv, config, result, methods, tmp_path):
    for method in methods:
        out = tmp_path / f"{method}.csv"
        cli("nav", "process", config, "-q", "-o", out, "--method", method)
        ref = read_csv(out)
        got = result.tracks[method]
        assert list(got.keys()) == list(ref.dtype.names)
        for name in ref.dtype.names:
            expected = ref[name]
            if name.startswith("sigma_bias"):  # a σ the method does not state: NaN, 0 in the CSV
                expected = np.where(expected > 0, expected, np.nan)
            np.testing.assert_array_equal(got[name], expected, err_msg=f"{method} {name}")


def test_simulate_writes_the_cli_files(simulated):
    sim = nav.simulate(simulated / "py", scenario="C", seed=4, duration_s=600, fixes_every_s=120)
    assert sim.files == ["dr.csv", "stations.csv", "lops.csv", "truth.csv", "fixes.csv", "nav.yaml"]
    assert sim.config == str(simulated / "py" / "nav.yaml")
    for name in sim.files:
        assert (simulated / "py" / name).read_bytes() == (simulated / "cli" / name).read_bytes(), name
    assert all(isinstance(i, int) for i in sim.blunders) and sim.settings


def test_process_matches_the_cli(cli, read_csv, simulated, tmp_path):
    config = simulated / "cli" / "nav.yaml"
    ref = json.loads(cli("nav", "process", config, "--json", "-q").stdout)
    r = nav.process(config)
    assert r.to_dict() == ref
    assert list(r.tracks) == ref["method_order"]
    assert r.methods["rts"].rms_m == ref["methods"]["rts"]["rms_m"]
    compare_tracks(cli, read_csv, config, r, ["rts", "sequential-bias-I", "fix-closure"], tmp_path)


def nmea(body):
    return f"${body}*{functools.reduce(lambda a, c: a ^ ord(c), body, 0):02X}\n"


def dm(value, width):
    deg = int(abs(value))
    return f"{deg:0{width}d}{(abs(value) - deg) * 60:07.4f}"


@pytest.fixture(scope="module")
def nmea_job(tmp_path_factory):
    """5 minutes of HDT, VTG and GGA at 1 Hz (logger stamps): a ship at 5 m/s on 60°."""
    d = tmp_path_factory.mktemp("nmea")
    lines, lat, lon = [], 50.0, 5.0
    for k in range(300):
        stamp = f"2014-08-01T10:{k // 60:02d}:{k % 60:02d}.000000Z "
        t = f"10{k // 60:02d}{k % 60:02d}.00"
        lines.append(stamp + nmea(f"HEHDT,{60.0 + 0.5 * math.sin(k / 9):.2f},T"))
        lines.append(stamp + nmea(f"GPVTG,60.0,T,,M,{5.0 * 3600 / 1852:.3f},N,18.0,K"))
        lines.append(stamp + nmea(f"GPGGA,{t},{dm(lat, 2)},N,{dm(lon, 3)},E,1,08,0.9,10.0,M,46.9,M,,"))
        lat += 5.0 * math.cos(math.radians(60)) / 6371000 * 180 / math.pi
        lon += 5.0 * math.sin(math.radians(60)) / (6371000 * math.cos(math.radians(lat))) * 180 / math.pi
    (d / "log.nmea").write_text("".join(lines))
    (d / "nav.yaml").write_text("nmea: {heading: log.nmea, speed: log.nmea, positions: log.nmea, "
                                "speed_sentence: vtg, fix_interval_s: 60, sigma_fix_m: 5}\n")
    return d


def test_process_nmea_matches_the_cli(cli, read_csv, nmea_job, tmp_path):
    config = nmea_job / "nav.yaml"
    ref = json.loads(cli("nav", "process", config, "--json", "-q").stdout)
    r = nav.process(config)
    assert r.to_dict() == ref
    assert "lat_deg" in r.tracks["ekf"] and r.fixes_used > 0
    compare_tracks(cli, read_csv, config, r, ["ekf", "dead-reckoning"], tmp_path)


def test_process_nmea_dict_files_from_the_current_directory(cli, nmea_job, monkeypatch):
    # the nmea block's files in a dict (docs/python.md "Dicts"): relative to the current directory
    ref = json.loads(cli("nav", "process", nmea_job / "nav.yaml", "--json", "-q").stdout)
    monkeypatch.chdir(nmea_job.parent)
    log = f"{nmea_job.name}/log.nmea"
    config = {"nmea": {"heading": log, "speed": log, "positions": log, "speed_sentence": "vtg",
                       "fix_interval_s": np.int64(60), "sigma_fix_m": np.float64(5)}}
    assert nav.process(config).to_dict() == ref
    config["nmea"]["heading"] = "log.nmea"   # not in the current directory: named as resolved from it
    with pytest.raises(meridian.Error) as e:
        nav.process(config)
    assert e.value.file == str(nmea_job.parent / "log.nmea")


def test_inspect_matches_the_cli(cli, nmea_job, tmp_path):
    log = nmea_job / "log.nmea"
    bad = tmp_path / "bad.nmea"
    text = log.read_text().splitlines(keepends=True)
    bad.write_text("".join(text[:20]) + "$GPGGA,garbage*00\n" + "".join(text[20:40]))
    ref = json.loads(cli("nav", "inspect", log, bad, "--json").stdout)
    r = nav.inspect(log, bad)
    assert r.to_dict() == ref
    assert len(r.files) == 2
    with pytest.raises(meridian.Error) as e:
        nav.inspect(tmp_path / "missing.nmea")
    assert e.value.file == str(tmp_path / "missing.nmea")
    with pytest.raises(meridian.InputError):
        nav.inspect()


def test_bad_input_raises_the_right_error(simulated, tmp_path):
    with pytest.raises(meridian.IoError) as e:
        nav.process(tmp_path / "missing.yaml")
    assert e.value.file == str(tmp_path / "missing.yaml")
    src = simulated / "cli"
    for name in ("dr.csv", "stations.csv", "lops.csv", "truth.csv", "fixes.csv"):
        (tmp_path / name).write_bytes((src / name).read_bytes())
    config = (src / "nav.yaml").read_text()
    (tmp_path / "nav.yaml").write_text(config + "threshhold_m: 100\n")
    with pytest.raises(meridian.InputError) as e:
        nav.process(tmp_path / "nav.yaml")
    assert e.value.file == str(tmp_path / "nav.yaml") and e.value.line == len(config.splitlines()) + 1
    (tmp_path / "nav.yaml").write_text(config)
    lops = (tmp_path / "lops.csv").read_text().splitlines()
    header = next(i for i, t in enumerate(lops) if not t.startswith("#"))
    cells = lops[header + 2].split(",")
    names = lops[header].split(",")
    cells[names.index("value")] = "nan"
    lops[header + 2] = ",".join(cells)
    (tmp_path / "lops.csv").write_text("\n".join(lops) + "\n")
    with pytest.raises(meridian.InputError) as e:
        nav.process(tmp_path / "nav.yaml")
    assert (e.value.file, e.value.line) == (str(tmp_path / "lops.csv"), header + 3)
    with pytest.raises(meridian.InputError) as e:
        nav.simulate(tmp_path / "x", scenario="E")
    assert e.value.field == "scenario"
