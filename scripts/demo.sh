#!/usr/bin/env bash
# The demo: the headless runner on the default maze under a scripted tilt program.
set -euo pipefail
cd "$(dirname "$0")/.."
.ws/devel/lib/marble_maze/simulate --tilt-csv config/demo_tilt.csv --duration 20 \
  --events /dev/stdout --out .ws/demo_trajectory.csv
echo "trajectory written to .ws/demo_trajectory.csv"
