"""Checks the instructions a step of the benchmark's cases against their budgets.

Usage: check_budgets.py BUDGETS TABLE [--junit FILE]

BUDGETS is bench/instruction_budgets.txt; TABLE what count_instructions.sh printed. Each rule
is a check, and so is "every case has a budget": each prints what it found, and with --junit
is written as one test case (count_results.py counts them with make test's others). Exits 1
when a check fails.
"""
import argparse
import collections
import math
import re
import sys
import xml.etree.ElementTree as ET

# One line of a budgets file: its kind ("budget" or "flat"), case regex, limit, and file:line.
Rule = collections.namedtuple("Rule", "kind regex limit where")


def read_rules(path):
    """The rules of a budgets file; a line that is not one stops the check, naming it."""
    rules = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            where = f"{path}:{number}"
            if len(words) != 3 or words[0] not in ("budget", "flat"):
                sys.exit(f"{where}: expected 'budget <case regex> <instructions>' or "
                         f"'flat <case regex> <ratio>', got: {line.strip()}")
            kind, pattern, limit = words
            try:
                regex = re.compile(pattern)
                limit = float(limit)
            except (re.error, ValueError) as e:
                sys.exit(f"{where}: {e}")
            if not (math.isfinite(limit) and limit > 0):
                sys.exit(f"{where}: the limit must be a positive number, got {words[2]}")
            rules.append(Rule(kind, regex, limit, where))
    return rules


def read_counts(path):
    """Case name -> instructions a step, from count_instructions.sh's table."""
    counts = {}
    with open(path) as f:
        for line in f:
            words = line.split()
            if len(words) == 3 and words[0].startswith("BM_") and words[1].isdigit():
                counts[words[0]] = int(words[1])
    return counts


def check(rule, counts):
    """The rule's verdict: (passed, message)."""
    pattern = rule.regex.pattern
    cases = {c: n for c, n in counts.items() if rule.regex.fullmatch(c)}
    if not cases:
        return False, f"{rule.where}: no benchmark case matches '{pattern}'"
    costliest = max(cases, key=cases.get)
    if rule.kind == "budget":
        over = [f"{c} {n}" for c, n in cases.items() if n > rule.limit]
        if over:
            return False, (f"{rule.where}: over the budget of {rule.limit:.0f} instructions a "
                           "step: " + ", ".join(over))
        return True, (f"{pattern}: at most {cases[costliest]} instructions a step, within "
                      f"{rule.limit:.0f}")
    cheapest = min(cases, key=cases.get)
    ratio = cases[costliest] / cases[cheapest] if cases[cheapest] > 0 else math.inf
    message = (f"{pattern}: the costliest, {costliest} ({cases[costliest]}), is {ratio:.3f} "
               f"times the cheapest, {cheapest} ({cases[cheapest]}), at most {rule.limit}")
    if ratio > rule.limit:
        return False, f"{rule.where}: {message}"
    return True, message


def every_case_budgeted(rules, counts, path):
    """A case the benchmark gained without a budget goes unchecked: that is a failure too."""
    if not counts:
        return False, "the table has no case: the count printed nothing"
    budgets = [rule.regex for rule in rules if rule.kind == "budget"]
    unbudgeted = [c for c in counts if not any(r.fullmatch(c) for r in budgets)]
    if unbudgeted:
        return False, f"{path}: no budget for " + ", ".join(unbudgeted)
    return True, f"every one of the {len(counts)} cases has a budget"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("budgets")
    parser.add_argument("table")
    parser.add_argument("--junit", help="write the verdicts here as JUnit XML")
    args = parser.parse_args()
    rules, counts = read_rules(args.budgets), read_counts(args.table)
    verdicts = [(f"{rule.kind} {rule.regex.pattern}", *check(rule, counts)) for rule in rules]
    verdicts.append(("every case has a budget", *every_case_budgeted(rules, counts, args.budgets)))
    suite = ET.Element("testsuite", name="instruction_budgets")
    for name, passed, message in verdicts:
        print(("" if passed else "FAILED: ") + message)
        case = ET.SubElement(suite, "testcase", classname="InstructionBudgets", name=name)
        if not passed:
            ET.SubElement(case, "failure", message=message)
    if args.junit:
        ET.ElementTree(suite).write(args.junit)
    return 0 if all(passed for _, passed, _ in verdicts) else 1


if __name__ == "__main__":
    sys.exit(main())
