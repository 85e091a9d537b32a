#!/usr/bin/env python3
"""rostest of the example agent in lockstep with the node in one process: their nodelets in one
manager (lockstep_pair.test) or both on one thread (lockstep_in_process.test), control period
0.02 s, 1000 periods. The states answer exactly 1000 commands, one period apart, and stop."""
import threading
import time
import unittest

import rospy
import rostest

from marble_maze.msg import MarbleState

PERIOD_NS = 20 * 10**6
# As both launch files set the agent's periods: no more than the node's marble_state queue holds
# (kCommandBurst), since the pair outruns this test's subscriber and a longer burst would drop
# the oldest states before they reach it.
PERIODS = 1000


class LockstepPairTest(unittest.TestCase):
    def test_the_agent_takes_exactly_its_periods_one_period_apart(self):
        stamps, arrived = [], threading.Condition()

        def on_state(msg):
            with arrived:
                stamps.append(msg.header.stamp.to_nsec())
                arrived.notify()

        rospy.Subscriber("marble_state", MarbleState, on_state, queue_size=10000)
        with arrived:  # (the agent starts 5 s after it sees the node)
            self.assertTrue(arrived.wait_for(lambda: stamps and stamps[-1] >= PERIODS * PERIOD_NS,
                                             timeout=40), "%d states" % len(stamps))
        time.sleep(1.0)  # none after the last
        with arrived:
            answers = [s for s in stamps if s > 0]
        self.assertEqual(answers, [k * PERIOD_NS for k in range(1, PERIODS + 1)])


if __name__ == "__main__":
    rospy.init_node("test_lockstep_pair")
    rostest.rosrun("marble_maze", "lockstep_pair", LockstepPairTest)
