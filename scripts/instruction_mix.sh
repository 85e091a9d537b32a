#!/usr/bin/env bash
# What a step's instructions are, by the processor ports that can run them: callgrind counts each
# instruction of the core library that the benchmark case runs, objdump names it, and each is
# put in a class. Scalar and two-lane floating-point adds, multiplies, divides, comparisons,
# minima and maxima run on two ports only (x86-64 from Skylake to Sunny Cove), so their count
# over two bounds a step's cycles from below whatever else it does. Setup is left out: the case
# runs STEPS and then 2 x STEPS steps, and the difference over STEPS is a step's (the same build
# counts the same). CASES is a regex of make bench's cases (default: free flight, open floor and
# the 100-cell maze); STEPS defaults to 10,000.
set -euo pipefail
. "$(dirname "$0")/workspace.sh"
filter=${1:-'^BM_FreeFlight$|^BM_OpenFloor$|^BM_StepByMazeSize/cells:100$'}
bench=$WS/devel/lib/marble_maze/marble_maze_bench
core=$WS/devel/lib/libmarble_maze_core.so
command -v valgrind >/dev/null || { echo "valgrind is missing: make deps installs it" >&2; exit 1; }
if [ ! -x "$bench" ] || [ ! -f "$core" ]; then
  echo "$bench is missing: make build builds it" >&2
  exit 1
fi
steps=${STEPS:-10000}
cases=$(MARBLE_MAZE_BENCH_STEPS=1 "$bench" --benchmark_list_tests=true |
  sed 's|/iterations:[0-9]*$||' | grep -E "$filter" || true)
[ -n "$cases" ] || { echo "no benchmark case matches '$filter'" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
objdump -d --no-show-raw-insn "$core" >"$out/core.s"

run() {  # CASE STEPS FILE: callgrind's count of each instruction the case runs
  local name
  name=$(printf '%s' "$1" | sed 's/[][\.*^$+?(){}|]/\\&/g')
  MARBLE_MAZE_BENCH_STEPS=$2 valgrind --tool=callgrind --dump-instr=yes --callgrind-out-file="$3" \
    "$bench" --benchmark_filter="^$name/iterations:$2\$" >"$out/log" 2>&1 ||
    { cat "$out/log" >&2; exit 1; }
}

printf '%-30s %8s %8s %8s %8s %8s   %s\n' "case (a step)" "all" "fp p0/p1" "shuffle" \
  "moves" "other" "fp ops / 2 (cycles at least)"
for c in $cases; do
  run "$c" "$steps" "$out/a.cg"
  run "$c" $((2 * steps)) "$out/b.cg"
  /usr/bin/python3 - "$out/core.s" "$core" "$out/a.cg" "$out/b.cg" "$steps" "$c" <<'PY'
import collections, re, sys
listing, core, first, second, steps, case = sys.argv[1:]
steps = int(steps)
ops = {int(a, 16): m for a, m in re.findall(r"^\s+([0-9a-f]+):\s+(\S+)", open(listing).read(), re.M)}
entry = {m.group(2): int(m.group(1), 16) for m in re.finditer(
    r"^([0-9a-f]+) <([^>]+)>:$", open(listing).read(), re.M)}["_ZN11marble_maze10Simulation4stepEv"]

def counts(path):
    """Each instruction's count in the core library, by its offset there."""
    names, by_address, last, in_core, skip, fn = {}, collections.Counter(), 0, False, False, ""
    step_at = None  # where Simulation::step() was loaded: the least address of it that ran
    for line in open(path):
        m = re.match(r"(c?ob|c?fn)=\((\d+)\)(?: (.*))?", line)
        if m:
            kind = m.group(1).lstrip("c")
            if m.group(3):
                names[kind, m.group(2)] = m.group(3).strip()
            if m.group(1) == "ob":
                in_core = names.get(("ob", m.group(2)), "").endswith("/" + core.split("/")[-1])
            if m.group(1) == "fn":
                fn = names.get(("fn", m.group(2)), "")
            continue
        if line.startswith("calls="):
            skip = True  # the next line is the call's inclusive cost
            continue
        if not line[:1] or line[0] not in "+-*0123456789":
            continue
        parts = line.split()
        p = parts[0]
        last = (last if p == "*" else last + int(p[1:], 0) if p[0] == "+" else
                last - int(p[1:], 0) if p[0] == "-" else int(p, 0))
        if skip:
            skip = False
        elif in_core:
            by_address[last] += int(parts[-1])
            if fn == "marble_maze::Simulation::step()":
                step_at = last if step_at is None else min(step_at, last)
    base = step_at - entry
    return collections.Counter({addr - base: n for addr, n in by_address.items()})


a, b = counts(first), counts(second)
fp = re.compile(r"^v?(add|sub|mul|div|sqrt|min|max|cmp|u?comi|round|f[n]?m(add|sub))\w*(sd|pd|ss|ps)$")
shuffle = re.compile(r"^v?(unpck|shuf|movddup|movhlps|movlhps|perm|pshuf|palignr|insert|extract)")
move = re.compile(r"^v?(mov(sd|apd|upd|aps|ups|ss|q|d|hpd|lpd|hps|lps))$")
classes = collections.Counter()
for addr in set(a) | set(b):
    n = b[addr] - a[addr]
    m = ops.get(addr, "?")
    kind = "fp" if fp.match(m) else "shuffle" if shuffle.match(m) else "move" if move.match(m) else "other"
    classes[kind] += n
    classes["all"] += n
per = {k: v / steps for k, v in classes.items()}
print("%-30s %8.0f %8.0f %8.0f %8.0f %8.0f   %.0f" % (case, per["all"], per["fp"], per["shuffle"],
      per["move"], per["other"], per["fp"] / 2))
PY
done
