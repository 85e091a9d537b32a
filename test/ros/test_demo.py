"""The headless demo as `make demo` runs it without a display (scripts/demo.sh): the autopilot
brings the marble to the classic maze's goal, the summary says how long it took, the demo stops
by itself with exit status 0, and roslaunch prints no dead-process banner.

Runs the demo on a master of its own (a free port), in the workspace given by MARBLE_MAZE_WS.
Plain unittest: python3 test/ros/test_demo.py; with --gtest_output=xml:FILE it writes JUnit XML
for catkin. About 20 s.
"""
import os
import re
import socket
import subprocess
import sys
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "demo.sh")


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


class DemoTest(unittest.TestCase):
    def test_headless_demo_reaches_the_goal_and_ends_cleanly(self):
        env = dict(os.environ)
        env.pop("DISPLAY", None)
        env["ROS_MASTER_URI"] = "http://localhost:%d" % free_port()
        run = subprocess.run(["bash", SCRIPT], env=env, stdin=subprocess.DEVNULL,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             timeout=240)
        output = run.stdout
        self.assertEqual(run.returncode, 0, output[-3000:])
        took = re.search(r"summary: the marble reached the goal in ([0-9.]+) s", output)
        self.assertTrue(took, output[-3000:])
        self.assertLess(float(took.group(1)), 60)
        self.assertNotIn("REQUIRED process", output)
        self.assertNotIn("has died", output)
        self.assertNotIn("HOLE", output)


if __name__ == "__main__":
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import xml_results
    xml_results.main()
