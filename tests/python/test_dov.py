"""meridian.dov against the CLI: the simulated line against `dov simulate`'s CSV, the summary
against `dov process --json` and the profile against its -o CSV, from the configuration and
from arrays; bad input."""

import json

import numpy as np
import pytest

import meridian
from meridian import dov

SIM = {"hours": 0.05, "rate_hz": 1.0, "seed": 3, "speed_m_s": 4.0}
SIM_ARGS = ["--hours", 0.05, "--rate-hz", 1, "--seed", 3, "--speed-m-s", 4]


@pytest.fixture(scope="module")
def line_files(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("dov")
    cli("dov", "simulate", *SIM_ARGS, "--out", d / "line.csv", "--config", d / "dov.yaml")
    return d


def test_simulate_matches_the_cli(line_files, read_csv):
    ref = read_csv(line_files / "line.csv")
    line = dov.simulate(**SIM)
    assert len(line) == len(ref)
    for name in ["time_s", "lat_deg", "lon_deg", "height_m", "speed_m_s", "model_eta_arcsec", "model_xi_arcsec",
                 "truth_eta_arcsec", "truth_xi_arcsec"]:
        np.testing.assert_array_equal(line[name], ref[name], err_msg=name)  # 17 digits in the CSV
    for prefix in ("lgu", "ins"):
        m = line[f"{prefix}_body_to_nav"]
        assert m.shape == (len(ref), 3, 3)
        for i in range(3):
            for j in range(3):
                np.testing.assert_array_equal(m[:, i, j], ref[f"{prefix}_{i + 1}{j + 1}"])


def test_process_matches_the_cli_from_the_configuration_and_from_arrays(cli, read_csv, line_files, tmp_path):
    config = line_files / "dov.yaml"
    ref = json.loads(cli("dov", "process", config, "--json", "-q", "-o", tmp_path / "profile.csv").stdout)
    profile = read_csv(tmp_path / "profile.csv")
    r = dov.process(config)
    assert r.to_dict() == ref
    assert r.epochs == ref["epochs"] == len(r.profile)
    assert list(r.profile.keys()) == list(profile.dtype.names)
    for name in profile.dtype.names:  # the CSV has 10 significant digits
        np.testing.assert_allclose(r.profile[name], profile[name], rtol=6e-10, atol=1e-12, err_msg=name)
    # The same line as arrays with the configuration's options: the same summary and profile.
    a = dov.process(dov.simulate(**SIM), sigma_model_arcsec=3, sigma_obs_arcsec=0.5)
    assert a.to_dict() == ref
    for name in profile.dtype.names:
        np.testing.assert_array_equal(a.profile[name], r.profile[name], err_msg=name)


def test_read_line_gives_the_simulated_arrays_from_csv_and_binary(cli, line_files, tmp_path):
    line = dov.simulate(**SIM)
    from_csv = dov.read_line(line_files / "line.csv")
    cli("dov", "convert", line_files / "line.csv", tmp_path / "line.bin")
    from_bin = dov.read_line(tmp_path / "line.bin")
    assert list(from_csv.keys()) == list(line.keys()) == list(from_bin.keys())
    for name in line.keys():
        np.testing.assert_array_equal(from_csv[name], line[name], err_msg=name)  # 17 digits
        np.testing.assert_array_equal(from_bin[name], line[name], err_msg=name)
    # processed from the arrays read back: the summary of the file itself
    ref = json.loads(cli("dov", "process", line_files / "dov.yaml", "--json", "-q").stdout)
    assert dov.process(from_bin, sigma_model_arcsec=3, sigma_obs_arcsec=0.5).to_dict() == ref
    # a column the reader does not use is warned about, as by the CLI
    text = (line_files / "line.csv").read_text().splitlines(keepends=True)
    extra = tmp_path / "extra.csv"
    extra.write_text("".join(text[:2]) + text[2].rstrip("\n") + ",status\n" +
                     "".join(t.rstrip("\n") + ",ok\n" for t in text[3:]))
    with pytest.warns(UserWarning, match="column status not used"):
        np.testing.assert_array_equal(dov.read_line(extra)["time_s"], line["time_s"])
    bad = tmp_path / "bad.csv"
    bad.write_text("".join(text[:5]) + text[5].replace(",", ",x", 1) + "".join(text[6:]))
    with pytest.raises(meridian.ParseError) as e:
        dov.read_line(bad)
    assert e.value.file == str(bad) and e.value.line == 6


def test_transport_rate_matches_the_cli(cli, tmp_path):
    args = ["--hours", 0.05, "--seed", 4, "--speed-m-s", 200, "--transport-rate"]
    cli("dov", "simulate", *args, "--out", tmp_path / "line.csv", "--config", tmp_path / "dov.yaml")
    ref = json.loads(cli("dov", "process", tmp_path / "dov.yaml", "--json", "-q").stdout)
    assert ref["transport_rate"]["baseline_s"] == 10.0 and ref["transport_rate"]["updates"] > 0
    line = dov.simulate(hours=0.05, seed=4, speed_m_s=200, transport_rate=True)
    a = dov.process(line, sigma_model_arcsec=3, sigma_obs_arcsec=0.5, transport_rate=True)
    assert a.to_dict() == ref
    with pytest.raises(meridian.InputError) as e:
        dov.simulate(hours=0.05, transport_rate="false")  # a truthy string is not a flag
    assert e.value.field == "transport_rate"
    # the default simulation is another line (the truth turns without the transport rate)
    plain = dov.simulate(hours=0.05, seed=4, speed_m_s=200)
    assert not np.array_equal(plain["lgu_body_to_nav"], line["lgu_body_to_nav"])


def test_bad_input_raises_the_right_error(line_files, tmp_path):
    line = dov.simulate(hours=0.01, seed=1).to_dict()
    bad = dict(line)
    bad["lat_deg"] = line["lat_deg"].copy()
    bad["lat_deg"][4] = np.nan
    with pytest.raises(meridian.InputError) as e:
        dov.process(bad)
    assert e.value.field == "lat_deg[4]"
    bad = dict(line, ins_body_to_nav=line["ins_body_to_nav"].reshape(-1, 9))
    with pytest.raises(meridian.InputError) as e:
        dov.process(bad)
    assert e.value.field == "ins_body_to_nav"
    bad = dict(line, speed_m_s=line["speed_m_s"][:-1])
    with pytest.raises(meridian.InputError):
        dov.process(bad)
    with pytest.raises(meridian.InputError) as e:
        dov.process(line, zeta=-1)
    assert (e.value.file, e.value.field) == ("<options>", "zeta")
    with pytest.raises(meridian.IoError) as e:
        dov.process(tmp_path / "missing.yaml")
    assert e.value.file == str(tmp_path / "missing.yaml")
    text = (line_files / "line.csv").read_text().splitlines()
    first = next(i for i, t in enumerate(text) if t.startswith("time_s"))
    text[first + 3] = text[first + 3].replace(",", ",x", 1)
    (tmp_path / "line.csv").write_text("\n".join(text) + "\n")
    (tmp_path / "dov.yaml").write_text("line: line.csv\n")
    with pytest.raises(meridian.ParseError) as e:
        dov.process(tmp_path / "dov.yaml")
    assert (e.value.file, e.value.line, e.value.field) == (str(tmp_path / "line.csv"), first + 4, "lat_deg")
    with pytest.raises(meridian.InputError) as e:
        dov.simulate(latitude_deg=95)
    assert e.value.field == "latitude_deg"
