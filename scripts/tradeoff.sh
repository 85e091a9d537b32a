#!/usr/bin/env bash
# Measures the speed-accuracy trade and writes doc/tradeoff.csv, doc/tradeoff.md and
# doc/tradeoff.png:  bash scripts/tradeoff.sh [--quick] [--starts N]
# The full sweep (144 options, 16 starts of play each) takes about a minute on one core; --quick takes
# seconds and writes to the workspace instead of doc/.
set -euo pipefail
export PATH="/usr/bin:$PATH"
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh python3-matplotlib
. scripts/workspace.sh
out=doc
for arg in "$@"; do [ "$arg" != --quick ] || out="$WS/tradeoff"; done
mkdir -p "$out"
"$WS/devel/lib/marble_maze/marble_maze_tradeoff" --out "$out/tradeoff.csv" "$@"
/usr/bin/python3 scripts/plot_tradeoff.py "$out/tradeoff.csv" "$out/tradeoff.md" "$out/tradeoff.png"
