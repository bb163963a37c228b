#!/usr/bin/env bash
# Regenerates the example data from the project's own simulator.
# Usage: examples/regenerate.sh [path/to/meridian]   (default: build/meridian)
set -euo pipefail
cd "$(dirname "$0")"
M=${1:-../build/meridian}
# A whole station campaign (known line before/after, three determinations on C-D).
"$M" gyro simulate --mode campaign --seed 2026 -o campaign.yaml
# Spec §8 scenario 2: lambda 0.30, tau 600", T_B 440 s, B 9 div, beta -0.12 div, no noise.
"$M" gyro simulate --mode non-tracking --sigma-time-s 0 --sigma-reading-div 0 -o spec-scenario-2.yaml
# The same oscillation with field noise (0.1 s, 0.05 div), three determinations.
"$M" gyro simulate --mode non-tracking --seed 7 --determinations 3 -o nontracking-noisy.yaml
# Tracking mode, spec §8 scenario 4 (M = 0°12'34", A = 8 div, kappa 0.002), 8" reading noise.
"$M" gyro simulate --mode tracking --seed 3 --tracking-reversals 7 --sigma-tracking-arcsec 8 -o tracking.yaml
# Transit-factor calibration: one gyro north seen from clamps 12' east and 12' west of it (spec §4.1).
"$M" gyro simulate --mode non-tracking --seed 5 --determinations 2 --beta-div -0.9 --clamp "0 12 00,359 48 00" \
  --levels 0 -o transit-factor.yaml
# Maglev gyro (docs/maglev-gyro.md): a two-position determination, 4000 samples per position at
# 20 Hz, alpha1 = 1.1459 deg, vibration on 20 % of position 1 (63-103 s); one file with a position column.
# Its bias b = 1.75e-5 A is the constant deviation I* of the calibration below (same instrument), so
#   meridian maglev calibrate maglev-calibration.csv --latitude 35 --json -o cal.json
#   meridian maglev reduce maglev-disturbed.csv --calibration cal.json --latitude 35
# passes the symmetry check.  Plain:  meridian maglev reduce maglev-disturbed.csv --scale 8000 --latitude 35
"$M" maglev simulate --alpha1=1.1459 --bias=1.75e-5 --samples=4000 --rate-hz=20 --white=1e-5 --ar1-phi=0.8 \
  --ar1-sigma=2e-6 --burst=1:63:103:2e-3:6e-4:0.5:8 --seed=12 --one-file --out maglev-disturbed
# A multi-angle calibration at 7 set-ups (-3 deg ... 3 deg) with a trend deviation (slopes 1.01 and 0.99 of
# K*w*cos(phi)), alpha* = 0.11459 deg, I* = 1.75e-5 A:  meridian maglev calibrate maglev-calibration.csv --latitude 35
"$M" maglev simulate --calibration-azimuths=-3,-2,-1,0,1,2,3 --slope-ratio1=1.01 --slope-ratio2=0.99 \
  --best-azimuth=0.11459 --constant-deviation=1.75e-5 --white=1e-5 --seed=4 --out maglev
# Marine navigation (docs/navigation.md): spec §8 scenario C (the DR speed bias changes at minutes
# 10 and 15), 30 min, DR and three range LOPs every 5 s:  meridian nav process nav-scenario-c/nav.yaml
"$M" nav simulate --scenario C --seed 1 --out nav-scenario-c
