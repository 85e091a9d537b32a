#!/usr/bin/env python3
"""rostest of the autopilot playing a maze through the package's public topics (run by
autopilot_classic.test, autopilot_prototype.test and autopilot_no_route.test).

Private parameters of this test: ~maze (the maze file the node loaded), ~expect ("goal": the
marble reaches a goal within ~limit seconds of ROS time with no hole on the way; "no_route": the
autopilot says so and stops), ~reconfigure_after (s of wall time into the play: the node's
restitution is changed through dynamic_reconfigure, which publishes `maze` again, and the
autopilot steers on along its route instead of starting over; unset: no change), ~load (a maze
the test loads through `load_maze` once the autopilot plays: it plays the new maze from its start
and reaches its goal, whatever states of the old maze it still hears; unset: none). It also
checks the latched `maze` topic against the maze file: its name, slots, solid tiles, start, goals
and holes, read here from the YAML independently of the package's parser.
"""
import threading
import time
import unittest

import rospy
import rostest
import yaml
from dynamic_reconfigure.client import Client
from std_msgs.msg import String

from marble_maze.msg import MarbleState, MazeDescription, MazeEvent
from marble_maze.srv import LoadMaze

WALL = "+-|#"


def tiles_from_file(path):
    """(name, slots (x, y, z), solid tiles as a set of (i, j, k), start, goals, holes), as
    doc/maze_format.md defines them."""
    with open(path) as f:
        doc = yaml.safe_load(f)
    if "layout" in doc:  # a flat maze: a floor slab under everything but the holes, then walls
        walls = doc["layout"].rstrip("\n").split("\n")
        plans = [["".join(" " if ch == "O" else "#" for ch in row) for row in walls], walls]
    else:
        plans = [p.rstrip("\n").split("\n") for p in doc["layers"]]
    ny, nx = len(plans[0]), len(plans[0][0])
    solid, start, goals = set(), None, []
    for k, rows in enumerate(plans):
        for line, row in enumerate(rows):
            j = ny - 1 - line  # the top line is the largest y
            for i, ch in enumerate(row):
                if ch in WALL:
                    solid.add((i, j, k))
                elif ch == "S":
                    start = (i, j)
                elif ch == "G":
                    goals.append((i, j))
    holes = sorted((i, j) for j in range(ny) for i in range(nx) if (i, j, 0) not in solid)
    return doc.get("name"), (nx, ny, len(plans)), solid, start, sorted(goals), holes


class AutopilotTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.maze = None
        self.states, self.events, self.statuses = [], [], []
        rospy.Subscriber("maze", MazeDescription, self.keep("maze"), queue_size=1)
        rospy.Subscriber("marble_state", MarbleState, self.keep("states"), queue_size=100)
        rospy.Subscriber("events", MazeEvent, self.keep("events"), queue_size=1000)
        rospy.Subscriber("autopilot/status", String, self.keep("statuses"), queue_size=10)

    def keep(self, name):
        def store(msg):
            with self.lock:
                if isinstance(getattr(self, name), list):
                    getattr(self, name).append(msg)
                else:
                    setattr(self, name, msg)
        return store

    def wait(self, predicate, timeout, what):
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                if predicate():
                    return
            time.sleep(0.05)
        self.fail("no %s within %g s of wall time" % (what, timeout))

    def test_maze_topic_describes_the_file(self):
        self.wait(lambda: self.maze is not None, 20, "latched maze message")
        name, slots, solid, start, goals, holes = tiles_from_file(rospy.get_param("~maze"))
        m = self.maze
        self.assertEqual(m.name, name)
        self.assertEqual(tuple(m.slots), slots)
        nx, ny, nz = slots
        got = {(i, j, k) for k in range(nz) for j in range(ny) for i in range(nx)
               if m.solid[i + nx * (j + ny * k)]}
        self.assertEqual(got, solid)
        self.assertEqual((m.start.i, m.start.j), start)
        self.assertEqual(sorted((g.i, g.j) for g in m.goals), goals)
        self.assertEqual(sorted((h.i, h.j) for h in m.holes), holes)
        self.assertGreater(m.tilt_limit, 0)

    def test_plays(self):
        expect = rospy.get_param("~expect")
        if expect == "goal":
            limit = rospy.get_param("~limit")
            self.wait(lambda: self.states, 20, "marble_state")
            with self.lock:
                start = self.states[0].header.stamp
            change_after = rospy.get_param("~reconfigure_after", None)
            load = rospy.get_param("~load", None)
            if change_after is not None or load is not None:  # both act once it plays
                self.wait(lambda: any("playing" in m.data for m in self.statuses), 20, "playing")
            if change_after is not None:
                time.sleep(change_after)
                Client("marble_maze", timeout=10).update_configuration({"restitution": 0.4})
            if load is not None:
                time.sleep(1.0)
                rospy.wait_for_service("load_maze", 10)
                answer = rospy.ServiceProxy("load_maze", LoadMaze)(load)
                self.assertTrue(answer.success, answer.message)
                with self.lock:
                    start = self.states[-1].header.stamp
            self.wait(lambda: any(e.kind == MazeEvent.GOAL for e in self.events), limit * 2 + 20,
                      "goal")
            with self.lock:
                goal = next(e for e in self.events if e.kind == MazeEvent.GOAL)
                holes = [e for e in self.events if e.kind in (MazeEvent.HOLE, MazeEvent.OFF_BOARD)]
            took = (goal.header.stamp - start).to_sec()
            print("reached the goal in %.2f s of ROS time" % took)
            self.assertFalse(holes, "fell in before the goal")
            self.assertLess(took, limit)
            if change_after is not None:  # one play, from the start to the goal
                # (The autopilot says so once its timer sees the goal in a state: after the event.)
                self.wait(lambda: any("reached the goal" in m.data for m in self.statuses), 10,
                          "'reached the goal' on autopilot/status")
                with self.lock:
                    said = [m.data for m in self.statuses]
                self.assertEqual(sum("playing" in m for m in said), 1, said)
        else:
            self.wait(lambda: self.statuses and "no route" in self.statuses[-1].data, 20,
                      "'no route' on autopilot/status")
            # And it stopped: the marble stays on the start.
            time.sleep(2.0)
            with self.lock:
                moved = self.states[-1].position_in_board
                first = self.states[0].position_in_board
            self.assertAlmostEqual(moved.x, first.x, delta=1e-6)
            self.assertAlmostEqual(moved.y, first.y, delta=1e-6)


if __name__ == "__main__":
    rospy.init_node("test_autopilot")
    rostest.rosrun("marble_maze", "autopilot", AutopilotTest)
