#!/usr/bin/env python3
"""rostest of the autopilot from ten cells of the classic maze (run by autopilot_cells.test): in
every namespace cell_I_J the marble reaches the goal within 40 s of ROS time, with no hole.

Each marble's end is read from its marble_state (at_goal, in_hole, off_board: held while the
marble stays there) rather than from its events, which are not latched: a marble a few seconds
from the goal got there before this test, started late on a loaded machine, had subscribed."""
import threading
import time
import unittest

import rosgraph
import rospy
import rostest

from marble_maze.msg import MarbleState

LIMIT = 40.0  # s of ROS time from the first event to the goal, at most


class AutopilotCellsTest(unittest.TestCase):
    def test_every_cell_reaches_the_goal(self):
        def event_topics():
            return sorted(t for t, _ in rosgraph.Master("/test").getTopicTypes()
                          if t.startswith("/cell_") and t.endswith("/events"))

        deadline = time.time() + 20
        topics = event_topics()
        while len(topics) < 10 and time.time() < deadline:
            time.sleep(0.5)
            topics = event_topics()
        self.assertEqual(len(topics), 10, topics)
        lock, ends = threading.Lock(), {}

        def on_state(state, cell):
            with lock:
                if cell not in ends and (state.at_goal or state.in_hole or state.off_board):
                    ends[cell] = state  # the first state that shows the end

        cells = [t[:-len("/events")] for t in topics]
        for cell in cells:
            rospy.Subscriber(cell + "/marble_state", MarbleState, on_state, cell, queue_size=100)
        start = rospy.Time.now()
        deadline = time.time() + LIMIT + 20
        while time.time() < deadline:
            with lock:
                if len(ends) == len(cells):
                    break
            time.sleep(0.2)
        with lock:
            for cell in cells:
                self.assertIn(cell, ends, "%s: no goal" % cell)
                self.assertTrue(ends[cell].at_goal, "%s: fell in" % cell)
                # (A marble at the goal before this test heard it counts from the test's start.)
                took = max(0.0, (ends[cell].header.stamp - start).to_sec())
                print("%s: at the goal %.1f s into the test" % (cell, took))
                self.assertLess(took, LIMIT, cell)


if __name__ == "__main__":
    rospy.init_node("test_autopilot_cells")
    rostest.rosrun("marble_maze", "autopilot_cells", AutopilotCellsTest)
