#!/usr/bin/env bash
# The step's cost now against the core of an earlier commit, both built here alike (-O3, a static
# library) and timed in turns on issue 11's cases (bench/step_cost.cpp): a speed-up that no
# machine's speed moves, beside make bench's nanoseconds. Usage: speedup.sh [COMMIT] (default:
# the first commit, whose step issue 11 asks to be three times faster); ROUNDS (default 3) runs
# of each build in turn, each case's best kept. Needs the repository's history.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
# Issue 11's "today" (0.3 us on the open floor, 0.3 to 0.5 us in the mazes) is this commit's.
commit=${1:-cd36eeb}
rounds=${ROUNDS:-3}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "ROUNDS: '$rounds' is not a positive whole number" >&2; exit 2; }
if ! git -C "$repo" cat-file -e "$commit^{commit}" 2>/dev/null; then
  echo "speedup: no commit '$commit' in this clone's history (a shallow clone lacks the old ones: git fetch --unshallow)" >&2
  exit 2
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/then"
git -C "$repo" archive "$commit" src/core include | tar -x -C "$work/then"

# build SOURCE OUT: SOURCE's core (src/core, include) as a static library, no built-in maze (the
# cases build theirs), and the cases against it.
build() {
  local src=$1 out=$2 flags=(-O3 -DNDEBUG -std=gnu++17 -I"$1/include" -I/usr/include/eigen3)
  mkdir -p "$out"
  sed 's/@EMBEDDED_MAZE_ENTRIES@//' "$src/src/core/embedded_mazes.cpp.in" >"$out/embedded_mazes.cpp"
  local f pid pids=()
  for f in "$src"/src/core/*.cpp "$out/embedded_mazes.cpp"; do
    g++ "${flags[@]}" -c "$f" -o "$out/$(basename "$f" .cpp).o" &
    pids+=($!)
    while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do sleep 0.1; done
  done
  for pid in "${pids[@]}"; do wait "$pid"; done  # (a compile that failed stops the script)
  ar rcs "$out/libcore.a" "$out"/*.o
  g++ "${flags[@]}" -I"$repo/test/core" -I"$repo/bench" "$repo/bench/step_cost.cpp" \
    "$out/libcore.a" -o "$out/step_cost" -lbenchmark -lyaml-cpp -lpthread
}
echo "building the core of $(git -C "$repo" log -1 --format='%h (%ad)' --date=short "$commit") and of this tree..."
build "$work/then" "$work/then.build"
build "$repo" "$work/now.build"

for ((r = 1; r <= rounds; ++r)); do
  for which in then now; do
    if ! "$work/$which.build/step_cost" --benchmark_format=csv >"$work/$which.$r.csv" \
      2>"$work/$which.err"; then
      echo "speedup: the cases of $which failed:" >&2
      cat "$work/$which.err" >&2
      exit 1
    fi
  done
done
/usr/bin/python3 - "$work" "$rounds" "$commit" <<'PY'
import csv, sys
work, rounds, commit = sys.argv[1], int(sys.argv[2]), sys.argv[3]
best = {}  # (build, case) -> the least ns a step over the rounds
order = []
for which in ("then", "now"):
    for r in range(1, rounds + 1):
        lines = open(f"{work}/{which}.{r}.csv").read().splitlines()
        start = next(i for i, l in enumerate(lines) if l.startswith("name,"))
        for row in csv.DictReader(lines[start:]):
            ns = float(row["cpu_time"]) * {"ns": 1, "us": 1e3, "ms": 1e6}[row["time_unit"]]
            key = (which, row["name"])
            best[key] = min(best.get(key, ns), ns)
            if row["name"] not in order:
                order.append(row["name"])
print(f"\nns a step, the best of {rounds} runs of each build in turn")
print(f"{'case':40} {commit:>10} {'now':>10} {'speed-up':>9}")
for name in order:
    then, now = best[("then", name)], best[("now", name)]
    print(f"{name:40} {then:10.1f} {now:10.1f} {then / now:8.2f}x")
PY
