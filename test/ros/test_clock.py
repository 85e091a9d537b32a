#!/usr/bin/env python3
"""rostest of ~clock (run by clock.test): the node owns /clock. Run free (real_time_factor 0) it
reaches at least MIN_FREE times real time; at real_time_factor 20 it keeps within 20% of it and
publishes marble_state at 50 Hz of simulated time (within 1 a second). Paused, its clock stands
and goes on being said. Wall time is measured here with time.time(): rospy follows /clock."""
import threading
import time
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

from marble_maze.msg import MarbleState

MIN_FREE = 100  # times real time, run free (measured: about 2000 on the development machine)


class ClockTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.clock = None
        self.stamps = []
        rospy.Subscriber("/clock", Clock, self.on_clock, queue_size=1)
        rospy.Subscriber("marble_state", MarbleState, self.on_state, queue_size=100000)

    def on_clock(self, msg):
        with self.lock:
            self.clock = msg.clock.to_sec()

    def on_state(self, msg):
        with self.lock:
            self.stamps.append(msg.header.stamp.to_sec())

    def factor_over(self, wall):
        deadline = time.time() + 20
        while self.clock is None and time.time() < deadline:
            time.sleep(0.05)
        with self.lock:
            c0 = self.clock
        t0 = time.time()
        time.sleep(wall)
        with self.lock:
            c1 = self.clock
        return (c1 - c0) / (time.time() - t0), c0, c1

    def test_free_then_at_a_factor(self):
        free, _, _ = self.factor_over(2.0)
        print("run free: %.0f times real time" % free)
        self.assertGreater(free, MIN_FREE)
        Client("/marble_maze", timeout=20).update_configuration({"real_time_factor": 20.0})
        time.sleep(1.0)
        factor, c0, c1 = self.factor_over(3.0)
        print("at real_time_factor 20: %.2f times real time" % factor)
        self.assertAlmostEqual(factor, 20.0, delta=4.0)
        with self.lock:
            inside = [s for s in self.stamps if c0 < s <= c1]
        rate = len(inside) / (c1 - c0)
        print("marble_state: %.2f per second of simulated time" % rate)
        self.assertAlmostEqual(rate, 50.0, delta=1.0)
        # At 100 times real time a millisecond's timer tick is 0.1 s of simulated time: /clock
        # still moves by at most one state period (20 ms) at a time.
        Client("/marble_maze", timeout=20).update_configuration({"real_time_factor": 100.0})
        said = []
        sub = rospy.Subscriber("/clock", Clock, lambda m: said.append(m.clock.to_sec()),
                               queue_size=100000)
        time.sleep(2.0)
        sub.unregister()
        gaps = sorted(b - a for a, b in zip(said, said[1:]) if b > a)
        median = gaps[len(gaps) // 2]
        print("/clock at factor 100: %d said, median gap %.4f s" % (len(said), median))
        self.assertGreater(len(gaps), 1000)
        self.assertLessEqual(gaps[len(gaps) // 2], 0.02 + 1e-9)

    def test_paused_the_clock_stands_and_is_still_said(self):
        # Paused, ROS time (the node's) stands still, and /clock goes on being said: a node
        # started meanwhile knows the time (nothing came: rostopic asked whether /clock was
        # published).
        pause = rospy.ServiceProxy("/pause", Trigger)
        resume = rospy.ServiceProxy("/resume", Trigger)
        rospy.wait_for_service("/pause", timeout=20)
        self.assertTrue(pause().success)
        try:
            time.sleep(0.5)
            heard = []
            sub = rospy.Subscriber("/clock", Clock, lambda m: heard.append(m.clock.to_nsec()))
            time.sleep(1.0)
            sub.unregister()
            self.assertGreater(len(heard), 5, "/clock not said while paused")
            self.assertEqual(len(set(heard)), 1, "the clock moved while paused")
        finally:
            resume()
        factor, _, _ = self.factor_over(1.0)
        self.assertGreater(factor, 1.0)  # and it runs again


if __name__ == "__main__":
    rospy.init_node("test_clock")
    rostest.rosrun("marble_maze", "clock", ClockTest)
