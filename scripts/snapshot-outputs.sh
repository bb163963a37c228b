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
    sed -i -E "s|$1|W|g; s|$out|OUT|g; s|$root|ROOT|g; s|$src|ROOT|g; s|\"elapsed_s\": [0-9.e+-]+|\"elapsed_s\": T|; s|^(path .*), [0-9.]+ s$|\1, T s|" "$f"
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
# The model's other formats and ways of naming it, truncation, threads.
run gravity-point-syn-gfc gravity point --model "$out/gravity-synth/syn.gfc" -- -33.5 "151 12 36" 20 --max-degree 10
run gravity-point-syn-cof gravity point --model "$out/gravity-synth/syn.egm.cof" 45 -170 --json --threads 1
run gravity-points-quiet-syn gravity points --model "$syn" --input "$out/points.csv" -q -o @W@/p.csv --max-degree 12
run gravity-grid-json-gtx gravity grid --model "$syn" --region d --spacing 30 --quantities geoid -o @W@/g.gtx --json -q
run gravity-grid-all-q gravity grid --model "$syn" --region 10/14/40/43 --spacing 1d --quantities xi,eta,geoid,anomaly,dg_east,dg_north,dg_up -o @W@/g.csv -q
run gravity-grid-fft gravity grid --model "$syn" --region 0/360/-80/80 --spacing 20d/10d --path fft -o @W@/g.nc --json
# Per-node heights from a NetCDF grid at the same nodes (the geoid of a first run, in metres).
"$M" gravity grid --model "$syn" --region 100/104/20/23 --spacing 1d --quantities geoid -o "$out/h.nc" -q > /dev/null 2>&1
run gravity-grid-heights gravity grid --model "$syn" --region 100/104/20/23 --spacing 1d -o @W@/g.csv --height-grid "$out/h.nc?geoid"
run gravity-grid-heights-json gravity grid --model "$syn" --region 100/104/20/23 --spacing 1d -o @W@/g.csv --height-grid "$out/h.nc" --json
run gravity-geoid-own-bilinear gravity geoid-grid --grid "$out/gravity-grid-gtx-syn-egm/g.gtx" -- -89 181 --interpolation bilinear
# Errors of the gravity commands: messages, files and lines named, exit codes.
printf 'not a model\n' > "$out/model.txt"
head -n 40 "$out/gravity-synth/syn.gfc" > "$out/short.gfc"
sed 's/^radius .*/radius -1/' "$out/gravity-synth/syn.gfc" > "$out/badradius.gfc"
cp "$syn" "$out/trunc.egm"; head -c 300 "$syn.cof" > "$out/trunc.egm.cof"
printf 'EGMF-2\n' > "$out/v2.egm"
printf 'P5\n# Offset -100\n4 3\n65535\n' > "$out/short.pgm"
printf 'not a grid' > "$out/grid.txt"
run err-gravity-model-missing gravity point --model no_such_model_xyz 10 10
run err-gravity-model-empty gravity point --model "" 10 10
run err-gravity-model-format gravity point --model "$out/model.txt" 10 10
run err-gravity-gfc-short gravity points --model "$out/short.gfc" --input "$out/points.csv"
run err-gravity-gfc-radius gravity point --model "$out/badradius.gfc" 10 10 --json
run err-gravity-egm-trunc gravity grid --model "$out/trunc.egm" --region 0/10/0/10 --spacing 5 -o @W@/g.csv
run err-gravity-egm-version gravity point --model "$out/v2.egm" 10 10
run err-gravity-point-lat gravity point --model "$syn" 95 10
run err-gravity-point-h gravity point --model "$syn" 10 10 -- -20000
run err-gravity-points-input gravity points --model "$syn" --input "$out/no-such-points.csv"
run err-gravity-points-outdir gravity points --model "$syn" --input "$out/points.csv" -o "$out/no-such-dir/p.csv"
run err-gravity-grid-quantity gravity grid --model "$syn" --region 0/10/0/10 --spacing 5 --quantities xi,rho -o @W@/g.csv
run err-gravity-grid-ext gravity grid --model "$syn" --region 0/10/0/10 --spacing 5 -o @W@/g.tif
run err-gravity-grid-gtx gravity grid --model "$syn" --region 0/10/0/10 --spacing 5 -o @W@/g.gtx
run err-gravity-grid-region gravity grid --model "$syn" --region 0/10/20/10 --spacing 5 -o @W@/g.csv
run err-gravity-grid-fft gravity grid --model "$syn" --region 0/10/0/10 --spacing 7 --path fft -o @W@/g.csv
run err-gravity-grid-heights gravity grid --model "$syn" --region 100/105/20/23 --spacing 1d -o @W@/g.csv --height-grid "$out/h.nc"
run err-gravity-grid-model gravity grid --model no_such_model_xyz --region 0/10/0/10 --spacing 5 -o @W@/g.csv
run err-geoid-grid-ext gravity geoid-grid --grid "$out/grid.txt" 10 10
run err-geoid-grid-pgm gravity geoid-grid --grid "$out/short.pgm" 10 10
run err-geoid-grid-interp gravity geoid-grid --grid "$out/gravity-grid-gtx-syn-egm/g.gtx" 10 10 --interpolation cubic
run err-geoid-grid-lat gravity geoid-grid --grid "$out/gravity-grid-gtx-syn-egm/g.gtx" 91 10
run err-geoid-grid-missing gravity geoid-grid --grid "$out/no-such.gtx" 10 10
if [ -d "$shared/cases/geoid-grids" ]; then
  run err-geoid-grid-outside gravity geoid-grid --grid "$shared/cases/geoid-grids/tile.gtx" 50 50 --json
fi

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
# Every input and option of the maglev runners (constants and calibration files, the chain, the
# processing options, denoise levels, the simulator's bursts) and the errors they locate.
mg=$out/maglev-simulate
printf 'scale_A_s_per_rad: 8000\nscale_sigma_A_s_per_rad: 2.5\nlatitude: "35 00 00"\ncircle_reading1: 12.5\nconstant_deviation_A: 1.75e-5\nconstant_deviation_sigma_A: 1e-7\n' > "$out/maglev-constants.yaml"
run maglev-reduce-config maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-constants.yaml" --json --report @W@/r.html
run maglev-reduce-config-text maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-constants.yaml" --scale 7990 --reading1 "10 00 00" --prior-bias 2e-5
run maglev-reduce-two maglev reduce "$mg/s-1.csv" "$mg/s-2.csv" --scale 8000 --scale-sigma 3 --latitude "35 30 00" --reading1 45 --reading1-sigma-arcsec 2 --target "47 10 00" --target-sigma-arcsec 1.5 --instrument-constant "0 01 30" --instrument-constant-sigma-arcsec 3 --eta-arcsec 4.5 --eta-sigma-arcsec 0.5 --convergence-deg 0.3 --json
run maglev-reduce-two-text maglev reduce "$mg/s-1.csv" "$mg/s-2.csv" --scale 8000 --latitude 35 --target 47 --no-denoise -o @W@/r.txt --report @W@/r.html
run maglev-reduce-noprocess maglev reduce examples/maglev-disturbed.csv --scale 8000 --latitude 35 --no-process --json --report @W@/r.html
run maglev-reduce-options maglev reduce examples/maglev-disturbed.csv --scale 8000 --latitude 35 --segment 100 --alpha 0.01 --lags 5 --wavelet db6 --level 3 --mode periodization --threshold hard --rule sure --json
run maglev-reduce-cal-config maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-constants.yaml" --calibration "$out/maglev-calibrate-json/cal.json" --json
run maglev-denoise-level maglev denoise "$mg/s-1.csv" --wavelet db2 --level 3 --mode periodization --threshold hard --rule sure
run maglev-simulate-burst maglev simulate --alpha1=0.7 --samples=800 --rate-hz=20 --ar1-phi=0.5 --ar1-sigma=2e-6 --drift=1e-9 --burst=1:5:15:2e-3:6e-4:0.5:8 --burst=2:3:9:1e-3:2e-4:0.5:4 --seed=9 --one-file --out @W@/b
run maglev-simulate-cal-full maglev simulate --calibration-azimuths=-3,-1.5,0,1.5,3 --slope-ratio1=1.01 --slope-ratio2=0.99 --best-azimuth=0.11459 --constant-deviation=1.75e-5 --latitude=40 --scale=9000 --samples=2000 --seed=5 --out @W@/c
run maglev-calibrate-report maglev calibrate "$out/maglev-simulate-cal-full/c-calibration.csv" --latitude 40 --nominal-scale 9000 --alpha 0.01 -o @W@/c.txt --report @W@/c.html
awk 'NR<=3{print; next} {print NR-3 ",0.01"}' "$mg/s-1.csv" > "$out/maglev-const.csv"
printf 'time,current\n0,0.01\n1,0.02\n2,0.01\n' > "$out/maglev-short.csv"
printf 'time,current,position\n0,0.01,1\n1,0.02,1\n' > "$out/maglev-one.csv"
printf 'azimuth,mean1,sigma1,mean2,sigma2\n0,1,1,2,1\n0,1.1,1,2.1,1\n' > "$out/maglev-cal-few.csv"
printf 'azimuth,mean1,sigma1,mean2,sigma2\n-1,1,0.1,2,0.1\n0,1,0.1,2,0.1\n1,1,0.1,2,0.1\n' > "$out/maglev-cal-parallel.csv"
printf 'latitude: 35\n' > "$out/maglev-no-k.yaml"
printf 'scale_A_s_per_rad: 8000\n' > "$out/maglev-no-lat.yaml"
printf 'scale_A_s_per_rad: -8000\nlatitude: 35\n' > "$out/maglev-bad-k.yaml"
printf 'scale_A_s_per_rad: 8000\nlatitude: 35\nlattitude: 3\n' > "$out/maglev-typo.yaml"
run err-maglev-const maglev reduce "$out/maglev-const.csv" "$mg/s-2.csv" --scale 8000 --latitude 35
run err-maglev-short maglev reduce "$out/maglev-short.csv" "$mg/s-2.csv" --scale 8000 --latitude 35
run err-maglev-short-one maglev reduce "$out/maglev-short.csv" --scale 8000 --latitude 35
run err-maglev-one-position maglev reduce "$out/maglev-one.csv" --scale 8000 --latitude 35
run err-maglev-alpha1 maglev reduce "$mg/s-1.csv" "$mg/s-2.csv" --scale 10 --latitude 35 --json
run err-maglev-missing maglev reduce "$out/maglev-nothing.csv" --scale 8000 --latitude 35
run err-maglev-no-k maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-no-k.yaml"
run err-maglev-no-lat maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-no-lat.yaml"
run err-maglev-bad-k maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-bad-k.yaml"
run err-maglev-typo maglev reduce examples/maglev-disturbed.csv --config "$out/maglev-typo.yaml"
run err-maglev-cal-missing maglev reduce examples/maglev-disturbed.csv --calibration "$out/maglev-nothing.json" --latitude 35
run err-maglev-latitude maglev reduce examples/maglev-disturbed.csv --scale 8000 --latitude "35 70 00"
run err-maglev-denoise-const maglev denoise "$out/maglev-const.csv" --level 2
run err-maglev-denoise-deep maglev denoise "$mg/s-1.csv" --level 9
run err-maglev-cal-few maglev calibrate "$out/maglev-cal-few.csv" --latitude 35
run err-maglev-cal-parallel maglev calibrate "$out/maglev-cal-parallel.csv" --latitude 35 --json
run err-maglev-cal-latitude maglev calibrate examples/maglev-calibration.csv --latitude 95
run err-maglev-sim-burst maglev simulate --samples 300 --burst 1:500:600:2e-3:6e-4:0.5:8 --out @W@/x
run err-maglev-sim-burst-text maglev simulate --samples 300 --burst 1:5:x --out @W@/x

# --- dov
run dov-simulate dov simulate --hours 0.05 --rate-hz 2 --seed 4 --out @W@/line.csv --config @W@/dov.yaml
run dov-simulate-bin dov simulate --hours 0.05 --rate-hz 2 --seed 4 --binary --out @W@/line.bin
w=$out/dov-simulate
run dov-process dov process "$w/dov.yaml" -o @W@/profile.csv --report @W@/r.html
run dov-process-json dov process "$w/dov.yaml" --json
run dov-convert dov convert "$w/line.csv" @W@/line.bin
run dov-convert-back dov convert "$out/dov-convert/line.bin" @W@/line.csv
# dov: every output path of `dov process` (profile and report to files or standard output, a
# binary line, a line long enough for the report's thinning, a gravity model for eta_G, xi_G),
# `dov convert` both ways with an unread column, and `dov simulate`'s option checks
run dov-process-stdout dov process "$w/dov.yaml" -q -o - --report @W@/r.html
run dov-process-report-stdout dov process "$w/dov.yaml" --json --report -
sed "s|^line: .*|line: $out/dov-simulate-bin/line.bin|" "$w/dov.yaml" > "$out/dov-bin.yaml"
run dov-process-bin dov process "$out/dov-bin.yaml" --json -o @W@/profile.csv
run dov-simulate-long dov simulate --hours 1.2 --rate-hz 2 --seed 5 --transport-rate --out @W@/line.csv --config @W@/dov.yaml
run dov-process-long dov process "$out/dov-simulate-long/dov.yaml" -o @W@/profile.csv --report @W@/r.html
awk -F, '/^#/ {print; next} {s=$1; for (i = 2; i <= NF; i++) if (i != 24 && i != 25) s = s "," $i; print s}' "$w/line.csv" > "$out/dov-nomodel.csv"
{ sed "s|^line: .*|line: $out/dov-nomodel.csv|" "$w/dov.yaml"; echo "gravity_model: {model: $syn, max_degree: 20}"; } > "$out/dov-gm.yaml"
run dov-process-gravity-model dov process "$out/dov-gm.yaml" -o @W@/profile.csv --report @W@/r.html
run dov-process-gravity-model-json dov process "$out/dov-gm.yaml" --json
run dov-simulate-stdout dov simulate --hours 0.002 --rate-hz 1 --seed 2 --heading 10d30 --out -
run dov-simulate-bin-config dov simulate --hours 0.01 --seed 6 --sigma-ins-arcsec 0 --binary --out @W@/l.bin --config @W@/c.yaml
run dov-process-bin-config dov process "$out/dov-simulate-bin-config/c.yaml"
awk -F, 'BEGIN {OFS = ","} /^#/ {print; next} {print $0, (NR == 3 ? "status,truth_eta_arcsecs" : "ok,1")}' "$w/line.csv" > "$out/dov-extra.csv"
run dov-convert-extra dov convert "$out/dov-extra.csv" @W@/extra.bin
run dov-convert-stdout dov convert "$out/dov-convert/line.bin" -
run dov-convert-nomodel dov convert "$out/dov-nomodel.csv" @W@/n.bin
run dov-convert-nomodel-back dov convert "$out/dov-convert-nomodel/n.bin" @W@/n.csv
sed "s|^line: .*|line: $out/dov-extra.csv|" "$w/dov.yaml" > "$out/dov-extra.yaml"
run dov-process-extra dov process "$out/dov-extra.yaml" --json

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
# dov: where each kind of error is located (line file and column, binary sample, configuration key)
dov_line() { sed "s|^line: .*|line: $1|" "$w/dov.yaml"; }
awk -F, 'BEGIN {OFS = ","} NR == 12 {$15 = "2"} 1' "$w/line.csv" > "$out/dov-ortho.csv"
dov_line "$out/dov-ortho.csv" > "$out/dov-ortho.yaml"
run err-dov-ortho dov process "$out/dov-ortho.yaml"
awk -F, 'BEGIN {OFS = ","} NR == 20 {$6 = 1; $7 = 0; $8 = 0; $9 = 0; $10 = 1; $11 = 0; $12 = 0; $13 = 0; $14 = 1} 1' "$w/line.csv" > "$out/dov-diff.csv"
dov_line "$out/dov-diff.csv" > "$out/dov-diff.yaml"
run err-dov-difference dov process "$out/dov-diff.yaml" --json
{ dov_line "$w/line.csv"; echo "max_step_s: 0.1"; } > "$out/dov-step.yaml"
run err-dov-step dov process "$out/dov-step.yaml"
{ dov_line "$w/line.csv"; echo "statistics_start_s: 100000"; } > "$out/dov-stat.yaml"
run err-dov-statistics dov process "$out/dov-stat.yaml"
{ dov_line "$w/line.csv"; echo "gravity_model: {model: $syn}"; } > "$out/dov-both.yaml"
run err-dov-both-model-sources dov process "$out/dov-both.yaml"
dov_line "$out/dov-nomodel.csv" > "$out/dov-none.yaml"
run err-dov-no-model-values dov process "$out/dov-none.yaml"
{ dov_line "$out/dov-nomodel.csv"; echo "gravity_model: {model: no-such-model-xyz}"; } > "$out/dov-nogm.yaml"
run err-dov-model-not-found dov process "$out/dov-nogm.yaml"
awk -F, 'BEGIN {OFS = ","} NR == 30 {$4 = "2e7"} 1' "$out/dov-nomodel.csv" > "$out/dov-high.csv"
{ dov_line "$out/dov-high.csv"; echo "gravity_model: {model: $syn}"; } > "$out/dov-high.yaml"
run err-dov-model-height dov process "$out/dov-high.yaml"
head -n 4 "$w/line.csv" > "$out/dov-short.csv"
dov_line "$out/dov-short.csv" > "$out/dov-short.yaml"
run err-dov-short dov process "$out/dov-short.yaml"
{ dov_line "$w/line.csv"; echo "sigma_obs_arcsecs: 1"; } > "$out/dov-typo.yaml"
run err-dov-typo dov process "$out/dov-typo.yaml"
awk -F, 'BEGIN {OFS = ","} NR == 40 {$1 = "0.25"} 1' "$w/line.csv" > "$out/dov-rev.csv"
run err-dov-rev-convert dov convert "$out/dov-rev.csv" @W@/rev.bin
dov_line "$out/err-dov-rev-convert/rev.bin" > "$out/dov-rev.yaml"
run err-dov-rev-bin dov process "$out/dov-rev.yaml"
run err-dov-outputs-same dov process "$w/dov.yaml" -o @W@/x.html --report @W@/x.html
run err-dov-output-is-input dov process "$w/dov.yaml" -o "$w/line.csv"
run err-dov-report-dir dov process "$w/dov.yaml" -o @W@/p.csv --report @W@/no/such/dir/r.html
run err-dov-convert-same dov convert "$w/line.csv" "$w/line.csv"
run err-dov-sim-lat dov simulate --latitude 95 --out @W@/l.csv
run err-dov-sim-rate dov simulate --rate-hz 0 --out @W@/l.csv
run err-dov-sim-track dov simulate --hours 100 --heading 0 --speed-m-s 100 --out @W@/l.csv
run err-dov-sim-config-stdout dov simulate --hours 0.01 --out - --config @W@/c.yaml
run err-dov-sim-binary-stdout dov simulate --hours 0.01 --binary --out -
run err-dov-sim-same dov simulate --hours 0.01 --out @W@/a.yaml --config @W@/a.yaml
run err-dov-sim-config-dir dov simulate --hours 0.01 --out @W@/l.csv --config @W@/no/such/dir/c.yaml
c=examples/nav-scenario-c
for k in "sigma_speed_m_s: -1" "initial: {x_m: 7.49, y_m: 1.36, sigma_m: 0}" "segment_s: 0" "projection: {central_meridian_deg: 500}"; do
  key=${k%%:*}
  { grep -v "^$key:" $c/nav.yaml | sed -E "s#^(dr|stations|lops|truth): (.*)#\1: $root/$c/\2#"; echo "$k"; } > "$out/nav-$key.yaml"
  run err-nav-$key nav process "$out/nav-$key.yaml"
done
# nav: every place an error is located (the reader's rows and keys, the plane, nav::process),
# the CLI's checks of options against the result, several files to inspect, a geographic job.
n="$out/nav-cases"; mkdir -p "$n"
abs() { sed -E "s#^(dr|stations|lops|truth|fixes): (.*)#\1: $root/$c/\2#" "$@"; }
printf 'time_s,type,station,station2,value,sigma_m,chain\n0,range,A,,20000,50,\n5,range,Q,,20000,50,\n' > "$n/lops-unknown.csv"
printf 'time_s,type,station,station2,value,sigma_m,chain\n0,range,A,,20000,50,\n5,range_difference,A,A,20,50,\n' > "$n/lops-same.csv"
printf 'time_s,type,station,station2,value,sigma_m,chain\n0,range,A,,20000,50,\n10,time_difference,A,B,3,50,X\n' > "$n/lops-td.csv"
printf 'name,lat_deg,lon_deg\nA,45.2,7.6\nB,45.1,7.8\nC,44.9,7.7\n' > "$n/stations-geo.csv"
printf 'time_s,x_m,y_m\n0,0,0\n5,1,1\n5,2,2\n' > "$n/truth-repeat.csv"
awk -F, 'NR==40{$1=$1+200}NR>40&&NF==3&&$1+0==$1{$1=$1+200}1' OFS=, $c/dr.csv > "$n/dr-gap.csv"
printf 'time_s,x_m,y_m,sigma_m\n3,10,10,5\n' > "$n/fixes.csv"
for k in lops-unknown lops-same lops-td truth-repeat dr-gap stations-geo stations-far bins fixes-initial sigma-kind; do
  case $k in
    lops-*) abs $c/nav.yaml | sed "s|^lops: .*|lops: $n/$k.csv|" ;;
    truth-repeat) abs $c/nav.yaml | sed "s|^truth: .*|truth: $n/$k.csv|" ;;
    dr-gap) abs $c/nav.yaml | sed "s|^dr: .*|dr: $n/dr-gap.csv|" ;;
    stations-geo) abs $c/nav.yaml | sed "s|^stations: .*|stations: $n/stations-geo.csv|" ;;
    stations-far) abs $c/nav.yaml | sed "s|^stations: .*|stations: $n/stations-geo.csv|; s|^initial: .*|initial: {lat: 45, lon: 7.7}|"
                  echo "projection: {type: utm, zone: 40}" ;;
    bins) abs $c/nav.yaml | sed "s|^statistics_bin_s: .*|statistics_bin_s: 1e-9|" ;;
    fixes-initial) abs $c/nav.yaml | grep -v '^initial:' | sed "s|^truth: .*|fixes: $n/fixes.csv|" ;;
    sigma-kind) abs $c/nav.yaml; echo "sigma_velocity_m_s: 0.1" ;;
  esac > "$n/$k.yaml"
  [ $k = lops-td ] && echo 'chains: [{name: X, propagation_speed_m_s: 3e8, estimate_offset: true}]' >> "$n/$k.yaml"
  run nav-case-$k nav process "$n/$k.yaml" --json
done
abs $c/nav.yaml | grep -v '^initial:' | sed "s|^truth: .*|fixes: $n/fixes.csv|" > "$n/no-initial.yaml"
printf 'time_s,x_m,y_m,sigma_m\n30,10,10,5\n' > "$n/fixes.csv"
run err-nav-case-no-initial nav process "$n/no-initial.yaml"
run err-nav-geojson-plane nav process $c/nav.yaml --geojson @W@/t.geojson
run err-nav-method-missing nav process $c/nav.yaml -o @W@/t.csv --method fix-closure
run err-nav-output-over-input nav process $c/nav.yaml -o $c/dr.csv
run err-nav-outputs-same nav process $c/nav.yaml -o @W@/t.csv --rejected @W@/t.csv
for f in "$n"/*; do normalise "$f"; done
run nav-process-c-fixes nav process "$out/nav-simulate-C/job/nav.yaml" --method fix-closure -o @W@/t.csv --rejected @W@/rej.csv
if [ -d "$shared/data/nmea" ]; then
  run nav-inspect-several nav inspect "$shared"/data/nmea/nbp1406-gyro.nmea "$shared"/data/nmea/plaka-sailboat-4h.nmea
  run nav-inspect-several-json nav inspect "$shared"/data/nmea/nbp1406-gyro.nmea "$shared"/data/nmea/plaka-sailboat-4h.nmea --json
  run nav-nbp1406-rts-track nav process examples/nav-nbp1406.yaml -o @W@/t.csv --quiet
fi

# --- gravity models named by a campaign and a deflection line (loaded through io_gravity)
sed -e '/^    eta_arcsec:/d' -e '/^    eta_sigma_arcsec:/d' examples/campaign.yaml > "$out/campaign-model.yaml"
printf 'gravity_model:\n  model: %s\n  max_degree: 20\n' "$syn" >> "$out/campaign-model.yaml"
run gyro-campaign-model gyro campaign "$out/campaign-model.yaml" --json
sed 's|^  model: .*|  model: no_such_model_xyz|' "$out/campaign-model.yaml" > "$out/campaign-nomodel.yaml"
run err-gyro-campaign-model gyro campaign "$out/campaign-nomodel.yaml"
sed 's|^  model: .*|  model: short.gfc|' "$out/campaign-model.yaml" > "$out/campaign-badmodel.yaml"
run err-gyro-campaign-badmodel gyro campaign "$out/campaign-badmodel.yaml"
awk -F, -v OFS=, '/^#/ {print; next} {$24 = $25 = ""; print}' "$out/dov-simulate/line.csv" | sed 's/,,,/,/' > "$out/line-nomodel.csv"
printf 'line: %s\ngravity_model:\n  model: %s\n  max_degree: 20\n' "$out/line-nomodel.csv" "$syn" > "$out/dov-model.yaml"
run dov-process-model dov process "$out/dov-model.yaml" --json
sed 's|^  model: .*|  model: no_such_model_xyz|' "$out/dov-model.yaml" > "$out/dov-nomodel.yaml"
run err-dov-process-model dov process "$out/dov-nomodel.yaml"

# --- the Python package, when built
if [ -d "$build/python/meridian" ]; then
  runpy py-gyro 'import meridian.gyro as g, json; print(json.dumps(g.reduce("examples/tracking.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-stochastic 'import meridian.gyro as g, json; print(json.dumps(g.stochastic("examples/tracking.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-stochastic-campaign-err 'import meridian.gyro as g; g.stochastic("examples/campaign.yaml")'
  runpy py-stochastic-dict-err 'import meridian.gyro as g; g.stochastic({"instrument": {"scale_value_arcsec": 600, "torsion_ratio": 0.3}, "station": {"latitude_deg": 34}, "determinations": [{"mode": "tracking", "reversals": ["358 52 32", "1 32 16", "358 52 48", "1 32 03", "358 53 05", "1 31 43"], "sigma_reading_arcsec": -8}]})'
  runpy py-reduce-dict-err 'import meridian.gyro as g; g.reduce({"instrument": {"scale_value_arcsec": 600}, "determinations": []})'
  runpy py-campaign 'import meridian.gyro as g, json; print(json.dumps(g.campaign("examples/campaign.yaml").to_dict(), sort_keys=True, default=str))'
  runpy py-maglev 'import meridian.maglev as m, json; print(json.dumps(m.reduce_files("examples/maglev-disturbed.csv", scale_A_s_per_rad=8000, latitude_deg=35).to_dict(), sort_keys=True, default=str))'
  runpy py-maglev-api "
import meridian.maglev as m, json, os, numpy as np
def show(name, r): print(name, json.dumps(r.to_dict(), sort_keys=True, default=str))
def fail(name, f):
    try: f(); print(name, 'no error')
    except Exception as e: print(name, type(e).__name__, repr(str(e)), getattr(e, 'file', None), getattr(e, 'line', None), getattr(e, 'field', None))
out = os.environ['W'] + '/..'
p1, p2 = m.simulate(alpha1_deg=0.8, samples=1500, rate_hz=20, ar1_phi=0.6, ar1_sigma_A=2e-6, bursts=[(1, 20, 40, 2e-3, 6e-4, 0.5, 8)], seed=5)
print('sim', repr(p1.current_A[:5].tolist()), repr(p2.time_s[:3].tolist()), len(p1), len(p2))
r = m.reduce(p1, p2, scale_A_s_per_rad=8000, latitude_deg=35, target_deg='45 30 00', eta_arcsec=4.5, prior_bias_A=2e-4, reading1_deg=10)
show('arrays', r)
print('series', r.series1.kept.sum(), repr(r.series1.cleaned_A[100:103].tolist()), repr(r.series2.time_s[:2].tolist()))
show('files-config', m.reduce_files('examples/maglev-disturbed.csv', config=out + '/maglev-constants.yaml', rule='sure', level=4))
show('files-cal', m.reduce_files('examples/maglev-disturbed.csv', calibration=out + '/maglev-calibrate-json/cal.json', latitude_deg=35, process=False))
show('two-files', m.reduce_files(out + '/maglev-simulate/s-1.csv', out + '/maglev-simulate/s-2.csv', scale_A_s_per_rad=8000, latitude_deg=35))
d = m.denoise(p1.current_A, full=True)
print('denoise', d.level, repr(d.noise_sigma), repr(d.values[:3].tolist()), d.thresholds)
print('denoise3', repr(m.denoise(p1.current_A[:300], wavelet='db6', level=3, mode='periodization', threshold='hard')[:3].tolist()))
t = m.simulate_calibration([-3, -1, 1, 3], slope_ratio1=1.01, slope_ratio2=0.99, best_azimuth_deg=0.1, constant_deviation_A=1e-5, samples=2000, seed=4)
print('simcal', json.dumps({k: t[k].tolist() for k in ['azimuth_deg', 'mean1_A', 'sigma1_A', 'mean2_A', 'sigma2_A']}))
show('cal-arrays', m.calibrate(t, latitude_deg=35, nominal_scale_A_s_per_rad=8000))
show('cal-file', m.calibrate('examples/maglev-calibration.csv', latitude_deg=35, alpha=0.01))
fail('err-nan', lambda: m.reduce((p1.time_s, np.where(np.arange(len(p1)) == 7, np.nan, p1.current_A)), p2, scale_A_s_per_rad=8000, latitude_deg=35))
fail('err-no-k', lambda: m.reduce(p1, p2, latitude_deg=35))
fail('err-no-lat', lambda: m.reduce(p1, p2, scale_A_s_per_rad=8000))
fail('err-no-k-config', lambda: m.reduce_files('examples/maglev-disturbed.csv', config=out + '/maglev-no-k.yaml'))
fail('err-const', lambda: m.reduce_files(out + '/maglev-const.csv', out + '/maglev-simulate/s-2.csv', scale_A_s_per_rad=8000, latitude_deg=35))
fail('err-short', lambda: m.reduce_files(out + '/maglev-short.csv', out + '/maglev-simulate/s-2.csv', scale_A_s_per_rad=8000, latitude_deg=35))
fail('err-alpha1', lambda: m.reduce(p1, p2, scale_A_s_per_rad=10, latitude_deg=35))
fail('err-missing', lambda: m.reduce_files(out + '/nothing.csv', scale_A_s_per_rad=8000, latitude_deg=35))
fail('err-cal-few', lambda: m.calibrate(out + '/maglev-cal-few.csv', latitude_deg=35))
fail('err-cal-arrays', lambda: m.calibrate({'azimuth_deg': [-1, 0, 1], 'mean1_A': [1, 2, 3], 'sigma1_A': [1, 1, 1], 'mean2_A': [3, 2, 1], 'sigma2_A': [1, np.nan, 1]}, latitude_deg=35))
fail('err-denoise-nan', lambda: m.denoise([1.0, np.nan, 2.0] * 20))
fail('err-denoise-deep', lambda: m.denoise(p1.current_A[:100], level=8))
fail('err-sim-burst', lambda: m.simulate(samples=300, bursts=[(1, 500, 600, 2e-3, 6e-4, 0.5, 8)]))
"
  runpy py-dov "import meridian.dov as d, json, os; r=d.process(os.environ['W']+'/../dov-simulate/dov.yaml'); print(json.dumps(r.to_dict(), sort_keys=True, default=str)[:200000])"
  runpy py-dov-profile "import meridian.dov as d, json, os; r=d.process(os.environ['W']+'/../dov-simulate/dov.yaml'); print(json.dumps({k: v.tolist() for k, v in r.profile.to_dict().items()}))"
  runpy py-dov-arrays "import meridian.dov as d, json; l=d.simulate(hours=0.02, seed=3, transport_rate=True); r=d.process(l, sigma_model_arcsec=2, transport_rate=True); print(json.dumps(r.to_dict(), sort_keys=True)); print(json.dumps({k: v.tolist() for k, v in r.profile.to_dict().items()})); print(json.dumps({k: v.tolist() for k, v in l.to_dict().items()}))"
  runpy py-dov-read-line "import meridian.dov as d, json, os; o=os.environ['W']+'/..'; print(json.dumps({k: v.tolist() for k, v in d.read_line(o+'/dov-simulate-bin/line.bin').to_dict().items()})); print(json.dumps({k: v.tolist() for k, v in d.read_line(o+'/dov-nomodel.csv').to_dict().items()})); d.read_line(o+'/dov-extra.csv')"
  runpy py-dov-errors "import meridian.dov as d, numpy as np, os
l = dict(d.simulate(hours=0.01, seed=3).to_dict()); l['speed_m_s'] = l['speed_m_s'].copy(); l['speed_m_s'][4] = -1
for f in (lambda: d.process(l), lambda: d.process(d.simulate(hours=0.01), gate_alpha=2), lambda: d.process(d.simulate(hours=0.01), gravity_model={'model': 'x'}), lambda: d.process(os.environ['W'] + '/../dov-ortho.yaml'), lambda: d.simulate(latitude_deg=95), lambda: d.simulate(hours=100, heading_deg=0, speed_m_s=100)):
    try: f()
    except Exception as e: print(type(e).__name__, e.file, e.line, e.field, e)
" 
  runpy py-nav 'import meridian.nav as n, json; print(json.dumps(n.process("examples/nav-scenario-c/nav.yaml").to_dict(), sort_keys=True, default=str)[:200000])'
  if [ -d "$shared/data/nmea" ]; then
    runpy py-nav-tracks 'import meridian.nav as n; r=n.process("examples/nav-nbp1406.yaml")
for m, t in sorted(r.tracks.items()):
    print(m, list(t._columns), [repr(t[c][::97].tolist()) for c in ("time_s", "x_m", "lat_deg", "lon_deg", "sigma_bias_north_m_s", "flags")])'
    runpy py-nav-inspect "import meridian.nav as n, json; print(json.dumps(n.inspect('$shared/data/nmea/nbp1406-gyro.nmea', '$shared/data/nmea/plaka-sailboat-4h.nmea').to_dict(), sort_keys=True))"
  fi
  runpy py-gravity "import meridian.gravity as g, numpy as np; m=g.GravityModel.open('$syn'); print(repr(m.deflection(np.array([10.,20.]), np.array([30.,40.]))))"
  gfc="$out/gravity-synth/syn.gfc"
  runpy py-gravity-open "import meridian.gravity as g, numpy as np, json; m=g.GravityModel.open('$gfc', max_degree=12, threads=1); print(json.dumps(m.info, sort_keys=True)); print(m.warnings, m.max_degree); d=m.deflection([[10.,20.],[-30,45]], [30.,40.], 100.); print(repr(d)); print(repr(m.grid(np.array([-10.,0,10]), np.array([0.,90,180,270]), 0.)))"
  runpy py-gravity-synthetic "import meridian.gravity as g, json; m=g.synthetic_model(degree=30, seed=4, threads=1); print(json.dumps(m.info, sort_keys=True)); print(repr(m.deflection(12.5, -60., geoid=False)))"
  runpy py-gravity-errors "import meridian.gravity as g
for f in (lambda: g.GravityModel.open('no_such_model_xyz'), lambda: g.GravityModel.open('$out/short.gfc'), lambda: g.GravityModel.open('$syn').deflection([10., 95.], 0.), lambda: g.GravityModel.open('$syn').grid([10., 0.], [0., float('nan')])):
    try: f()
    except Exception as e: print(type(e).__name__, e, getattr(e, 'field', None))"
fi
for f in "$out"/*.*; do normalise "$f"; done
echo "snapshot: $(ls -d "$out"/*/ | wc -l) runs in $out"
