#!/usr/bin/env python3
"""rostest of marble_maze_node's timed actions (run by timeouts.test), counted in steps of
simulated time: ~tilt_timeout levels the board when tilt commands stop; ~rate_timeout stops a
tilt rate whose publisher went quiet; ~auto_reset puts the marble back on the start after a hole.

Tolerances: the board is level again within 1e-9 rad; the marble is back on the start within
1e-6 m. Waits are generous (wall time) so that a loaded machine does not fail the test.
"""
import math
import subprocess
import threading
import time
import unittest

import rospy
import rostest

from marble_maze.msg import BoardTilt, BoardTiltRate, MarbleState, MazeEvent

WAIT = 10.0  # s of wall time


class Latest:
    """The latest message of a topic, and every event seen."""

    def __init__(self):
        self.lock = threading.Lock()
        self.state = None
        self.events = []
        rospy.Subscriber("marble_state", MarbleState, self._on_state, queue_size=10)
        rospy.Subscriber("events", MazeEvent, self._on_event, queue_size=1000)

    def _on_state(self, msg):
        with self.lock:
            self.state = msg

    def _on_event(self, msg):
        with self.lock:
            self.events.append(msg)

    def wait_for(self, predicate, timeout=WAIT):
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                if self.state is not None and predicate(self.state, self.events):
                    return self.state
            time.sleep(0.01)
        return None


class Timeouts(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_timeouts")
        cls.latest = Latest()
        cls.tilt = rospy.Publisher("tilt", BoardTilt, queue_size=10)
        cls.rate = rospy.Publisher("tilt_rate", BoardTiltRate, queue_size=10)
        cls.start = cls.latest.wait_for(lambda s, e: True, timeout=30)
        assert cls.start is not None, "no marble_state"

    def send(self, roll, pitch):
        msg = BoardTilt(roll=roll, pitch=pitch)  # a zero stamp: apply on arrival
        self.tilt.publish(msg)

    def test_1_tilt_timeout_levels_the_board(self):
        # One command, then silence: the board tilts, then levels 0.5 s after the command.
        deadline = time.time() + WAIT
        while self.tilt.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.01)
        self.send(0.05, 0.0)
        tilted = self.latest.wait_for(lambda s, e: s.roll > 0.01)
        self.assertIsNotNone(tilted, "the board never tilted")
        levelled = self.latest.wait_for(lambda s, e: abs(s.roll) < 1e-9 and abs(s.pitch) < 1e-9)
        self.assertIsNotNone(levelled, "the board did not level after the tilt timeout")
        self.assertGreaterEqual((levelled.header.stamp - tilted.header.stamp).to_sec(), 0.4)

    def test_2_auto_reset_after_a_hole(self):
        # Keep sending a tilt towards the far-right corner (+x, +y), where the hole is.
        holed = None
        deadline = time.time() + 3 * WAIT
        while holed is None and time.time() < deadline:
            self.send(-0.1, 0.1)  # negative roll lowers +y, positive pitch lowers +x
            holed = self.latest.wait_for(
                lambda s, e: any(ev.kind == MazeEvent.HOLE for ev in e), timeout=0.1)
        self.assertIsNotNone(holed, "the marble never fell into the hole")
        start = self.start.position_in_board
        back = self.latest.wait_for(
            lambda s, e: not s.in_hole and math.dist(
                (s.position_in_board.x, s.position_in_board.y, s.position_in_board.z),
                (start.x, start.y, start.z)) < 1e-6)
        self.assertIsNotNone(back, "the marble was not put back on the start")

    def test_3_rate_commands_run_out(self):
        # One rate command, then silence (a publisher that died): after ~rate_timeout (0.3 s in
        # this launch) the board stops turning, at 0.1 rad/s x 0.3 s = 0.03 rad, instead of
        # turning on to its limit; the tilt timeout (0.5 s) then levels it.
        deadline = time.time() + WAIT
        while self.rate.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.01)
        # The tilt timeout levels the board after the last test's commands. (No tilt is sent to
        # level it: the node takes the two topics over connections of their own, and a tilt that
        # arrived after the rate command would take the board back from it.)
        level = self.latest.wait_for(lambda s, e: abs(s.roll) < 1e-9 and abs(s.pitch) < 1e-9)
        self.assertIsNotNone(level, "the board did not level")
        self.rate.publish(BoardTiltRate(roll_rate=0.1, pitch_rate=0.0))
        self.assertIsNotNone(self.latest.wait_for(lambda s, e: s.roll > 0.005), "never turned")
        highest, end = 0.0, time.time() + 1.5
        while time.time() < end:
            with self.latest.lock:
                highest = max(highest, self.latest.state.roll)
            time.sleep(0.005)
        self.assertAlmostEqual(highest, 0.03, delta=0.002)

    def test_4_a_publisher_killed_mid_stream(self):
        # Another process publishes a tilt at 50 Hz and is killed (SIGKILL: no goodbye on its
        # connection). The node carries on, and the board levels a tilt timeout (0.5 s) after
        # the last command it had.
        script = ("import rospy\n"
                  "from marble_maze.msg import BoardTilt\n"
                  "rospy.init_node('doomed_publisher', disable_signals=True)\n"
                  "pub = rospy.Publisher('tilt', BoardTilt, queue_size=10)\n"
                  "rate = rospy.Rate(50)\n"
                  "while True:\n"
                  "    pub.publish(BoardTilt(roll=0.04, pitch=0.0))\n"
                  "    rate.sleep()\n")
        doomed = subprocess.Popen(["/usr/bin/python3", "-c", script])
        try:
            tilted = self.latest.wait_for(lambda s, e: s.roll > 0.039, timeout=3 * WAIT)
            self.assertIsNotNone(tilted, "the doomed publisher's tilt never came")
            time.sleep(1.0)  # it is publishing: the board stays tilted past the timeout
            with self.latest.lock:
                self.assertGreater(self.latest.state.roll, 0.039)
        finally:
            doomed.kill()
            doomed.wait()
        with self.latest.lock:
            killed_at = self.latest.state.header.stamp
        # The timeout acts about 0.5 s after the last command: the board starts down then.
        falling = self.latest.wait_for(lambda s, e: s.roll < 0.039)
        self.assertIsNotNone(falling, "the board stayed tilted after its publisher died")
        self.assertAlmostEqual((falling.header.stamp - killed_at).to_sec(), 0.5, delta=0.25)
        levelled = self.latest.wait_for(lambda s, e: abs(s.roll) < 1e-9 and abs(s.pitch) < 1e-9)
        self.assertIsNotNone(levelled, "the board did not level after its publisher died")
        later = self.latest.wait_for(lambda s, e: s.header.stamp > levelled.header.stamp)
        self.assertIsNotNone(later, "the node stopped publishing")


if __name__ == "__main__":
    rostest.rosrun("marble_maze", "test_timeouts", Timeouts)
