#!/usr/bin/env bash
# The fuzzers of the maze-file parser, of the runner's command line and of a session's restore
# from a bag's snapshot (libFuzzer on the sanitized core, scripts/sanitized_build.sh):
#   bash scripts/fuzz.sh [SECONDS [RESULTS_DIR]]
# replays every input of fuzz/regressions/ (each a crash or hang once found), then runs each
# fuzzer for SECONDS of wall time (default 10; the three side by side) from the checked-in corpus
# (and mazes/), new inputs going to a scratch corpus in WS/sanitize. A finding stops the run: its
# input is written to WS/sanitize/findings/, to be fixed and then added to fuzz/regressions/ for
# good. Prints each fuzzer's executions and, given RESULTS_DIR, writes a JUnit file there with a
# case per fuzzer.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
seconds=${1:-10}
results=${2:-}
build="$WS/sanitize"
record() {  # record NAME FAILURE-MESSAGE-OR-EMPTY: a JUnit case, into the fuzzer's own file
  if [ -z "$2" ]; then
    echo "<testcase classname=\"fuzz\" name=\"$1\"/>" >> "$cases_file"
  else
    echo "<testcase classname=\"fuzz\" name=\"$1\"><failure message=\"$2\"/></testcase>" \
      >> "$cases_file"
  fi
}
mkdir -p "$build/findings"
bash "$repo/scripts/sanitized_build.sh" maze_fuzzer args_fuzzer snapshot_fuzzer || exit 1
fuzz() {  # fuzz NAME: its regressions, then SECONDS of fuzzing; exits non-zero on a failure
  local fuzzer=$1 cases_file="$build/$1.cases"  # (record writes to it)
  : > "$cases_file"
  binary="$build/${fuzzer}_fuzzer"
  regressions=("$repo/fuzz/regressions/$fuzzer"/*)
  if [ -e "${regressions[0]}" ]; then
    if ! "$binary" "${regressions[@]}" > "$build/$fuzzer-regressions.log" 2>&1; then
      tail -n 30 "$build/$fuzzer-regressions.log"
      echo "$fuzzer fuzzer: a regression input fails again (log: $build/$fuzzer-regressions.log)"
      record "${fuzzer}_regressions" "a regression input fails again"
      return 1
    fi
    record "${fuzzer}_regressions" ""
  fi
  scratch="$build/corpus-$fuzzer"
  mkdir -p "$scratch"
  # -timeout: an input taking more than 10 s is a hang; -rss_limit_mb: one taking 2 GB a leak.
  seeds=("$repo/fuzz/corpus/$fuzzer")
  [ "$fuzzer" = maze ] && seeds+=("$repo/mazes")  # the shipped mazes seed it too
  "$binary" "$scratch" "${seeds[@]}" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
    -artifact_prefix="$build/findings/$fuzzer-" > "$build/$fuzzer.log" 2>&1
  result=$?
  runs=$(grep -o "stat::number_of_executed_units: *[0-9]*" "$build/$fuzzer.log" | grep -o "[0-9]*$")
  echo "$fuzzer fuzzer: ${runs:-0} executions in $seconds s," \
    "$(find "$scratch" -type f | wc -l) inputs in its corpus"
  if [ $result -ne 0 ]; then
    grep -E "ERROR|runtime error|SUMMARY|Test unit written" "$build/$fuzzer.log" | head -n 20
    echo "$fuzzer fuzzer: a finding (log: $build/$fuzzer.log; input in $build/findings/)"
    record "${fuzzer}_fuzzer" "a finding: see $build/$fuzzer.log"
    return 1
  fi
  record "${fuzzer}_fuzzer" ""
}
# The three side by side on the machine's cores (each runs for the same wall time); their reports
# after all three.
pids=()
for fuzzer in maze args snapshot; do
  fuzz "$fuzzer" > "$build/$fuzzer.report" 2>&1 &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
cases=""
for fuzzer in maze args snapshot; do
  cat "$build/$fuzzer.report"
  cases+=$(cat "$build/$fuzzer.cases")
done
if [ -n "$results" ]; then
  mkdir -p "$results"
  echo "<testsuite name=\"fuzz\">$cases</testsuite>" > "$results/fuzz.xml"
fi
exit $status
