#!/usr/bin/env bash
# Counts the instructions a step of every benchmark case (count_instructions.sh, about 30 s) and
# checks them against bench/instruction_budgets.txt. With a directory, its verdicts go there as
# JUnit XML too (make test's results). Exits non-zero when a case is over its budget.
set -euo pipefail
. "$(dirname "$0")/workspace.sh"
table="$WS/instructions.log"
# (A result left by an earlier check must not stand for this one.)
[ $# -eq 0 ] || rm -f "$1/instruction_budgets.xml"
bash "$repo/scripts/count_instructions.sh" '.' > "$table" 2>&1 || { cat "$table"; exit 1; }
cat "$table"
junit=()
if [ $# -gt 0 ]; then
  mkdir -p "$1"
  junit=(--junit "$1/instruction_budgets.xml")
fi
/usr/bin/python3 "$repo/scripts/check_budgets.py" "$repo/bench/instruction_budgets.txt" "$table" \
  "${junit[@]}"
