#!/usr/bin/env bash
# Regenerates the seed corpora in tests/fuzz/corpus/ from examples/ and from
# files the CLI writes (a synthetic degree-4 model), plus tiny grids and point
# files made here. Usage: tests/fuzz/make_seeds.sh [path/to/meridian]
set -euo pipefail
cd "$(dirname "$0")"
exe=${1:-../../build/meridian}
c=corpus
rm -rf "$c" && mkdir -p "$c"/{fuzz_gyro_reduce,fuzz_gyro_campaign,fuzz_icgem,fuzz_egm,fuzz_grid_gtx,fuzz_grid_pgm,fuzz_points_csv,fuzz_dov_line,fuzz_dov_binary,fuzz_nmea,fuzz_nav_csv}
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT
for f in tracking nontracking-noisy spec-scenario-2 transit-factor; do cp ../../examples/$f.yaml $c/fuzz_gyro_reduce/; done
cp ../../examples/campaign.yaml $c/fuzz_gyro_campaign/
# The same books as JSON (the readers take JSON as is).
python3 - "$c" <<'PY'
import json, sys, yaml
c = sys.argv[1]
for src, dst in [("../../examples/tracking.yaml", "fuzz_gyro_reduce/tracking.json"),
                 ("../../examples/campaign.yaml", "fuzz_gyro_campaign/campaign.json")]:
    with open(src) as f:
        doc = yaml.safe_load(f)
    with open(f"{c}/{dst}", "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
PY
"$exe" gravity synth-model --degree 4 --seed 1 --out "$tmp/s4" > /dev/null
cp "$tmp/s4.gfc" $c/fuzz_icgem/synth4.gfc
{ cat "$tmp/s4.egm"; printf '\n@@COF@@\n'; cat "$tmp/s4.egm.cof"; } > $c/fuzz_egm/synth4.egm-and-cof
python3 - "$c" <<'PY'
import struct, sys
c = sys.argv[1]
def gtx(path, lat0, lon0, dlat, dlon, rows, cols, f):
    with open(path, "wb") as out:
        out.write(struct.pack(">ddddii", lat0, lon0, dlat, dlon, rows, cols))
        for r in range(rows):
            for k in range(cols):
                out.write(struct.pack(">f", f(lat0 + r * dlat, lon0 + k * dlon)))
plane = lambda la, lo: 20 + 0.8 * (la - 56) - 0.6 * (lo - 21)
gtx(f"{c}/fuzz_grid_gtx/tile.gtx", 56, 21, 0.5, 0.5, 4, 4, lambda la, lo: -88.8888 if (la, lo) == (57.0, 22.0) else plane(la, lo))
gtx(f"{c}/fuzz_grid_gtx/global30-west180.gtx", -90, -180, 30, 30, 7, 12, lambda la, lo: 0.1 * la - 0.05 * lo)
gtx(f"{c}/fuzz_grid_gtx/antimeridian.gtx", -20, 172, 2, 2, 3, 5, lambda la, lo: 10 + 0.1 * la)
# A GeographicLib .pgm: rows from 90 N, columns from 0 E over 360 deg.
rows, cols = 7, 12
with open(f"{c}/fuzz_grid_pgm/global30.pgm", "wb") as out:
    out.write(b"P5\n# Description seed grid\n# Offset -108\n# Scale 0.003\n%d %d\n65535\n" % (cols, rows))
    for r in range(rows):
        for k in range(cols):
            out.write(struct.pack(">H", (r * 977 + k * 131) % 65536))
PY
printf 'lat,lon,h\n10,20,0\n-89.9,0,5000\n45 30 00,-120,100\n' > $c/fuzz_points_csv/header-comma.csv
printf '# comment\r\n56.3;21.2;10.5\r\n\r\n-33 52 10.5;151 12 30;0\r\n' > $c/fuzz_points_csv/semicolon-crlf.csv
printf '0 0\n89.999 539.9 -400\n' > $c/fuzz_points_csv/whitespace.csv
# Deflection-of-the-vertical lines from the simulator: 5 s at 1 Hz with truth, and the same
# without the model columns (a line for a configuration that names a gravity model).
"$exe" dov simulate --hours 0.0014 --rate-hz 1 --seed 1 --out $c/fuzz_dov_line/line-5s.csv > /dev/null
python3 - "$c" <<'PY'
import sys
c = sys.argv[1]
rows = open(f"{c}/fuzz_dov_line/line-5s.csv").read().splitlines()
hdr = next(r for r in rows if not r.startswith("#")).split(",")
drop = {hdr.index("model_eta_arcsec"), hdr.index("model_xi_arcsec")}
out = [r if r.startswith("#") else ",".join(f for i, f in enumerate(r.split(",")) if i not in drop) for r in rows]
open(f"{c}/fuzz_dov_line/no-model-columns.csv", "w").write("\n".join(out) + "\n")
PY
# The same 5 s as binary lines (docs/file-formats.md): with model and truth, and without either.
"$exe" dov simulate --hours 0.0014 --rate-hz 1 --seed 1 --binary --out $c/fuzz_dov_binary/line-5s.bin > /dev/null
"$exe" dov convert $c/fuzz_dov_line/no-model-columns.csv $c/fuzz_dov_binary/no-model.bin 2> /dev/null
# NMEA 0183 logs written here (not copies of ../shared/data): the quirks of real loggers —
# logger stamps, lower-case checksums, proprietary and undecoded types, empty fields, the 1.x
# GLL without checksum, a comment, CR LF, a day change, no final newline.
python3 - "$c" <<'PY'
import sys
c = sys.argv[1]
def s(body, lower=False):
    x = 0
    for ch in body.encode():
        x ^= ch
    return f"${body}*{x:02x}" if lower else f"${body}*{x:02X}"
stamped = [f"2014-08-01T23:59:5{i}.160000Z " + t for i, t in enumerate([
    s("INZDA,235950.17,31,07,2014,,"), s("INGGA,235950.16,6402.3208,S,06203.4560,W,2,09,0.9,4.5,M,20.1,M,3.0,0130"),
    s("INHDT,123.45,T"), s("INVTG,122.9,T,,M,9.8,N,18.1,K,D"), s("PSXN,20,1,0,0,0"),
    s("INGGA,000001.16,6402.3300,S,06203.4400,W,2,09,0.9,4.6,M,20.1,M,3.0,0130"),
    s("HEHDT,218.53,T", lower=True), s("VDVBW,5.1,0.2,A,5.3,0.1,A")])]
open(f"{c}/fuzz_nmea/logger-stamped.nmea", "w").write("\n".join(stamped) + "\n")
yacht = ["# chart plotter", s("GPRMC,120000,A,5231.1000,N,00513.2000,E,5.2,270.0,150610,1.0,W"),
         s("IIHDT,,T"), s("GPGGA,120001,5231.1010,N,00513.1990,E,1,07,1.2,,M,,M,,"),
         s("GPRMC,120000,A,5231.1000,N,00513.2000,E,5.2,270.0,150610,1.0,W"), s("IIXDR,C,19.5,C,AIRTEMP")]
open(f"{c}/fuzz_nmea/yacht-crlf.nmea", "w", newline="").write("\r\n".join(yacht))
open(f"{c}/fuzz_nmea/no-checksum-1x.nmea", "w").write(
    "$GPGLL,2200.097,S,01756.346,W\n$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K\n$GPZDA,000001,01,08,1994,00,00\n")
PY
du -sh $c
# Navigation CSVs from nav simulate (a minute of scenario A with a fix), each prefixed by the
# byte that selects its reader in fuzz_nav_csv (0 DR, 1 stations, 2 LOPs, 3 fixes, 4 truth),
# plus hand-written speed/heading, geographic and hyperbolic records.
"$exe" nav simulate --scenario A --seed 1 --duration-s 60 --fixes-every-s 30 --out "$tmp/nav" > /dev/null
python3 - "$c" "$tmp/nav" <<'PY'
import sys
c, d = sys.argv[1], sys.argv[2]
files = [("dr.csv", 0), ("stations.csv", 1), ("lops.csv", 2), ("fixes.csv", 3), ("truth.csv", 4)]
for name, sel in files:
    open(f"{c}/fuzz_nav_csv/{name}", "wb").write(bytes([sel]) + open(f"{d}/{name}", "rb").read())
extra = [
    (0, "time_s,speed_m_s,heading_deg\n0,5.1,359.5\n1,5.0,0 30 00\n2.5,4.9,1.5\n"),
    (1, "name,lat_deg,lon_deg\nA,52 10 30.5,4.5\nB,-33.9,151.2\n"),
    (2, "time_s,type,station,station2,value,sigma_m,chain\n0,range_difference,A,B,1234.5,20,Loran\n"
        "1,time_difference,A,B,12.5,30,Loran\n2,range,A,,15000,50,\n"),
    (3, "time_s;lat_deg;lon_deg;sigma_x_m;sigma_y_m\r\n0;52.1;4.4;3;4\r\n"),
    (4, "time_s x_m y_m\n0 0 0\n1 1 1\n"),
]
for i, (sel, text) in enumerate(extra):
    open(f"{c}/fuzz_nav_csv/hand-{i}.csv", "wb").write(bytes([sel]) + text.encode())
PY
