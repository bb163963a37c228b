"""docs/python.md's tour runs as written: its ```python blocks, in order, in one
namespace, from the repository root."""

import re


def test_the_tour_runs_as_written(source_dir, monkeypatch, capsys):
    text = (source_dir / "docs" / "python.md").read_text(encoding="utf-8")
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    assert len(blocks) >= 5
    monkeypatch.chdir(source_dir)
    namespace = {"__name__": "__tour__"}
    for i, code in enumerate(blocks):
        exec(compile(code, f"docs/python.md block {i + 1}", "exec"), namespace)
    out = capsys.readouterr().out
    # The values the docs quote in comments.
    for quoted in ["xi = -0.344″  eta = 1.212″  N = -11.142 m", "all 359.974 3.46",
                   "['determinations', 'file', 'notes', 'torsion_ratio']", "157.35 123.75833333333334",
                   "<meridian.gravity.GravityModel 'synth360s1' degree 360>", "(3, 5) float64", "(7, 9)",
                   "lat_deg[1, 0] | latitude 95 deg is outside [-90, 90]", "<dict> station.latitude_deg",
                   "-0°00'16.2\" 359°00'00.0\"", "True",
                   "358.8542 0.2 [6, 7, 8, 9, 10]", "1800 (4000,)", "(4000,) float64", "413 8000.0",
                   "(901, 3, 3)", "901 ['filtered', 'model', 'smoothed']", "['ekf', 'rts'] 6.81",
                   "(361,) 1800.0", "121", "True 590.9",
                   "Result(cov_xy_m2=-1.37182497799293, sigma_x_m=10.714924183654398,", "7 white-noise ['white-noise', 'c-exponential']"]:
        assert quoted in out, quoted
