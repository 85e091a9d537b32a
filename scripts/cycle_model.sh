#!/usr/bin/env bash
# What holds a step's time, by a model of the processor (scripts/cycle_model.py): each case of
# make bench's (free flight, the open floor, the 100-cell maze) is run for STEPS steps (default
# 20,000, as make instructions counts them) under valgrind's lackey, which traces them, and the
# model takes SAMPLES windows of WINDOW steps spread over the run (default 20 of 50) and gives
# their cycles a step: the chain of dependent values alone, the width alone, the window alone,
# and both. The same build gives the same figures from run to run. FREE, a regex of functions,
# takes their work out of the model (what a stage costs); CHAIN=1 lists the functions the chain
# runs through; MACHINE, JSON, sets the model's rules for another processor (an AMD Zen 2's
# window: MACHINE='{"window": 224}'). About 2 minutes a case.
set -euo pipefail
. "$(dirname "$0")/workspace.sh"
driver=$WS/devel/lib/marble_maze/marble_maze_cycle_driver
command -v valgrind >/dev/null || { echo "valgrind is missing: make deps installs it" >&2; exit 1; }
/usr/bin/python3 -c 'import capstone' 2>/dev/null ||
  { echo "python3-capstone is missing: make deps installs it" >&2; exit 1; }
[ -x "$driver" ] || { echo "$driver is missing: make build builds it" >&2; exit 1; }
cases=${1:-free_flight open_floor maze:100}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
options=()
[ -z "${FREE:-}" ] || options+=(--free "$FREE")
[ -z "${CHAIN:-}" ] || options+=(--chain)
[ -z "${MACHINE:-}" ] || options+=(--machine "$MACHINE")
printf '%-14s %8s %8s %8s %8s %8s\n' "case" "instr" "chain" "width" "window" "model"
for c in $cases; do
  valgrind --tool=lackey --trace-mem=yes --log-file="$out/trace" \
    "$driver" "$c" "${STEPS:-20000}" "${SAMPLES:-20}" "${WINDOW:-50}" >"$out/driver" 2>"$out/log" ||
    { cat "$out/log" >&2; exit 1; }
  printf '%-14s ' "$c"
  /usr/bin/python3 "$repo/scripts/cycle_model.py" "$out/driver" "$out/trace" "${options[@]}"
done
