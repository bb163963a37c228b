#!/usr/bin/env bash
# Runs every command of a built `meridian` (and the Python package, when built) on the bundled
# examples and, when present, on ../shared/cases and ../shared/data, and keeps what each run
# printed and wrote: stdout, stderr, the exit code and every output file, one folder per run.
#
#   scripts/snapshot-outputs.sh BUILD_DIR OUT_DIR
#   diff -r OUT_DIR_BEFORE OUT_DIR_AFTER
#
# For refactors that promise byte-identical outputs (docs/architecture.md): snapshot the build of
# the commit before, then of the change, and compare. It is a developer's tool, not a test: a
# test compares with independent references, never with the code's own earlier output.
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 BUILD_DIR OUT_DIR" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
M="$build/meridian"
[ -x "$M" ] || { echo "$M: not built" >&2; exit 2; }
rm -rf "$2" && mkdir -p "$2"
out=$(cd "$2" && pwd)
shared="$root/../shared"
# The source tree the build was configured from (its examples are compiled into `meridian demo`).
src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt")
cd "$root"
export MERIDIAN_PROGRESS_DELAY_S=1000

# run NAME ARGS…: runs `meridian ARGS…` in a fresh working folder $out/NAME, whose files are
# what the run wrote (the paths in ARGS are relative to the repository root or absolute; W stands
# for the working folder).
run() {
  local name=$1; shift
  local w="$out/$name"
  mkdir -p "$w"
  local args=()
  for a in "$@"; do args+=("${a//@W@/$w}"); done
  (cd "$root" && "$M" "${args[@]}" > "$w/stdout" 2> "$w/stderr"; echo $? > "$w/rc")
  normalise "$w"
}
# The same text in every snapshot: the folders' paths (this run's, the snapshot's, the source
# trees of this script and of the build) and wall-clock times. NetCDF files become their ncdump.
normalise() {
  local f
  for f in $(find "$1" -type f); do
    case "$f" in
      *.nc) ncdump "$f" > "$f.cdl" 2> /dev/null && rm -f "$f"; f="$f.cdl" ;;
      *.bin|*.gtx|*.cof|*.pgm) continue ;;
    esac
    sed -i -E "s|$1|W|g; s|$out|OUT|g; s|$root|ROOT|g; s|$src|ROOT|g; s|\"elapsed_s\": [0-9.e+-]+|\"elapsed_s\": T|; s|(thread\(s\) over [a-z]+), [0-9.]+ s|\1, T s|" "$f"
  done
}
runpy() {
  local name=$1 code=$2
  local w="$out/$name"
  mkdir -p "$w"
  (cd "$root" && PYTHONPATH="$build/python" W="$w" /usr/bin/python3 -c "$code" > "$w/stdout" 2> "$w/stderr"
   echo $? > "$w/rc")
  normalise "$w"
}

# --- gyro
for f in spec-scenario-2 tracking nontracking-noisy campaign; do
  [ $f = campaign ] && continue
  run gyro-reduce-$f gyro reduce examples/$f.yaml
  run gyro-reduce-$f-json gyro reduce examples/$f.yaml --json -o @W@/out.json --report @W@/r.html
done
run gyro-transit-factor gyro transit-factor examples/transit-factor.yaml
run gyro-transit-factor-json gyro transit-factor examples/transit-factor.yaml --json
run gyro-campaign gyro campaign examples/campaign.yaml
run gyro-campaign-json gyro campaign examples/campaign.yaml --json --strict -o @W@/c.json --report @W@/c.html
run gyro-stochastic-tracking gyro stochastic examples/tracking.yaml --report @W@/s.html
run gyro-stochastic-tracking-json gyro stochastic examples/tracking.yaml --json
run gyro-stochastic-campaign gyro stochastic examples/campaign.yaml
for k in campaign reduce; do run gyro-template-$k gyro template --kind $k -o @W@/t.yaml; done
run gyro-simulate-nt gyro simulate --mode non-tracking --seed 1 --beta-div 0.4 -o @W@/s.yaml
run gyro-simulate-tr gyro simulate --mode tracking --seed 3 --tracking-reversals 7 --sigma-tracking-arcsec 8
run gyro-simulate-campaign gyro simulate --mode campaign --seed 9 -o @W@/c.yaml
run gyro-orientations-same gyro orientations examples/campaign.yaml examples/campaign.yaml
run gyro-orientations gyro orientations examples/campaign.yaml "$out/gyro-simulate-campaign/c.yaml"
run gyro-orientations-json gyro orientations examples/campaign.yaml "$out/gyro-simulate-campaign/c.yaml" --json
run demo demo --output-dir @W@/demo
# gyro stochastic on every kind of book, its located errors, and the option checks of simulate
run gyro-stochastic-campaign-json gyro stochastic examples/campaign.yaml --json
for f in spec-scenario-2 nontracking-noisy transit-factor; do run gyro-stochastic-$f gyro stochastic examples/$f.yaml; done
sed 's/^\(\s*reversals: \).*/\1[10, 20, 10, 20, 10, 20, 10]/' examples/tracking.yaml > "$out/flat-tracking.yaml"
run err-gyro-stochastic-flat gyro stochastic "$out/flat-tracking.yaml"
sed 's/^\(\s*sigma_reading_arcsec:\).*/\1 -8/' examples/tracking.yaml > "$out/bad-sigma-tracking.yaml"
run err-gyro-stochastic-parse gyro stochastic "$out/bad-sigma-tracking.yaml" --json
run err-gyro-stochastic-missing gyro stochastic "$out/no-such-book.yaml"
{ cat examples/tracking.yaml
  printf '    zero_position:\n      before: {reversals_div: [4.2, -3.7, 3.9, -3.5, 3.7, -3.3, 3.5]}\n'
  printf '      after: {reversals_div: [4.1, -3.6, 3.8, -3.4, 3.6, -3.2]}\n'; } > "$out/zero-runs.yaml"
run gyro-stochastic-zero-runs gyro stochastic "$out/zero-runs.yaml" --json --report @W@/z.html
run gyro-stochastic-zero-runs-text gyro stochastic "$out/zero-runs.yaml"
run gyro-template-bad gyro template --kind other
sed 's/^\(\s*torsion_ratio: 0.3\)$/\1\n  periods: {tracking_s: 400, nontracking_s: 440}/' examples/tracking.yaml > "$out/both-constants.yaml"
run err-gyro-reduce-instrument gyro reduce "$out/both-constants.yaml"
sed 's/latitude_deg: 34.2/latitude_deg: 89.5/' examples/tracking.yaml > "$out/polar-station.yaml"
run err-gyro-stochastic-latitude gyro stochastic "$out/polar-station.yaml"
run gyro-simulate-tr-markov gyro simulate --mode tracking --seed 5 --tracking-reversals 9 --noise markov1 --rho1 0.6 --sigma-initial-arcsec 4 --sigma-tracking-arcsec 6
run gyro-simulate-clamps gyro simulate --mode non-tracking --seed 2 --determinations 3 --clamp "0,0 30,359 30" --quiet
run gyro-simulate-physics gyro simulate --seed 4 --spin-momentum-Nms 0.2 --inertia-kgm2 2e-4 --torsion-Nm-per-rad 1e-4 --latitude-deg 48.1
for bad in "--mode campaign --noise markov1" "--mode campaign --sigma-initial-arcsec 3" "--mode campaign --levels 1,2" \
           "--mode tracking --levels 1,2" "--mode non-tracking --kappa 0.1" "--mode tracking --clamp 0,1" \
           "--clamp 0,1,2" "--clamp x" "--clamp" "--mode other" "--noise pink" "--sigma-initial-arcsec 2" \
           "--mode tracking --noise markov1 --sigma-initial-arcsec -1" "--mode tracking --noise markov2 --rho1 0.5 --rho2 0.6" \
           "--determinations 0" "--centre abc --mode tracking" "--beta-div nan" "--mode tracking --rho1 nan --noise markov1"; do
  n=$(echo "$bad" | tr -c 'a-z0-9\n' - | tr -s - | sed 's/^-//; s/-$//')
  run err-gyro-simulate-$n gyro simulate $bad
done
if [ -d "$shared/cases" ]; then
  for f in "$shared"/cases/gyro-field/*.yaml "$shared"/cases/gyro-field/crew-mistakes-2/*.yaml; do
    n=$(basename "$(dirname "$f")")-$(basename "$f" .yaml)
    run case-campaign-$n gyro campaign "$f" --strict
    run case-campaign-$n-json gyro campaign "$f" --json --report @W@/r.html
  done
  c2=$shared/cases/gyro-field/crew-mistakes-2
  run case-orientations gyro orientations "$c2/job.yaml" "$c2/m5a.yaml" --json
  run case-orientations-same gyro orientations "$c2/job.yaml" "$c2/m2a.yaml"
  for f in "$shared"/cases/gyro-stochastic/*.yaml; do
    n=$(basename "$f" .yaml)
    run case-stochastic-$n gyro stochastic "$f"
    run case-stochastic-$n-json gyro stochastic "$f" --json --report @W@/r.html
  done
fi

# --- gravity
gm=""
[ -f "$shared/data/gravity/egm96.egm" ] && gm="$shared/data/gravity/egm96.egm"
run gravity-synth gravity synth-model --degree 24 --seed 3 --out @W@/syn
syn="$out/gravity-synth/syn.egm"
printf 'lat,lon,h\n30,120,0\n-45.5,-70.25,1200\n89.9,10,0\n0,0,0\n' > "$out/points.csv"
for m in "$syn" $gm "$shared/data/gravity/GGM05S.gfc"; do
  [ -f "$m" ] || continue
  n=$(basename "$m" | tr . -)
  run gravity-point-$n gravity point --model "$m" 30.5 120.25 100
  run gravity-point-$n-json gravity point --model "$m" 30.5 120.25 --json
  run gravity-points-$n gravity points --model "$m" --input "$out/points.csv" -o @W@/p.csv --report @W@/p.html
  run gravity-points-stdout-$n gravity points --model "$m" --input "$out/points.csv" --track-tolerance-arcsec 0.01
  run gravity-grid-csv-$n gravity grid --model "$m" --region 100/110/20/25 --spacing 1d -o @W@/g.csv --json
  run gravity-grid-nc-$n gravity grid --model "$m" --region 100/110/20/25 --spacing 1d -r --quantities xi,eta,geoid,anomaly -o @W@/g.nc
  run gravity-grid-gtx-$n gravity grid --model "$m" --region 0/360/-90/90 --spacing 10d --quantities geoid -o @W@/g.gtx
  run gravity-grid-par-$n gravity grid --model "$m" --region 100/107/20/24.9 --spacing 0.7d --path parallel -o @W@/g.csv
done
if [ -d "$shared/cases/geoid-grids" ]; then
  for g in "$shared"/cases/geoid-grids/*.gtx; do
    n=$(basename "$g" .gtx)
    run geoid-grid-$n gravity geoid-grid --grid "$g" 10 10
    run geoid-grid-$n-json gravity geoid-grid --grid "$g" 10 10 --json --interpolation bilinear
  done
fi
run gravity-geoid-own gravity geoid-grid --grid "$out/gravity-grid-gtx-syn-egm/g.gtx" 12.5 33 --json

# --- maglev
run maglev-reduce maglev reduce examples/maglev-disturbed.csv --scale 8000 --latitude 35
run maglev-reduce-json maglev reduce examples/maglev-disturbed.csv --scale 8000 --latitude 35 --json -o @W@/r.json --report @W@/r.html
run maglev-calibrate maglev calibrate examples/maglev-calibration.csv --latitude 35
run maglev-calibrate-json maglev calibrate examples/maglev-calibration.csv --latitude 35 --json -o @W@/cal.json
run maglev-reduce-cal maglev reduce examples/maglev-disturbed.csv --calibration "$out/maglev-calibrate-json/cal.json" --latitude 35
run maglev-denoise maglev denoise examples/maglev-disturbed.csv -o @W@/d.csv
run maglev-simulate maglev simulate --alpha1=1.1 --samples=500 --seed=3 --out @W@/s
run maglev-simulate-cal maglev simulate --calibration-azimuths=-3,0,3 --seed=4 --out @W@/c
if [ -d "$shared/cases/maglev-field" ]; then
  d=$shared/cases/maglev-field
  run case-maglev-drift maglev reduce "$d/continuous-drift.csv" --scale 8000 --latitude 35 --json
  run case-maglev-settling maglev reduce "$d/settling-1.csv" "$d/settling-2.csv" --scale 8000 --latitude 35
  run case-maglev-jump maglev reduce "$d/jump-28-1.csv" "$d/jump-28-2.csv" --scale 8000 --latitude 35 --json
  for c in cal-F-example cal_gon_clean; do run case-maglev-$c maglev calibrate "$d/$c.csv" --latitude 35 --json; done
fi

# --- dov
run dov-simulate dov simulate --hours 0.05 --rate-hz 2 --seed 4 --out @W@/line.csv --config @W@/dov.yaml
run dov-simulate-bin dov simulate --hours 0.05 --rate-hz 2 --seed 4 --binary --out @W@/line.bin
w=$out/dov-simulate
run dov-process dov process "$w/dov.yaml" -o @W@/profile.csv --report @W@/r.html
run dov-process-json dov process "$w/dov.yaml" --json
run dov-convert dov convert "$w/line.csv" @W@/line.bin
run dov-convert-back dov convert "$out/dov-convert/line.bin" @W@/line.csv

# --- nav
for s in A B C D; do run nav-simulate-$s nav simulate --scenario $s --seed 2 --out @W@/job --fixes-every-s 120; done
run nav-process-c nav process examples/nav-scenario-c/nav.yaml
run nav-process-c-all nav process examples/nav-scenario-c/nav.yaml --json -o @W@/t.csv --rejected @W@/rej.csv --report @W@/r.html
run nav-process-c-geojson nav process examples/nav-scenario-c/nav.yaml --geojson @W@/t.geojson
for s in A D; do
  run nav-process-$s nav process "$out/nav-simulate-$s/job/nav.yaml" --method ekf -o @W@/t.csv --report @W@/r.html
done
if [ -d "$shared/data/nmea" ]; then
  run nav-nbp1406 nav process examples/nav-nbp1406.yaml --json --report @W@/r.html -o @W@/t.csv --geojson @W@/t.geojson --rejected @W@/rej.csv
  run nav-nbp1406-text nav process examples/nav-nbp1406.yaml --method sequential-bias-I -o @W@/t.csv
  for f in "$shared"/data/nmea/*.nmea; do
    run nav-inspect-$(basename "$f" .nmea) nav inspect "$f"
    run nav-inspect-$(basename "$f" .nmea)-json nav inspect "$f" --json
  done
fi
if [ -d "$shared/cases/nav-field" ]; then
  run case-nav-divergence nav process "$shared/cases/nav-field/divergence-bias-1.1/nav.yaml" --json --report @W@/r.html
  run case-nav-line-noise nav inspect "$shared/cases/nav-field/line-noise.nmea"
fi

# --- errors: the located messages and exit codes
printf 'lat,lon\n30,120\n95,0\n' > "$out/bad-points.csv"
run err-gravity-points gravity points --model "$syn" --input "$out/bad-points.csv"
sed 's/^\(\s*period_s:\).*/\1 -3/' examples/tracking.yaml > "$out/bad-tracking.yaml"
run err-gyro-reduce gyro reduce "$out/bad-tracking.yaml"
awk 'NR==12{$0="1,2,3"}1' examples/maglev-disturbed.csv > "$out/bad-maglev.csv"
run err-maglev maglev reduce "$out/bad-maglev.csv" --scale 8000 --latitude 35
awk -F, 'NR==8{$3="x"}1' OFS=, examples/nav-scenario-c/dr.csv > "$out/bad-dr.csv"
sed "s|dr.csv|$out/bad-dr.csv|" examples/nav-scenario-c/nav.yaml > "$out/bad-nav.yaml"
run err-nav nav process "$out/bad-nav.yaml"
awk -F, 'NR==30{$5="nan"}1' OFS=, "$w/line.csv" > "$out/bad-line.csv"
sed "s|line.csv|$out/bad-line.csv|" "$w/dov.yaml" > "$out/bad-dov.yaml"
run err-dov dov process "$out/bad-dov.yaml"
awk -F, 'NR==30{$5="-3"}1' OFS=, "$w/line.csv" > "$out/bad-line2.csv"
sed "s|line.csv|$out/bad-line2.csv|" "$w/dov.yaml" > "$out/bad-dov2.yaml"
run err-dov-speed dov process "$out/bad-dov2.yaml"
awk -F, 'NR==30{$2="95"}1' OFS=, "$w/line.csv" > "$out/bad-line3.csv"
sed "s|line.csv|$out/bad-line3.csv|" "$w/dov.yaml" > "$out/bad-dov3.yaml"
run err-dov-lat dov process "$out/bad-dov3.yaml" --json
sed "s|^\(sigma_obs_arcsec:\).*|\1 -1|" "$w/dov.yaml" > "$out/dov-bad-sigma.yaml"
run err-dov-config dov process "$out/dov-bad-sigma.yaml"
c=examples/nav-scenario-c
for k in "sigma_speed_m_s: -1" "initial: {x_m: 7.49, y_m: 1.36, sigma_m: 0}" "segment_s: 0" "projection: {central_meridian_deg: 500}"; do
  key=${k%%:*}
  { grep -v "^$key:" $c/nav.yaml | sed "s|^\(dr\|stations\|lops\|truth\): \(.*\)|\1: $root/$c/\2|"; echo "$k"; } > "$out/nav-$key.yaml"
  run err-nav-$key nav process "$out/nav-$key.yaml"
done

# --- the Python package, when built
if [ -d "$build/python/meridian" ]; then
  runpy py-gyro 'import meridian.gyro as g, json; print(json.dumps(g.reduce("examples/tracking.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-stochastic 'import meridian.gyro as g, json; print(json.dumps(g.stochastic("examples/tracking.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-stochastic-campaign-err 'import meridian.gyro as g; g.stochastic("examples/campaign.yaml")'
  runpy py-stochastic-dict-err 'import meridian.gyro as g; g.stochastic({"instrument": {"scale_value_arcsec": 600, "torsion_ratio": 0.3}, "station": {"latitude_deg": 34}, "determinations": [{"mode": "tracking", "reversals": ["358 52 32", "1 32 16", "358 52 48", "1 32 03", "358 53 05", "1 31 43"], "sigma_reading_arcsec": -8}]})'
  runpy py-reduce-dict-err 'import meridian.gyro as g; g.reduce({"instrument": {"scale_value_arcsec": 600}, "determinations": []})'
  runpy py-campaign 'import meridian.gyro as g, json; print(json.dumps(g.campaign("examples/campaign.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-maglev 'import meridian.maglev as m, json; print(json.dumps(m.reduce_files("examples/maglev-disturbed.csv", scale_A_s_per_rad=8000, latitude_deg=35).to_dict(), sort_keys=True, default=str))'
  runpy py-dov "import meridian.dov as d, json, os; r=d.process(os.environ['W']+'/../dov-simulate/dov.yaml'); print(json.dumps(r.to_dict(), sort_keys=True, default=str)[:200000])"
  runpy py-nav 'import meridian.nav as n, json; print(json.dumps(n.process("examples/nav-scenario-c/nav.yaml").to_dict(), sort_keys=True, default=str)[:200000])'
  runpy py-gravity "import meridian.gravity as g, numpy as np; m=g.GravityModel.open('$syn'); print(repr(m.deflection(np.array([10.,20.]), np.array([30.,40.]))))"
fi
for f in "$out"/*.*; do normalise "$f"; done
echo "snapshot: $(ls -d "$out"/*/ | wc -l) runs in $out"
