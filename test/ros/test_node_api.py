#!/usr/bin/env python3
"""rostest of marble_maze_node's ROS interface (run by node_api.test): graph, tf, markers, motion,
services, the tilt limits and the refusal of non-finite tilts.

The node runs on test/ros/open_room.yaml: an open 11 x 9 cell room with the start S in the middle,
at the board's origin, so that a small tilt rolls the marble unobstructed for about a second.
node_api.test sets tilt_limit and tilt_rate_limit to values other than their defaults, and this
test reads them back from the parameter server, so the test also checks that they are honoured.

Tolerances: positions that must be equal (tf against marble_state, reset against the start,
paused states) within POS_TOL = 1e-6 m; angles that must be equal within ANGLE_TOL = 1e-9 rad;
"moves downhill" means more than MOVE = 5 mm along the slope with less than POS_TOL across it.
Waits are long (WAIT = 10 s of wall time) so that a loaded machine does not fail the test; the
physics is checked on the node's own stamps, not on wall time.
"""
import math
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
import tf2_ros
from std_srvs.srv import Trigger
from visualization_msgs.msg import Marker, MarkerArray

from marble_maze.msg import BoardTilt, BoardTiltRate, MarbleState, MazeEvent

PKG = "marble_maze"
NODE = "/marble_maze"
POS_TOL = 1e-6  # m
ANGLE_TOL = 1e-9  # rad
MOVE = 0.005  # m: "rolled downhill"
WAIT = 10.0  # s of wall time: the longest wait for anything that should happen
SLOPE = 0.02  # rad: the tilt of the motion tests (about 0.14 m/s^2 along the slope)


def xyz(p):
    return (p.x, p.y, p.z)


def distance(a, b):
    return math.sqrt(sum((u - v) ** 2 for u, v in zip(a, b)))


def board_quaternion(roll, pitch):
    """(x, y, z, w) of R = Ry(pitch) Rx(roll), the board's orientation in the world (REP 103)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    return (cp * sr, sp * cr, -sp * sr, cp * cr)


def first_message(topic, msg_type):
    """The first message a new subscriber gets on `topic` within WAIT, or None."""
    got = []
    sub = rospy.Subscriber(topic, msg_type, got.append)
    deadline = time.time() + WAIT
    while not got and time.time() < deadline:
        time.sleep(0.01)
    sub.unregister()
    return got[0] if got else None


class Recorder:
    """Keeps every message of a topic (with its wall arrival time) for the waits and checks."""

    def __init__(self, topic, msg_type, check_stamps=False):
        self.lock = threading.Lock()
        self.msgs = []
        self.check_stamps = check_stamps
        self.stamp_errors = []  # (previous, next) stamps that do not strictly increase
        self.sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=1000)

    def _on_msg(self, msg):
        with self.lock:
            if (self.check_stamps and self.msgs
                    and not msg.header.stamp > self.msgs[-1].header.stamp):
                self.stamp_errors.append((self.msgs[-1].header.stamp.to_sec(),
                                          msg.header.stamp.to_sec()))
            self.msgs.append(msg)

    def count(self):
        with self.lock:
            return len(self.msgs)

    def since(self, index):
        with self.lock:
            return list(self.msgs[index:])

    def latest(self):
        with self.lock:
            return self.msgs[-1] if self.msgs else None

    def wait_for(self, predicate, start=0, timeout=WAIT):
        """The first message from index `start` on for which predicate holds, or None."""
        deadline = time.time() + timeout
        index = start
        while time.time() < deadline and not rospy.is_shutdown():
            for msg in self.since(index):
                index += 1
                if predicate(msg):
                    return msg
            time.sleep(0.005)
        return None


class TiltSender:
    """Sends one tilt message over and over (20 Hz) so that none is lost to a slow connection."""

    def __init__(self):
        self.tilt_pub = rospy.Publisher("tilt", BoardTilt, queue_size=10)
        self.rate_pub = rospy.Publisher("tilt_rate", BoardTiltRate, queue_size=10)
        self.lock = threading.Lock()
        self.msg = None
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def send(self, msg):
        with self.lock:
            self.msg = msg

    def tilt(self, roll, pitch):
        self.send(BoardTilt(roll=roll, pitch=pitch))  # stamp zero: apply on arrival

    def rate(self, roll_rate, pitch_rate):
        self.send(BoardTiltRate(roll_rate=roll_rate, pitch_rate=pitch_rate))

    def stop(self):
        """Stops sending and gives what was in flight the time to arrive."""
        self.send(None)
        time.sleep(0.3)

    def _run(self):
        while not rospy.is_shutdown():
            with self.lock:
                msg = self.msg
            if isinstance(msg, BoardTilt):
                self.tilt_pub.publish(msg)
            elif isinstance(msg, BoardTiltRate):
                self.rate_pub.publish(msg)
            time.sleep(0.05)


class NodeApiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tilt_limit = rospy.get_param(NODE + "/tilt_limit")
        cls.rate_limit = rospy.get_param(NODE + "/tilt_rate_limit")
        cls.states = Recorder("marble_state", MarbleState, check_stamps=True)
        cls.events = Recorder("events", MazeEvent)
        cls.tf_buffer = tf2_ros.Buffer(cache_time=rospy.Duration(60))
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        cls.sender = TiltSender()
        for name in ("reset", "pause", "resume"):
            rospy.wait_for_service(name, timeout=30)
            setattr(cls, name, rospy.ServiceProxy(name, Trigger))
        first = cls.states.wait_for(lambda m: True, timeout=30)
        assert first is not None, "no marble_state within 30 s"
        cls.start_state = first  # before any tilt: the marble at the start
        cls.start = xyz(first.position_in_board)

    def setUp(self):
        # Every test starts from the marble at rest at the start of a level board. Should that
        # fail once, the following tests fail at once rather than each waiting for it.
        cls = self.__class__
        self.assertFalse(getattr(cls, "setup_failed", False), "reset failed in an earlier setUp")
        cls.setup_failed = True
        self.sender.stop()
        self.assertTrue(self.resume().success)
        self.assertTrue(self.reset().success)
        at_start = self.states.wait_for(
            lambda m: distance(xyz(m.position_in_board), self.start) < POS_TOL
            and m.roll == 0.0 and m.pitch == 0.0,
            start=self.states.count())
        self.assertIsNotNone(at_start, "the marble did not come back to the start after reset")
        cls.setup_failed = False

    def tearDown(self):
        self.sender.stop()

    # --- helpers ---

    def roll_until(self, predicate, what):
        """Waits for a state meeting predicate (after the tilt being sent); fails naming `what`."""
        msg = self.states.wait_for(predicate, start=self.states.count())
        self.assertIsNotNone(msg, "within %g s: %s" % (WAIT, what))
        return msg

    def check_tf(self, state):
        """tf world -> board -> marble at the state's stamp agrees with the state."""
        stamp = state.header.stamp
        marble = self.tf_buffer.lookup_transform("world", "marble", stamp, rospy.Duration(WAIT))
        # tf2's Python binding passes times as float seconds: at today's epoch that rounds
        # them by up to ~0.1 us, so the stamp comes back within 1 us, not exactly.
        self.assertLess(abs((marble.header.stamp - stamp).to_sec()), 1e-6)
        t = marble.transform.translation
        self.assertLess(distance((t.x, t.y, t.z), xyz(state.position)), POS_TOL,
                        "tf world->marble at %.3f s vs marble_state.position" % stamp.to_sec())
        in_board = self.tf_buffer.lookup_transform("board", "marble", stamp, rospy.Duration(WAIT))
        t = in_board.transform.translation
        self.assertLess(distance((t.x, t.y, t.z), xyz(state.position_in_board)), POS_TOL,
                        "tf board->marble vs marble_state.position_in_board")
        board = self.tf_buffer.lookup_transform("world", "board", stamp, rospy.Duration(WAIT))
        self.assertLess(distance(xyz(board.transform.translation), (0, 0, 0)), POS_TOL,
                        "the board pivots about the world origin")
        q = board.transform.rotation
        expected = board_quaternion(state.roll, state.pitch)
        sign = 1.0 if q.w * expected[3] >= 0 else -1.0  # q and -q are the same rotation
        self.assertLess(distance((sign * q.x, sign * q.y, sign * q.z, sign * q.w), expected),
                        ANGLE_TOL, "tf world->board vs marble_state roll, pitch")

    # --- the tests ---

    def test_graph(self):
        """Topics, their types, subscriptions and services, as the master knows them."""
        master = rosgraph.Master(rospy.get_name())
        publishes = {"/marble_state": "marble_maze/MarbleState",
                     "/events": "marble_maze/MazeEvent",
                     "/maze_markers": "visualization_msgs/MarkerArray",
                     "/marble_marker": "visualization_msgs/Marker",
                     "/tf": "tf2_msgs/TFMessage"}
        subscribes = {"/tilt": "marble_maze/BoardTilt", "/tilt_rate": "marble_maze/BoardTiltRate"}
        pubs, subs, srvs = master.getSystemState()
        pubs, subs, srvs = dict(pubs), dict(subs), dict(srvs)
        types = dict(master.getTopicTypes())
        for topic, msg_type in publishes.items():
            self.assertIn(NODE, pubs.get(topic, []), "%s does not publish %s" % (NODE, topic))
            self.assertEqual(types.get(topic), msg_type, topic)
        for topic, msg_type in subscribes.items():
            self.assertIn(NODE, subs.get(topic, []), "%s does not subscribe %s" % (NODE, topic))
            self.assertEqual(types.get(topic), msg_type, topic)
        for service in ("/reset", "/pause", "/resume"):
            self.assertIn(NODE, srvs.get(service, []), "%s does not offer %s" % (NODE, service))
            self.assertTrue(master.lookupService(service))

    def test_start_state(self):
        """The first state, before any tilt: the marble rests on the floor at the room's centre."""
        s = self.start_state
        self.assertEqual(s.header.frame_id, "world")
        # open_room.yaml is symmetric about its start cell: the start is at the pivot, and the
        # marble's centre one radius (6 mm) above the floor's top surface.
        for got, want in zip(self.start, (0.0, 0.0, 0.006)):
            self.assertAlmostEqual(got, want, delta=1e-9)
        self.assertEqual((s.roll, s.pitch), (0.0, 0.0))
        self.assertFalse(s.in_hole or s.at_goal or s.off_board)
        # (The first state's tf may have gone out before the listener connected: check a new one,
        # with the marble still at the start after setUp.)
        now = self.states.wait_for(lambda m: True, start=self.states.count())
        self.assertLess(distance(xyz(now.position_in_board), self.start), POS_TOL)
        self.check_tf(now)

    def test_tf_tree(self):
        """world -> board -> marble resolves, at the latest time and at a state's stamp."""
        self.assertTrue(self.tf_buffer.can_transform("world", "marble", rospy.Time(0),
                                                     rospy.Duration(WAIT)))
        self.check_tf(self.states.wait_for(lambda m: True, start=self.states.count()))

    def test_maze_markers(self):
        """maze_markers is latched: a late subscriber gets the whole maze, CUBE_LISTs in board."""
        array = first_message("maze_markers", MarkerArray)
        self.assertIsNotNone(array, "no latched maze_markers for a late subscriber")
        markers = array.markers
        by_ns = {}
        for m in markers:
            self.assertEqual(m.header.frame_id, "board")
            self.assertEqual(m.type, Marker.CUBE_LIST)
            self.assertEqual(m.action, Marker.ADD)
            self.assertTrue(m.frame_locked)
            self.assertTrue(m.points, "empty marker %s/%d" % (m.ns, m.id))
            self.assertTrue(m.scale.x > 0 and m.scale.y > 0 and m.scale.z > 0)
            self.assertGreater(m.color.a, 0.0)
            by_ns.setdefault(m.ns, []).append(m)
        self.assertEqual(set(by_ns), {"floor", "walls", "holes", "start", "goal"})
        ids = [(m.ns, m.id) for m in markers]
        self.assertEqual(len(ids), len(set(ids)), "repeated (ns, id)")
        # open_room.yaml: one start in the middle, the goal in the far-left corner (-x, +y) and
        # the hole in the far-right corner (+x, +y): the top line of the plan is the +y edge.
        points = {ns: [p for m in ms for p in m.points] for ns, ms in by_ns.items()}
        self.assertEqual(len(points["start"]), 1)
        self.assertAlmostEqual(points["start"][0].x, self.start[0], delta=1e-9)
        self.assertAlmostEqual(points["start"][0].y, self.start[1], delta=1e-9)
        self.assertEqual(len(points["goal"]), 1)
        self.assertLess(points["goal"][0].x, -0.1)
        self.assertGreater(points["goal"][0].y, 0.08)
        self.assertEqual(len(points["holes"]), 1)
        self.assertGreater(points["holes"][0].x, 0.1)
        self.assertGreater(points["holes"][0].y, 0.08)

    def test_marble_marker(self):
        m = first_message("marble_marker", Marker)
        self.assertIsNotNone(m, "no marble_marker")
        self.assertEqual(m.header.frame_id, "marble")
        self.assertEqual(m.type, Marker.SPHERE)
        self.assertAlmostEqual(m.scale.x, 0.012, delta=1e-12)  # 2 x the 6 mm radius
        self.assertTrue(m.frame_locked)

    def _check_downhill(self, roll, pitch, axis, sign):
        """Under a constant tilt the marble rolls along `axis` of the board in direction `sign`,
        not across it, and every state agrees with tf."""
        self.sender.tilt(roll, pitch)
        first = self.states.count()
        moved = self.roll_until(
            lambda m: sign * (getattr(m.position_in_board, axis)
                              - self.start["xy".index(axis)]) > MOVE,
            "the marble rolls more than %g m towards %s%s under roll %g, pitch %g"
            % (MOVE, "+" if sign > 0 else "-", axis, roll, pitch))
        across = "y" if axis == "x" else "x"
        states = [m for m in self.states.since(first) if m.header.stamp <= moved.header.stamp]
        self.assertGreater(len(states), 5)
        for m in states:
            self.assertLess(abs(getattr(m.position_in_board, across)
                                - self.start["xy".index(across)]), POS_TOL,
                            "the marble strays across the slope")
            self.assertAlmostEqual(m.position_in_board.z, self.start[2], delta=1e-5)
        # Downhill, not jumping: the velocity along the slope has the motion's sign.
        velocity_in_board_axis = moved.velocity.x if axis == "x" else (
            moved.velocity.y * math.cos(moved.roll) + moved.velocity.z * math.sin(moved.roll))
        self.assertGreater(sign * velocity_in_board_axis, 0.0)
        # tf at the stamps of states in motion (a sample of them: each waits for tf).
        for m in states[-1::-max(1, len(states) // 8)]:
            self.check_tf(m)

    def test_downhill_roll(self):
        """Positive roll raises the board's +y side: the marble rolls towards -y (REP 103)."""
        self._check_downhill(SLOPE, 0.0, "y", -1)

    def test_downhill_pitch(self):
        """Positive pitch lowers the board's +x side: the marble rolls towards +x (REP 103)."""
        self._check_downhill(0.0, SLOPE, "x", +1)

    def test_reset(self):
        """reset succeeds and puts the marble back at the start, at rest on a level board."""
        self.sender.tilt(0.0, SLOPE)
        self.roll_until(lambda m: m.position_in_board.x - self.start[0] > MOVE,
                        "the marble rolls towards +x")
        self.sender.stop()  # the board stays at pitch SLOPE: the marble keeps rolling
        before = self.states.count()
        response = self.reset()
        self.assertTrue(response.success)
        self.assertTrue(response.message)
        # The board is level again after the reset and only then: the first level state is the
        # first one after the reset.
        after = self.states.wait_for(lambda m: m.pitch == 0.0, start=before)
        self.assertIsNotNone(after, "no level board after reset")
        time.sleep(0.5)
        states = [m for m in self.states.since(before) if m.header.stamp >= after.header.stamp]
        self.assertGreater(len(states), 5)
        for m in states:
            self.assertLess(distance(xyz(m.position_in_board), self.start), POS_TOL,
                            "after reset: %s, start %s" % (xyz(m.position_in_board), self.start))
            self.assertLess(distance(xyz(m.velocity), (0, 0, 0)), 1e-6)
            self.assertEqual((m.roll, m.pitch), (0.0, 0.0))
        self.assertFalse(self.states.stamp_errors,
                         "marble_state stamps not increasing (prev, next)")

    def test_tilt_limit(self):
        """A tilt beyond tilt_limit is clamped to it, reached at no more than tilt_rate_limit;
        the marble thrown against the walls reports collisions on events."""
        lim, rate = self.tilt_limit, self.rate_limit
        first_event = self.events.count()
        first = self.states.count()
        self.sender.tilt(1.0, -1.0)
        reached = self.roll_until(
            lambda m: abs(m.roll - lim) <= ANGLE_TOL and abs(m.pitch + lim) <= ANGLE_TOL,
            "the board reaches roll %g, pitch %g (the limit)" % (lim, -lim))
        time.sleep(1.0)  # the marble hits the walls meanwhile
        states = self.states.since(first)
        previous = None
        for m in states:
            self.assertLessEqual(abs(m.roll), lim + ANGLE_TOL, "roll beyond tilt_limit")
            self.assertLessEqual(abs(m.pitch), lim + ANGLE_TOL, "pitch beyond tilt_limit")
            if previous is not None:
                dt = (m.header.stamp - previous.header.stamp).to_sec()
                self.assertLessEqual(abs(m.roll - previous.roll), rate * dt + ANGLE_TOL,
                                     "roll faster than tilt_rate_limit")
                self.assertLessEqual(abs(m.pitch - previous.pitch), rate * dt + ANGLE_TOL,
                                     "pitch faster than tilt_rate_limit")
            previous = m
        # At the rate limit, the ramp from level to the limit takes lim / rate seconds.
        ramp = (reached.header.stamp - states[0].header.stamp).to_sec()
        self.assertGreaterEqual(ramp, lim / rate - 0.021)  # less one publish period and a step
        after = [m for m in states if m.header.stamp >= reached.header.stamp]
        self.assertTrue(all(abs(m.roll - lim) <= ANGLE_TOL for m in after))
        collision = self.events.wait_for(lambda e: e.kind == MazeEvent.COLLISION,
                                         start=first_event)
        self.assertIsNotNone(collision, "no collision event with the marble thrown at the walls")
        self.assertEqual(collision.header.frame_id, "board")
        self.assertGreater(collision.impact_speed, 0.0)

    def test_tilt_rate_limit(self):
        """tilt_rate beyond tilt_rate_limit is clamped; the board stops at the tilt limit."""
        lim, rate = self.tilt_limit, self.rate_limit
        first = self.states.count()
        self.sender.rate(-10.0, 0.0)
        self.roll_until(lambda m: abs(m.roll + lim) <= ANGLE_TOL, "roll reaches -tilt_limit")
        time.sleep(0.3)
        states = self.states.since(first)
        moving = [(a, b) for a, b in zip(states, states[1:]) if b.roll != a.roll]
        self.assertTrue(moving)
        for a, b in zip(states, states[1:]):
            dt = (b.header.stamp - a.header.stamp).to_sec()
            self.assertLessEqual(b.roll, a.roll + ANGLE_TOL, "roll must only decrease")
            self.assertLessEqual(a.roll - b.roll, rate * dt + ANGLE_TOL, "faster than the limit")
            self.assertGreaterEqual(b.roll, -lim - ANGLE_TOL, "beyond the tilt limit")
            self.assertEqual(b.pitch, 0.0)
        # Between two states wholly inside the ramp, the board turned at exactly the limit.
        inside = [(a, b) for a, b in moving
                  if abs(a.roll) > ANGLE_TOL and abs(b.roll + lim) > ANGLE_TOL]
        self.assertTrue(inside)
        for a, b in inside:
            dt = (b.header.stamp - a.header.stamp).to_sec()
            self.assertAlmostEqual((a.roll - b.roll) / dt, rate, delta=1e-6)

    def test_non_finite_tilt_refused(self):
        """NaN and infinite tilts and tilt rates are refused: the board keeps its tilt, the node
        keeps publishing, and a good tilt afterwards still works."""
        roll, pitch = 0.01, -0.01
        self.sender.tilt(roll, pitch)
        self.roll_until(lambda m: abs(m.roll - roll) <= ANGLE_TOL
                        and abs(m.pitch - pitch) <= ANGLE_TOL, "the board reaches the tilt")
        self.sender.stop()
        first = self.states.count()
        nan, inf = float("nan"), float("inf")
        bad = [BoardTilt(roll=nan, pitch=0.0), BoardTilt(roll=0.0, pitch=nan),
               BoardTilt(roll=inf, pitch=-inf), BoardTilt(roll=nan, pitch=nan),
               BoardTiltRate(roll_rate=nan, pitch_rate=0.0),
               BoardTiltRate(roll_rate=0.0, pitch_rate=-inf)]
        for _ in range(4):
            for msg in bad:
                self.sender.send(msg)
                time.sleep(0.06)  # the sender sends each at least once
        self.sender.stop()
        time.sleep(0.3)
        states = self.states.since(first)
        self.assertGreater(len(states), 10, "the node stopped publishing after non-finite tilts")
        for m in states:
            self.assertFalse(math.isnan(m.roll) or math.isnan(m.pitch))
            self.assertAlmostEqual(m.roll, roll, delta=ANGLE_TOL)
            self.assertAlmostEqual(m.pitch, pitch, delta=ANGLE_TOL)
            self.assertTrue(all(math.isfinite(v) for v in xyz(m.position) + xyz(m.velocity)))
        self.sender.tilt(-roll, 0.0)
        self.roll_until(lambda m: abs(m.roll + roll) <= ANGLE_TOL and m.pitch == 0.0,
                        "a good tilt is obeyed after the refused ones")

    def test_pause_resume(self):
        """pause stops the simulation (no motion), resume goes on from where it stopped."""
        self.sender.tilt(0.0, SLOPE)
        self.roll_until(lambda m: m.position_in_board.x - self.start[0] > 0.002,
                        "the marble rolls towards +x")
        response = self.pause()
        self.assertTrue(response.success)
        time.sleep(0.3)  # what was published before the pause arrives
        paused = self.states.latest()
        index = self.states.count()
        time.sleep(0.5)
        later = self.states.latest()
        self.assertEqual(xyz(later.position), xyz(paused.position), "moved while paused")
        for m in self.states.since(index):  # states while paused, if any, do not move
            self.assertEqual(xyz(m.position_in_board), xyz(paused.position_in_board))
        self.assertTrue(self.pause().success, "pause when paused")
        index = self.states.count()
        self.assertTrue(self.resume().success)
        resumed = self.states.wait_for(lambda m: m.header.stamp > paused.header.stamp,
                                       start=index)
        self.assertIsNotNone(resumed, "no marble_state after resume")
        # Where it stopped: the paused time is not simulated (0.8 s more rolling would have moved
        # it by centimetres).
        self.assertLess(distance(xyz(resumed.position_in_board),
                                 xyz(paused.position_in_board)), 0.002)
        self.roll_until(lambda m: m.position_in_board.x - paused.position_in_board.x > 0.002,
                        "the marble rolls on after resume")
        self.assertFalse(self.states.stamp_errors,
                         "marble_state stamps not increasing (prev, next)")


if __name__ == "__main__":
    rospy.init_node("test_node_api")
    rostest.rosrun(PKG, "node_api", NodeApiTest, sys.argv)
