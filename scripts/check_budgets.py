"""Checks the instructions a step of the benchmark's cases against their budgets.

Usage: check_budgets.py BUDGETS TABLE [--junit FILE]

BUDGETS is bench/instruction_budgets.txt; TABLE what count_instructions.sh printed for the cases
it names. Each rule is a check: it prints what it found, and with --junit writes one test case
per rule (count_results.py counts them with make test's others). Exits 1 when a rule fails.
"""
import collections
import re
import sys
import xml.etree.ElementTree as ET

# One line of a budgets file: its kind ("budget" or "flat"), case regex (as written and compiled),
# limit, and file:line.
Rule = collections.namedtuple("Rule", "kind pattern regex limit where")


def read_rules(path):
    """The rules of a budgets file."""
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
            rules.append(Rule(kind, pattern, regex, limit, where))
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
    cases = [c for c in counts if rule.regex.fullmatch(c)]
    if not cases:
        return False, f"{rule.where}: no benchmark case matches '{rule.pattern}'"
    if rule.kind == "budget":
        over = [f"{c} {counts[c]}" for c in cases if counts[c] > rule.limit]
        if over:
            return False, (f"{rule.where}: over the budget of {rule.limit:.0f} instructions a "
                           "step: " + ", ".join(over))
        most = max(counts[c] for c in cases)
        return True, f"{rule.pattern}: at most {most} instructions a step, within {rule.limit:.0f}"
    first = counts[cases[0]]
    ratios = {c: counts[c] / first for c in cases}
    worst = max(ratios, key=ratios.get)
    message = (f"{rule.pattern}: {min(ratios.values()):.3f} to {ratios[worst]:.3f} times "
               f"{cases[0]}, at most {rule.limit} ({worst}: {counts[worst]} instructions a step "
               f"against {first})")
    if ratios[worst] > rule.limit:
        return False, f"{rule.where}: {message}"
    return True, message


def every_case_budgeted(rules, counts, path):
    """A case the benchmark gained without a budget goes unchecked: that is a failure too."""
    budgets = [rule.regex for rule in rules if rule.kind == "budget"]
    unbudgeted = [c for c in counts if not any(r.fullmatch(c) for r in budgets)]
    if unbudgeted:
        return False, f"{path}: no budget for " + ", ".join(unbudgeted)
    return True, f"every one of the {len(counts)} cases has a budget"


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
    verdicts = [(f"{rule.kind} {rule.pattern}", *check(rule, counts)) for rule in rules]
    verdicts.append(("every case has a budget", *every_case_budgeted(rules, counts, args[0])))
    suite = ET.Element("testsuite", name="instruction_budgets")
    for name, passed, message in verdicts:
        print(("" if passed else "FAILED: ") + message)
        case = ET.SubElement(suite, "testcase", classname="InstructionBudgets", name=name)
        if not passed:
            ET.SubElement(case, "failure", message=message)
    if junit:
        ET.ElementTree(suite).write(junit)
    return 0 if all(passed for _, passed, _ in verdicts) else 1


if __name__ == "__main__":
    sys.exit(main())
