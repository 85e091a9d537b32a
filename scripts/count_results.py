"""Counts the test cases in JUnit XML result files and prints "N passed, N failed", after the
name and the first and last lines of the text of each case that failed.

Exits 1 when any case failed, when a test left no result (catkin writes a MISSING-*.xml then),
or when no case ran at all. Usage: count_results.py DIR [--also-failed WHAT]...
"""
import pathlib
import sys
import xml.etree.ElementTree as ET

WHY_LINES = 4  # of each failure's text, printed under its name (and its last line)


def why(problem):
    """The first lines of a failure's text and its last (rosunit puts an assertion's message
    before its traceback, gtest and unittest's own runner after), indented."""
    text = (problem.text or "").strip() or problem.get("message", "")
    lines = [line for line in text.splitlines() if line.strip()]
    if len(lines) > WHY_LINES:
        lines = lines[:WHY_LINES - 1] + ["..."] + lines[-1:]
    return "".join("\n    " + line[:300] for line in lines)


def count(directory):
    passed, failed, names = 0, 0, []
    for path in sorted(pathlib.Path(directory).rglob("*.xml")):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            failed += 1
            names.append(f"{path.name} (unreadable result file)")
            continue
        cases = list(root.iter("testcase"))
        if not cases:  # a suite that produced no cases, e.g. a crashed test binary
            if int(root.get("failures", 0)) + int(root.get("errors", 0)) > 0:
                failed += 1
                names.append(path.name)
            continue
        # rostest's own file has one case per <test> node, whose cases are counted from their own
        # rosunit-*.xml files: it adds only its failures (a test node that crashed or timed out).
        wrapper = path.name.startswith("rostest-")
        for case in cases:
            problem = case.find("failure")
            if problem is None:
                problem = case.find("error")
            if problem is not None:
                failed += 1
                names.append(f"{case.get('classname')}.{case.get('name')}{why(problem)}")
            elif case.find("skipped") is None and not wrapper:
                passed += 1
    return passed, failed, names


def main():
    args = sys.argv[1:]
    passed, failed, names = count(args[0] if args else ".")
    for i, arg in enumerate(args):  # steps that failed before leaving results, e.g. the build
        if arg == "--also-failed" and i + 1 < len(args):
            failed += 1
            names.append(args[i + 1])
    for name in names:
        print(f"FAILED: {name}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
