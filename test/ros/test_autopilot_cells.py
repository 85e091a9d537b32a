#!/usr/bin/env python3
"""rostest of the autopilot from ten cells of the classic maze (run by autopilot_cells.test): in
every namespace cell_I_J the marble reaches the goal within 40 s of ROS time, with no hole."""
import threading
import time
import unittest

import rosgraph
import rospy
import rostest

from marble_maze.msg import MazeEvent

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
        lock, seen = threading.Lock(), {t: [] for t in topics}
        for topic in topics:
            rospy.Subscriber(topic, MazeEvent,
                             lambda e, t=topic: (lock.acquire(), seen[t].append(e), lock.release()),
                             queue_size=1000)
        start = rospy.Time.now()

        def done(events):
            return any(e.kind in (MazeEvent.GOAL, MazeEvent.HOLE, MazeEvent.OFF_BOARD)
                       for e in events)

        deadline = time.time() + LIMIT + 20
        while time.time() < deadline:
            with lock:
                if all(done(e) for e in seen.values()):
                    break
            time.sleep(0.2)
        with lock:
            for topic, events in sorted(seen.items()):
                ends = [e for e in events if e.kind != MazeEvent.COLLISION]
                self.assertTrue(ends, "%s: no goal" % topic)
                self.assertEqual(ends[0].kind, MazeEvent.GOAL, "%s: fell in" % topic)
                took = (ends[0].header.stamp - start).to_sec()
                print("%s: goal after %.1f s" % (topic, took))
                self.assertLess(took, LIMIT, topic)


if __name__ == "__main__":
    rospy.init_node("test_autopilot_cells")
    rostest.rosrun("marble_maze", "autopilot_cells", AutopilotCellsTest)
