#!/usr/bin/env bash
# Instructions a step, counted by callgrind: the cost of a step that no machine's speed or load
# moves, where make bench's times vary by 10% from run to run. Runs the benchmark cases matching
# the regex given (default: free flight, open floor, mazes) under callgrind, each for the same
# STEPS steps (default 20,000; MARBLE_MAZE_BENCH_STEPS), and prints Simulation::step's inclusive
# count over its calls (the benchmark's own loop and the scenes' building left out), with each
# case's ratio to free flight. The same build gives the same counts.
set -euo pipefail
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
filter=${1:-'FreeFlight|OpenFloor|MazeSize'}
bench=$WS/devel/lib/marble_maze/marble_maze_bench
command -v valgrind >/dev/null || { echo "valgrind is missing: make deps installs it" >&2; exit 1; }
[ -x "$bench" ] || { echo "$bench is missing: make build builds it" >&2; exit 1; }
export MARBLE_MAZE_BENCH_STEPS=${STEPS:-20000}
# (The cases' names end in /iterations:N then: the regex is matched against them without it.)
cases=$("$bench" --benchmark_list_tests=true | sed 's|/iterations:[0-9]*$||' | grep -E "$filter" || true)
[ -n "$cases" ] || { echo "no benchmark case matches '$filter'" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Instructions per call of Simulation::step in one callgrind file: the inclusive cost of every
# call to it, over the number of calls.
per_step() {
  /usr/bin/python3 - "$1" <<'PY'
import re, sys
names, calls, cost, pending, target = {}, 0, 0, False, ""
for line in open(sys.argv[1]):
    m = re.match(r"cfn=\((\d+)\)(?: (.*))?", line)
    if m:
        if m.group(2):
            names[m.group(1)] = m.group(2).strip()
        target = names.get(m.group(1), "")
        continue
    if line.startswith("calls="):
        pending = target.startswith("marble_maze::Simulation::step()")
        if pending:
            calls += int(line.split()[0][len("calls="):])
        continue
    if pending:  # the line after a call: its position and inclusive cost
        cost += int(line.split()[-1])
        pending = False
    m = re.match(r"fn=\((\d+)\)(?: (.*))?", line)
    if m and m.group(2):
        names[m.group(1)] = m.group(2).strip()
if calls == 0:
    sys.exit("Simulation::step was never called")
print(cost // calls)
PY
}

count() {
  # (The case's name as a regex of itself: its metacharacters escaped.)
  local name
  name=$(printf '%s' "$1" | sed 's/[][\.*^$+?(){}|]/\\&/g')
  valgrind --tool=callgrind --cache-sim=no \
    --branch-sim=no --callgrind-out-file="$out/cg" "$bench" \
    --benchmark_filter="^$name/iterations:$MARBLE_MAZE_BENCH_STEPS\$" \
    >"$out/log" 2>&1 || { cat "$out/log" >&2; exit 1; }
  per_step "$out/cg"
}

baseline=$(count BM_FreeFlight)
printf '%-42s %22s %14s\n' "case ($MARBLE_MAZE_BENCH_STEPS steps each)" "instructions a step" \
  "/ free flight"
for c in $cases; do
  n=$baseline
  [ "$c" = BM_FreeFlight ] || n=$(count "$c")
  awk -v c="$c" -v n="$n" -v b="$baseline" \
    'BEGIN { printf "%-42s %22d %14.2f\n", c, n, n / b }'
done
