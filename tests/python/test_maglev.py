"""meridian.maglev against the CLI's --json and CSV output on the same files, denoise against
PyWavelets (pywt.wavedec → pywt.threshold → pywt.waverec) to 1e-10, and bad input."""

import json
import math
import pickle

import numpy as np
import pytest
import pywt

import meridian
from meridian import maglev

REDUCE_ARGS = ["--scale", 8000, "--latitude", 35]


def cli_json(cli, *args):
    return json.loads(cli(*args, "--json").stdout)


def pywt_denoise(x, wavelet, level, mode, threshold):
    coeffs = pywt.wavedec(x, wavelet, mode=mode, level=level)
    sigma = np.median(np.abs(coeffs[-1])) / 0.6745
    lam = sigma * math.sqrt(2.0 * math.log(len(x)))
    coeffs = [coeffs[0]] + [pywt.threshold(d, lam, mode=threshold) for d in coeffs[1:]]
    return pywt.waverec(coeffs, wavelet, mode=mode)[: len(x)]


@pytest.mark.parametrize("n, wavelet, level, mode, threshold", [
    (1000, "db4", 4, "symmetric", "soft"), (777, "db4", 5, "periodization", "hard"),
    (513, "db2", 3, "symmetric", "hard"), (2048, "db10", 6, "periodization", "soft")])
def test_denoise_equals_pywavelets(n, wavelet, level, mode, threshold):
    rng = np.random.default_rng(n)
    x = np.sin(np.linspace(0, 12, n)) + 0.3 * rng.standard_normal(n)
    got = maglev.denoise(x, wavelet=wavelet, level=level, mode=mode, threshold=threshold, rule="universal")
    assert got.shape == x.shape and got.dtype == np.float64
    np.testing.assert_allclose(got, pywt_denoise(x, wavelet, level, mode, threshold), rtol=0, atol=1e-10)


def test_denoise_matches_the_cli_and_reports_its_thresholds(cli, read_csv, tmp_path):
    rng = np.random.default_rng(5)
    x = 1e-3 + 1e-5 * rng.standard_normal(600)
    f = tmp_path / "s.csv"
    np.savetxt(f, np.column_stack([np.arange(600) * 0.05, x]), delimiter=",", fmt="%.17g",
               header="time [s],current [A]", comments="")
    for rule in ("universal", "sure"):
        out = tmp_path / f"d-{rule}.csv"
        cli("maglev", "denoise", f, "--rule", rule, "--threshold", "hard", "-o", out)
        ref = read_csv(out)["current_A"]
        info = maglev.denoise(x, rule=rule, threshold="hard", full=True)
        np.testing.assert_array_equal(info.values, ref)  # the CLI writes 17 digits
        assert info.level == 6 and len(info.thresholds) == 6 and info.noise_sigma > 0
        assert sorted(info.to_dict()) == ["coefficients", "level", "mode", "noise_sigma", "rule", "threshold",
                                          "thresholds", "wavelet", "zeroed"]


def test_reduce_files_and_arrays_match_the_cli(cli, source_dir):
    path = source_dir / "examples" / "maglev-disturbed.csv"
    ref = cli_json(cli, "maglev", "reduce", path, *REDUCE_ARGS)
    r = maglev.reduce_files(path, scale_A_s_per_rad=8000, latitude_deg=35)
    assert r.to_dict() == ref
    assert r.result.north_deg == ref["result"]["north_deg"]
    assert r.series1.kept.dtype == bool and len(r.series1) == ref["position1"]["samples"]
    assert int(r.series1.kept.sum()) == ref["position1"]["kept_samples"]
    # The same series as arrays give the same result; a DMS latitude is read as the CLI does.
    a = maglev.reduce((r.series1.time_s, r.series1.current_A), r.series2, scale_A_s_per_rad=8000,
                      latitude_deg="35 00 00")
    assert a.to_dict() == ref
    np.testing.assert_array_equal(a.series2.cleaned_A, r.series2.cleaned_A)
    # Results and their tables pickle (to cross process boundaries) and stay read-only.
    b = pickle.loads(pickle.dumps(a))
    assert b.to_dict() == ref
    np.testing.assert_array_equal(b.series1.kept, a.series1.kept)
    with pytest.raises(ValueError):
        b.series1.cleaned_A[0] = 0.0


def test_reduce_options_and_the_azimuth_chain_match_the_cli(cli, source_dir):
    path = source_dir / "examples" / "maglev-disturbed.csv"
    ref = cli_json(cli, "maglev", "reduce", path, *REDUCE_ARGS, "--no-denoise", "--target", "45 30 00",
                   "--eta-arcsec", 4.5, "--convergence-deg", 0.3, "--prior-bias", 1.75e-5, "--rule", "sure")
    r = maglev.reduce_files(path, scale_A_s_per_rad=8000, latitude_deg=35, denoise=False, target_deg="45 30 00",
                            eta_arcsec=4.5, convergence_deg=0.3, prior_bias_A=1.75e-5, rule="sure")
    assert r.to_dict() == ref
    assert "azimuth" in ref and "symmetry" in ref


def test_calibrate_matches_the_cli_and_feeds_reduce(cli, read_csv, source_dir, tmp_path):
    table = source_dir / "examples" / "maglev-calibration.csv"
    ref = cli_json(cli, "maglev", "calibrate", table, "--latitude", 35)
    c = maglev.calibrate(table, latitude_deg=35)
    assert c.to_dict() == ref
    stored = tmp_path / "cal.json"
    stored.write_text(json.dumps(c.to_dict()))
    path = source_dir / "examples" / "maglev-disturbed.csv"
    r = maglev.reduce_files(path, calibration=stored, latitude_deg=35, process=False)
    assert r.to_dict() == cli_json(cli, "maglev", "reduce", path, "--calibration", stored, "--latitude", 35,
                                   "--no-process")
    # From arrays: the table's columns as read.
    cols = read_csv(table)
    arrays = dict(zip(["azimuth_deg", "mean1_A", "sigma1_A", "mean2_A", "sigma2_A"], (cols[n] for n in cols.dtype.names)))
    assert maglev.calibrate(arrays, latitude_deg=35).to_dict() == ref


def test_simulate_matches_the_cli(cli, read_csv, tmp_path):
    cli("maglev", "simulate", "--samples=400", "--rate-hz=20", "--ar1-phi=0.5", "--ar1-sigma=2e-6",
        "--burst=2:3:8:1e-3:2e-4:0.5:4", "--seed=9", "--one-file", "--out", tmp_path / "m")
    ref = read_csv(tmp_path / "m.csv")
    p1, p2 = maglev.simulate(samples=400, rate_hz=20, ar1_phi=0.5, ar1_sigma_A=2e-6,
                             bursts=[(2, 3, 8, 1e-3, 2e-4, 0.5, 4)], seed=9)
    for p, k in ((p1, 1), (p2, 2)):
        rows = ref[ref["position"] == k]
        np.testing.assert_array_equal(p.time_s, rows["time_s"])
        np.testing.assert_array_equal(p.current_A, rows["current_A"])
    cli("maglev", "simulate", "--calibration-azimuths=-2,0,2", "--constant-deviation=1e-5", "--seed=4",
        "--out", tmp_path / "c")
    ref = read_csv(tmp_path / "c-calibration.csv")
    t = maglev.simulate_calibration([-2, 0, 2], constant_deviation_A=1e-5, seed=4)
    for name in ["azimuth_deg", "mean1_A", "sigma1_A", "mean2_A", "sigma2_A"]:  # the table's digits
        rtol = 6e-4 if name.startswith("sigma") else 1e-10  # σ with 4 digits, means with 12
        np.testing.assert_allclose(t[name], ref[name], rtol=rtol, atol=1e-13, err_msg=name)


def test_bad_input_raises_the_right_error(source_dir, tmp_path):
    p1, p2 = maglev.simulate(samples=300, seed=2)
    k = {"scale_A_s_per_rad": 8000, "latitude_deg": 35}
    bad = p1.current_A.copy()
    bad[3] = np.nan
    with pytest.raises(meridian.InputError) as e:
        maglev.reduce((p1.time_s, bad), p2, **k)
    assert e.value.field == "position1.current_A[3]"
    with pytest.raises(meridian.InputError) as e:
        maglev.reduce((p1.time_s.reshape(30, 10), p1.current_A), p2, **k)
    assert e.value.field == "position1.time_s"
    with pytest.raises(meridian.InputError) as e:
        maglev.reduce(p1, p2, latitude_deg=35)
    assert e.value.field == "scale_A_s_per_rad"
    for latitude, error in [(95, meridian.InputError), ("35 70 00", meridian.ParseError)]:
        with pytest.raises(error) as e:
            maglev.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=latitude)
        assert e.value.field == "latitude_deg"
    with pytest.raises(meridian.InputError) as e:
        maglev.reduce((p1.time_s[::-1], p1.current_A), p2, **k)
    assert e.value.field == "position1.time_s[1]"
    with pytest.raises(meridian.IoError) as e:
        maglev.reduce_files(tmp_path / "missing.csv", **k)
    assert e.value.file == str(tmp_path / "missing.csv")
    f = tmp_path / "bad.csv"
    f.write_text("time,current,position\n0,1e-3,1\n0.1,x,1\n0,2e-3,2\n")
    with pytest.raises(meridian.ParseError) as e:
        maglev.reduce_files(f, **k)
    assert (e.value.file, e.value.line, e.value.field) == (str(f), 3, "current")
    with pytest.raises(meridian.InputError) as e:
        maglev.denoise([1.0, np.nan, 2.0] * 20)
    assert e.value.field == "series"
    for kwargs, field in [({"level": 12}, "level"), ({"wavelet": "haar"}, "wavelet"), ({"mode": "zero"}, "mode"),
                          ({"level": 0}, "level"), ({"rule": "minimax"}, "rule")]:
        with pytest.raises(meridian.InputError) as e:
            maglev.denoise(np.arange(100.0) % 7, **kwargs)
        assert e.value.field == field
    with pytest.raises(meridian.InputError) as e:
        maglev.denoise(np.zeros((4, 4)))
    assert e.value.field == "series"
    table = {"azimuth_deg": [-1, 0, 1], "mean1_A": [1, 2, 3], "sigma1_A": [1, 1, 1], "mean2_A": [3, 2, 1],
             "sigma2_A": [1, np.nan, 1]}
    with pytest.raises(meridian.InputError) as e:
        maglev.calibrate(table, latitude_deg=35)
    assert e.value.field.startswith("table[1]")
    with pytest.raises(meridian.InputError) as e:
        maglev.calibrate({k: v[:2] for k, v in table.items()}, latitude_deg=35)  # 2 set-ups are too few
    with pytest.raises(meridian.InputError) as e:
        maglev.simulate(samples=10, rate_hz=0)
    assert e.value.field == "rate_hz"
