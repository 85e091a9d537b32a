"""Runs a Python test script's cases as catkin's run_tests calls it: with --gtest_output=xml:PATH,
unittest's text runner, and each case's result written to PATH as JUnit XML, a skipped case
marked <skipped> (rosunit's writer reports one as passed, and scripts/count_results.py would count
it so); without the option, unittest's own main.

    if __name__ == "__main__":
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
        import xml_results
        xml_results.main()
"""
import os
import re
import sys
import time
import unittest
import xml.etree.ElementTree as ET

OPTION = "--gtest_output=xml:"
# What XML 1.0 cannot hold (the colour codes of a launch's output in a message, say): left out.
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def _names(test):
    """The class's name and the case's of a test, a subtest (the case's name with its
    parameters) or a class's or module's set-up error (no class; its description)."""
    case = getattr(test, "test_case", test)
    if not isinstance(case, unittest.TestCase):
        return "", test.id()
    classname = "%s.%s" % (type(case).__module__, type(case).__qualname__)
    return classname, test.id()[len(classname) + 1:]


class _Recorder(unittest.TextTestResult):
    """unittest's text result, which also keeps each case's outcome and time."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # Each case's (class, name, seconds, outcome: None, failure, error or skipped, text), by
        # its id: a case that failed and then erred in its tearDown is one case that failed.
        self.cases = {}
        self._began = time.perf_counter()

    def _keep(self, test, outcome=None, text=""):
        kept = self.cases.get(test.id())
        if kept is None or kept[3] is None:
            self.cases[test.id()] = (*_names(test), time.perf_counter() - self._began, outcome,
                                     text)

    def startTest(self, test):
        self._began = time.perf_counter()
        super().startTest(test)

    def addSuccess(self, test):
        super().addSuccess(test)
        self._keep(test)

    def addFailure(self, test, err):
        super().addFailure(test, err)
        self._keep(test, "failure", self.failures[-1][1])

    def addError(self, test, err):
        super().addError(test, err)
        self._keep(test, "error", self.errors[-1][1])

    def addSubTest(self, test, subtest, err):
        super().addSubTest(test, subtest, err)
        if err is not None:  # (a case whose subtest failed gets no addFailure of its own)
            failed = issubclass(err[0], test.failureException)
            self._keep(subtest, "failure" if failed else "error",
                       (self.failures if failed else self.errors)[-1][1])

    def addSkip(self, test, reason):
        super().addSkip(test, reason)
        self._keep(test, "skipped", reason)

    def addExpectedFailure(self, test, err):
        super().addExpectedFailure(test, err)
        self._keep(test)

    def addUnexpectedSuccess(self, test):
        super().addUnexpectedSuccess(test)
        self._keep(test, "failure", "passed where it was expected to fail")


def write(path, name, cases, seconds):
    """The cases, as _Recorder keeps them, as a JUnit XML test suite in `path`."""
    count = {kind: sum(1 for case in cases if case[3] == kind)
             for kind in ("failure", "error", "skipped")}
    suite = ET.Element("testsuite", name=name, tests=str(len(cases)),
                       failures=str(count["failure"]), errors=str(count["error"]),
                       skipped=str(count["skipped"]), time="%.3f" % seconds)
    for classname, case_name, case_seconds, outcome, text in cases:
        case = ET.SubElement(suite, "testcase", classname=classname, name=case_name,
                             time="%.4f" % case_seconds)
        if outcome:
            text = _NOT_XML.sub("", text)
            lines = text.strip().splitlines()
            ET.SubElement(case, outcome, message=lines[-1] if lines else "").text = text
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)


def main():
    """Runs the cases of the script run as __main__; exits 1 when any failed."""
    paths = [arg[len(OPTION):] for arg in sys.argv[1:] if arg.startswith(OPTION)]
    if not paths:
        unittest.main(module="__main__")
        return
    cases = unittest.defaultTestLoader.loadTestsFromModule(sys.modules["__main__"])
    began = time.perf_counter()
    result = unittest.TextTestRunner(verbosity=2, resultclass=_Recorder).run(cases)
    name = os.path.splitext(os.path.basename(sys.argv[0]))[0]
    write(paths[-1], name, list(result.cases.values()), time.perf_counter() - began)
    sys.exit(0 if result.wasSuccessful() else 1)
