"""meridian.gyro against the CLI's --json output on the same files, from files and dicts;
meridian.angle."""

import json
import math

import pytest
import yaml

import meridian
from meridian import angle, gyro


def cli_json(cli, *args):
    return json.loads(cli(*args, "--json").stdout)


@pytest.mark.parametrize("example", ["tracking.yaml", "nontracking-noisy.yaml", "spec-scenario-2.yaml"])
def test_reduce_matches_the_cli_from_a_file_and_a_dict(cli, source_dir, example):
    path = source_dir / "examples" / example
    ref = cli_json(cli, "gyro", "reduce", path)
    r = gyro.reduce(path)
    assert r.to_dict() == ref
    assert r.determinations[0].north_reading_deg == ref["determinations"][0]["north_reading_deg"]
    d = gyro.reduce(yaml.safe_load(path.read_text()))
    expected = dict(ref)
    expected.pop("file")
    got = d.to_dict()
    got.pop("file")
    assert got == expected


def test_campaign_matches_the_cli(cli, source_dir):
    path = source_dir / "examples" / "campaign.yaml"
    assert gyro.campaign(path).to_dict() == cli_json(cli, "gyro", "campaign", path)


def test_stochastic_matches_the_cli_from_a_file_and_a_dict(cli, source_dir):
    path = source_dir / "examples" / "tracking.yaml"
    ref = cli_json(cli, "gyro", "stochastic", path)
    r = gyro.stochastic(path)
    assert r.to_dict() == ref
    assert len(r.series) >= 1
    recommended = [m for m in r.series[0].models if m.recommended]
    assert len(recommended) == 1 and recommended[0].name == r.series[0].recommended
    got = gyro.stochastic(yaml.safe_load(path.read_text())).to_dict()
    assert got["series"] == ref["series"]


def test_stochastic_refuses_a_book_without_a_long_enough_series(source_dir):
    content = yaml.safe_load((source_dir / "examples" / "tracking.yaml").read_text())
    for d in content["determinations"]:
        if "reversals" in d:
            d["reversals"] = d["reversals"][:5]
    with pytest.raises(meridian.InputError):
        gyro.stochastic(content)


def test_results_are_read_only_views(source_dir):
    r = gyro.reduce(source_dir / "examples" / "tracking.yaml")
    with pytest.raises(AttributeError):
        r.file = "x"
    with pytest.raises(AttributeError):
        r.no_such_key
    d = r.to_dict()
    d["file"] = "changed"
    assert r.file != "changed"


def test_errors_name_file_line_and_field(source_dir, tmp_path):
    content = yaml.safe_load((source_dir / "examples" / "tracking.yaml").read_text())
    content["station"]["latitude_deg"] = 95.0
    with pytest.raises(meridian.InputError) as e:
        gyro.reduce(content)
    assert e.value.file == "<dict>" and e.value.line is None
    assert e.value.field == "station.latitude_deg"
    # The same from a file: its name and line.
    f = tmp_path / "bad.yaml"
    f.write_text("instrument:\n  scale_value_arcsec: 600\nstation:\n  latitude_deg: 95\ndeterminations: []\n")
    with pytest.raises(meridian.InputError) as e:
        gyro.reduce(f)
    assert e.value.file == str(f) and e.value.line == 4 and e.value.field == "station.latitude_deg"
    with pytest.raises(meridian.Error) as e:
        gyro.reduce(tmp_path / "missing.yaml")
    assert e.value.file == str(tmp_path / "missing.yaml")


def test_angles():
    assert angle.parse_deg("157°21'00\"") == pytest.approx(157.35, abs=1e-12)
    assert angle.parse_deg("-0 01 16.2") == pytest.approx(-(1 / 60 + 16.2 / 3600), abs=1e-12)
    assert angle.parse_deg("123.4530", "ddd.mmss") == pytest.approx(123 + 45 / 60 + 30 / 3600, abs=1e-12)
    assert angle.parse_deg("174.8333", "gon") == pytest.approx(174.8333 * 0.9, abs=1e-12)
    assert angle.format_dms(157.35) == "157°21'00.0\""
    assert angle.format_dms(-0.0045, 2, symbols=False) == "-0 00 16.20"
    assert angle.format_direction_dms(-1.0) == "359°00'00.0\""
    assert angle.format_ddd_mmss(123 + 45 / 60 + 30.5 / 3600) == "123.45305"
    assert angle.format_dms(math.nan) == "nan"
    for text, unit in [("12:75:00", "dms"), ("nan", "dms"), ("123.4599", "ddd.mmss"), ("1", "furlong")]:
        with pytest.raises(meridian.ParseError):
            angle.parse_deg(text, unit)
