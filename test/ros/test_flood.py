#!/usr/bin/env python3
"""rostest of marble_maze_node under a flood (run by flood.test): tilt_flood publishes tilt
commands at 10 kHz for 10 s, each stamped now and numbered in its roll. Checks that
  - marble_state keeps coming at 50 Hz of ROS time (+-15 %): rostest's own hztest, run during the
    flood (rostest runs a launch file's tests one after another, so the test starts it), and a
    count here; in each second of it, half the states arrive within 0.1 s of their stamps: the
    node keeps its step rate (a median, which this process's own hiccups do not move);
  - the node's resident memory (VmRSS) during and after the flood stays within 30 MB of what it
    was before: the queues are bounded (a tilt subscription of 100, a command queue of 10,000);
  - the commands it applies (the TILT inputs it publishes on `inputs`, numbered by the flood)
    come in the order of their stamps: each roll above the one before, each step at or after
    the one before;
  - the flood flooded: at least 90,000 commands sent, and of the inputs it published the test
    heard at least half (a Python subscriber at 10 kHz may drop some; the order is checked on
    those heard).
"""
import subprocess
import sys
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rosnode
import rospy
import rostest

from marble_maze.msg import MarbleState, SimInput

PKG = "marble_maze"
NODE = "/marble_maze"
RSS_BOUND_KB = 30 * 1024


def resident_kb(pid):
    with open("/proc/%d/status" % pid) as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise AssertionError("no VmRSS for pid %d" % pid)


def node_pid(name):
    deadline = time.time() + 30
    while time.time() < deadline:
        try:
            uri = rosnode.get_api_uri(rosgraph.Master("/test_flood"), name)
            if uri:
                return xmlrpc.client.ServerProxy(uri).getPid("/test_flood")[2]
        except Exception:  # not up yet
            pass
        time.sleep(0.2)
    raise AssertionError("node %s not found" % name)


class FloodTest(unittest.TestCase):
    def test_flood(self):
        lock = threading.Lock()
        states, inputs = [], []

        def on_state(msg):
            with lock:
                states.append((msg.header.stamp.to_sec(), rospy.get_time()))

        def on_input(msg):
            if msg.kind == SimInput.TILT:
                with lock:
                    inputs.append((msg.roll, msg.step))

        rospy.Subscriber("marble_state", MarbleState, on_state, queue_size=1000)
        rospy.Subscriber("inputs", SimInput, on_input, queue_size=200000, tcp_nodelay=True)
        pid = node_pid(NODE)
        time.sleep(3.0)  # the node settled: its maze, markers and first states out
        before = resident_kb(pid)

        rospy.set_param("/tilt_flood/start", True)
        begin = rospy.get_time()
        hztest = subprocess.Popen(
            ["/usr/bin/python3", "/usr/share/rostest/nodes/hztest", "--text", "__name:=hz_flood",
             "_topic:=marble_state", "_hz:=50.0", "_hzerror:=7.5", "_test_duration:=6.0",
             "_wait_time:=5.0"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        during = []
        deadline = time.time() + 60
        while not rospy.get_param("/tilt_flood/done", False):
            self.assertLess(time.time(), deadline, "the flood never ended")
            during.append(resident_kb(pid))
            time.sleep(0.25)
        end = rospy.get_time()
        hz_output = hztest.communicate(timeout=30)[0]
        time.sleep(2.0)
        after = resident_kb(pid)
        sent = rospy.get_param("/tilt_flood/sent")
        with lock:
            flood_states = [s for s in states if begin + 1 <= s[0] <= end - 1]
            heard = list(inputs)
        summary = ("flood: %d commands sent; %d applied inputs heard; RSS before %d kB, most "
                   "during %d kB, after %d kB; %d states in %.1f s"
                   % (sent, len(heard), before, max(during), after, len(flood_states),
                      end - begin - 2))
        print(summary)

        self.assertGreaterEqual(sent, 90000, summary)
        self.assertEqual(hztest.returncode, 0, "hztest during the flood:\n" + hz_output)
        rate = len(flood_states) / (end - begin - 2)
        self.assertAlmostEqual(rate, 50.0, delta=7.5, msg=summary)
        # How far the node's states lag ROS time, second by second: the median of each second,
        # which a hiccup of this test's own process (busy hearing 10 kHz of inputs) does not move.
        # A node that fell behind its step rate would lag more and more.
        by_second = {}
        for stamp, received in flood_states:
            by_second.setdefault(int(stamp - begin), []).append(received - stamp)
        medians = [sorted(lags)[len(lags) // 2] for _, lags in sorted(by_second.items())]
        self.assertLess(max(medians), 0.1, "marble_state fell behind ROS time: the median lag "
                        "of each second %s" % ["%.3f" % m for m in medians])
        self.assertLess(max(during) - before, RSS_BOUND_KB, summary)
        self.assertLess(after - before, RSS_BOUND_KB, summary)
        self.assertGreaterEqual(len(heard), sent // 2, summary)
        for (roll_a, step_a), (roll_b, step_b) in zip(heard, heard[1:]):
            self.assertGreater(roll_b, roll_a, "a command applied out of stamp order")
            self.assertGreaterEqual(step_b, step_a)


if __name__ == "__main__":
    rospy.init_node("test_flood")
    rostest.rosrun(PKG, "flood", FloodTest, sys.argv)
