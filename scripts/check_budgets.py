"""Checks the instructions a step of the benchmark's cases against their budgets.

Usage: check_budgets.py BUDGETS TABLE [--junit FILE]

BUDGETS is bench/instruction_budgets.txt; TABLE what count_instructions.sh printed for the cases
it names. Each rule is a check: it prints what it found, and with --junit writes one test case
per rule (count_results.py counts them with make test's others). Exits 1 when a rule fails.
"""
import re
import sys
import xml.etree.ElementTree as ET


def read_rules(path):
    """The rules of a budgets file, as (kind, regex, limit, where)."""
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
            rules.append((kind, pattern, regex, limit, where))
    return rules


def read_counts(path):
    """Case name -> instructions a step, from count_instructions.sh's table, in its order."""
    counts = {}
    with open(path) as f:
        for line in f:
            words = line.split()
            if len(words) == 3 and words[0].startswith("BM_") and words[1].isdigit():
                counts[words[0]] = int(words[1])
    return counts


def check(rule, counts):
    """The rule's verdict: (passed, message)."""
    kind, pattern, regex, limit, where = rule
    cases = [c for c in counts if regex.fullmatch(c)]
    if not cases:
        return False, f"{where}: no benchmark case matches '{pattern}'"
    if kind == "budget":
        over = [f"{c} {counts[c]}" for c in cases if counts[c] > limit]
        if over:
            return False, (f"{where}: over the budget of {limit:.0f} instructions a step: "
                           + ", ".join(over))
        most = max(counts[c] for c in cases)
        return True, f"{pattern}: at most {most} instructions a step, within {limit:.0f}"
    first = counts[cases[0]]
    ratios = {c: counts[c] / first for c in cases}
    worst = max(ratios, key=ratios.get)
    message = (f"{pattern}: {min(ratios.values()):.3f} to {ratios[worst]:.3f} times {cases[0]}, "
               f"at most {limit} ({worst}: {counts[worst]} instructions a step against {first})")
    if ratios[worst] > limit:
        return False, f"{where}: {message}"
    return True, message


def main():
    args = sys.argv[1:]
    junit = None
    if "--junit" in args:
        i = args.index("--junit")
        junit = args[i + 1] if i + 1 < len(args) else sys.exit("--junit needs a file")
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    rules, counts = read_rules(args[0]), read_counts(args[1])
    suite = ET.Element("testsuite", name="instruction_budgets")
    failed = 0
    for rule in rules:
        passed, message = check(rule, counts)
        print(("" if passed else "FAILED: ") + message)
        case = ET.SubElement(suite, "testcase", classname="InstructionBudgets",
                             name=f"{rule[0]} {rule[1]}")
        if not passed:
            failed += 1
            ET.SubElement(case, "failure", message=message)
    # A case the benchmark gained without a budget is unchecked: that is a failure too.
    budgeted = [rule[2] for rule in rules if rule[0] == "budget"]
    unbudgeted = [c for c in counts if not any(r.fullmatch(c) for r in budgeted)]
    case = ET.SubElement(suite, "testcase", classname="InstructionBudgets",
                         name="every case has a budget")
    if unbudgeted:
        failed += 1
        message = f"{args[0]}: no budget for " + ", ".join(unbudgeted)
        print("FAILED: " + message)
        ET.SubElement(case, "failure", message=message)
    if junit:
        ET.ElementTree(suite).write(junit)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
