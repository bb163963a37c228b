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
