#!/usr/bin/env bash
# make lint: catkin_lint on the package, clang-format's layout (.clang-format), clang-tidy (.clang-tidy: checks that find bugs) on the
# C++, flake8 (.flake8) on the Python and shellcheck on the scripts. Prints what each found and
# exits non-zero when any found something.
set -uo pipefail
export PATH="/usr/bin:$PATH"
# shellcheck source=scripts/workspace.sh
. "$(dirname "$0")/workspace.sh"
cd "$repo" || exit 1
status=0

run() {
  local name=$1
  shift
  echo "== $name"
  if ! "$@"; then
    echo "$name found problems"
    status=1
  fi
}

# clang-tidy reads the flags of the workspace's build (scripts/build.sh exports them), each
# file named as the build names it (through the workspace's link to this clone); its own summary
# lines ("N warnings generated") are noise, its findings name file:line:col.
# (The functions below are called through `run`.)
# shellcheck disable=SC2317
tidy() {
  local db=$WS/build
  if [ ! -f "$db/compile_commands.json" ]; then
    echo "no $db/compile_commands.json: run make build first"
    return 1
  fi
  local out
  out=$(git ls-files 'src/*.cpp' 'bench/*.cpp' 'test/*.cpp' ':!test/sanitize' |
    sed "s|^|$WS/src/marble_maze/|" |
    xargs -P 2 -n 4 clang-tidy -p "$db" --quiet 2>/dev/null |
    grep -E '^[^ ].*: (warning|error):' | sort -u)
  [ -z "$out" ] || { echo "$out"; return 1; }
}

# shellcheck disable=SC2317
python_files() {
  git ls-files '*.py'
  # shellcheck disable=SC2046
  grep -l '^#!.*python' $(git ls-files 'nodes/*' 'scripts/*') 2>/dev/null | grep -v '\.py$'
}

run catkin_lint catkin_lint --strict -q .
# shellcheck disable=SC2046
run clang-format clang-format --dry-run -Werror $(git ls-files '*.cpp' '*.h')
run clang-tidy tidy
# shellcheck disable=SC2046
run flake8 flake8 $(python_files | sort -u)
# shellcheck disable=SC2046
run shellcheck shellcheck -x $(git ls-files '*.sh') .ci/run
exit $status
