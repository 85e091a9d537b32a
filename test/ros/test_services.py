#!/usr/bin/env python3
"""rostest of the node's services and live tuning (run by services.test, maze open_room.yaml).

  - step: refused while running; while paused it advances exactly N steps (the state's stamp
    moves by N steps of 1 ms, within 1 ns), and the frozen state goes on being published; the
    same sequence of reset, place_marble, tilt and
    step calls gives bit-identical states;
  - place_marble: refused inside a tile and off the board, the marble staying where it was;
  - load_maze: refused for a missing and a malformed file (file:line:col), and a file of
    another kind quoted only in part, the old maze still running; a built-in maze loads, `maze`
    and the markers follow; a maze with 5 ms steps runs at real time, one with steps longer than
    ~publish_rate allows is refused;
  - dynamic_reconfigure: restitution 0.9 acts on the next bounce as eq. (1) says (the upward
    speed after it is 0.9 times the approach, less the gravity since, within 1e-6 m/s); a bad
    value is refused and nothing changes; the values in force are on the parameter server, and
    a value changed live holds over a maze loaded later;
  - /diagnostics carries the real-time factor; odom is published in world with child marble;
  - a microsecond step of 1000 substeps set live leaves the node answering its services within
    10 s, /diagnostics saying it fell behind; a `step` call of more than 1e7 substeps is refused;
  - steps taken while paused put the simulation ahead of ROS time: /diagnostics says so, and
    states come again once ROS time has caught up;
  - a tilt stamped 1 s ahead, the step set to 2 ms meanwhile, turns the board from its stamp on.
"""
import math
import os
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from dynamic_reconfigure.client import Client
from geometry_msgs.msg import Point, Vector3
from nav_msgs.msg import Odometry
from std_srvs.srv import Trigger

from marble_maze.msg import BoardTilt, MarbleState, MazeDescription, MazeEvent, SceneDescription
from marble_maze.srv import LoadMaze, PlaceMarble, Step

NODE = "/marble_maze"
G, STEP = 9.81, 0.001
RADIUS = 0.006


def call(name, srv_type, *args):
    rospy.wait_for_service(name, timeout=20)
    return rospy.ServiceProxy(name, srv_type)(*args)


def stamp_ns(msg):
    return msg.header.stamp.secs * 10**9 + msg.header.stamp.nsecs


class Latest:
    def __init__(self, topic, msg_type):
        self.lock = threading.Lock()
        self.all = []
        rospy.Subscriber(topic, msg_type, self._on, queue_size=1000)

    def _on(self, msg):
        with self.lock:
            self.all.append(msg)

    def wait(self, predicate, timeout=10.0):
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                found = [m for m in self.all if predicate(m)]
            if found:
                return found[0]
            time.sleep(0.02)
        return None


class ServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tilt = rospy.Publisher("tilt", BoardTilt, queue_size=10)
        cls.states = Latest("marble_state", MarbleState)
        cls.events = Latest("events", MazeEvent)
        cls.mazes = Latest("maze", MazeDescription)
        cls.diagnostics = Latest("/diagnostics", DiagnosticArray)
        cls.odom = Latest("odom", Odometry)
        time.sleep(1.0)

    def setUp(self):
        call("resume", Trigger)
        call("reset", Trigger)

    def place(self, x, y, z, v=(0, 0, 0), w=(0, 0, 0)):
        return call("place_marble", PlaceMarble, Point(x, y, z), Vector3(*v), Vector3(*w))

    def test_1_step_only_while_paused_and_exactly_n(self):
        self.assertFalse(call("step", Step, 10).success)
        self.assertIn("pause", call("step", Step, 10).message)
        call("pause", Trigger)
        first = call("step", Step, 1)
        self.assertTrue(first.success, first.message)
        after = call("step", Step, 250)
        self.assertTrue(after.success, after.message)
        self.assertEqual(stamp_ns(after.state) - stamp_ns(first.state), 250 * 10**6)
        self.assertFalse(call("step", Step, 0).success)
        # Paused, the frozen state goes on being published (tf does not go stale).
        count = len(self.states.all)
        deadline = time.time() + 5  # (some 25 come in 0.5 s; a loaded machine may stall)
        while len(self.states.all) - count <= 10 and time.time() < deadline:
            time.sleep(0.05)
        frozen = self.states.all[count:]
        self.assertGreater(len(frozen), 10)
        self.assertEqual({m.position.x for m in frozen}, {after.state.position.x})

    def sequence(self):
        call("pause", Trigger)
        call("reset", Trigger)
        self.assertTrue(self.place(0.01, -0.02, RADIUS + 0.004, (0.1, 0.05, 0), (0, 2, 0)).success)
        self.tilt.publish(BoardTilt(roll=0.05, pitch=-0.03))
        time.sleep(0.3)  # the command arrives while paused: it acts at the next step taken
        call("step", Step, 300)
        self.tilt.publish(BoardTilt(roll=-0.04, pitch=0.02))
        time.sleep(0.3)
        return call("step", Step, 700).state

    def test_2_the_same_calls_give_bit_identical_states(self):
        a, b = self.sequence(), self.sequence()
        for field in ("position", "velocity", "angular_velocity", "position_in_board"):
            va, vb = getattr(a, field), getattr(b, field)
            self.assertEqual((va.x, va.y, va.z), (vb.x, vb.y, vb.z), field)
        self.assertEqual((a.roll, a.pitch), (b.roll, b.pitch))
        self.assertNotEqual(a.position_in_board.x, 0.01, "the marble did move")

    def test_3_place_refuses_tiles_and_off_board(self):
        call("pause", Trigger)
        before = call("step", Step, 1).state.position_in_board
        inside = self.place(0.0, 0.0, 0.001)  # sunk into the floor
        self.assertFalse(inside.success)
        self.assertIn("inside tile", inside.message)
        off = self.place(0.5, 0.0, RADIUS)
        self.assertFalse(off.success)
        self.assertIn("off the board", off.message)
        still = call("step", Step, 1).state.position_in_board
        self.assertAlmostEqual(still.x, before.x, delta=1e-9)
        ok = self.place(0.03, 0.02, RADIUS)
        self.assertTrue(ok.success, ok.message)
        self.assertAlmostEqual(call("step", Step, 1).state.position_in_board.x, 0.03, delta=1e-6)

    def test_4_load_maze_refuses_bad_files_and_loads_a_good_one(self):
        missing = call("load_maze", LoadMaze, "/nonexistent/maze.yaml")
        self.assertFalse(missing.success)
        self.assertIn("/nonexistent/maze.yaml", missing.message)
        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
            f.write("grid:\n  x: [0.005, 0.02]\n  y: 0.01\n  z: 0.01\nlayout: |\n  +?+\n")
        broken = call("load_maze", LoadMaze, f.name)
        os.unlink(f.name)
        self.assertFalse(broken.success)
        self.assertIn(os.path.basename(f.name) + ":6:", broken.message)
        # A file of another kind is quoted only in part: the service gives back its start and
        # its size, not the file.
        with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as f:
            f.write("".join("user%d:x:1000:1000::/home/user:/bin/bash\n" % k for k in range(100)))
            f.write("the last line\n")
        other = call("load_maze", LoadMaze, f.name)
        os.unlink(f.name)
        self.assertFalse(other.success)
        self.assertIn("found 'user0:x:1000:1000::/home/user:/bin/bash user1:", other.message)
        self.assertIn(" bytes)", other.message)
        self.assertNotIn("the last line", other.message)
        self.assertLess(len(other.message), len(f.name) + 200)
        self.assertEqual(self.mazes.all[-1].name, "open_room")  # the old maze runs on
        loaded = call("load_maze", LoadMaze, "prototype")
        self.assertTrue(loaded.success, loaded.message)
        self.assertIsNotNone(self.mazes.wait(lambda m: m.name == "prototype"))
        self.assertEqual(rospy.get_param(NODE + "/maze"), "prototype")
        back = call("load_maze", LoadMaze, rospy.get_param("~maze"))
        self.assertTrue(back.success, back.message)

    def test_4b_a_maze_with_another_step_runs_at_real_time_or_is_refused(self):
        with open(rospy.get_param("~maze")) as f:
            room = f.read()

        def with_step(step):
            with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
                f.write(room.replace("\nphysics:\n", "\nphysics:\n  step: %g\n" % step))
            loaded = call("load_maze", LoadMaze, f.name)
            os.unlink(f.name)
            return loaded

        try:
            # 5 ms steps: still one simulated second a second of ROS time (the steps were tied to
            # ROS time at the old length: five times real time).
            loaded = with_step(0.005)
            self.assertTrue(loaded.success, loaded.message)
            after = rospy.get_rostime() + rospy.Duration(1.5)
            status = self.diagnostics.wait(
                lambda a: a.header.stamp > after and
                any(kv.key == "real-time factor" for s in a.status for kv in s.values),
                timeout=10)
            self.assertIsNotNone(status, "no real-time factor on /diagnostics")
            factor = next(float(kv.value) for s in status.status for kv in s.values
                          if kv.key == "real-time factor")
            self.assertLess(abs(factor - 1), 0.5, factor)
            # 50 ms steps: fewer than ~publish_rate's 50 a second, refused as at start.
            refused = with_step(0.05)
            self.assertFalse(refused.success)
            self.assertIn("~publish_rate", refused.message)
        finally:
            back = call("load_maze", LoadMaze, rospy.get_param("~maze"))
            self.assertTrue(back.success, back.message)

    def test_5_reconfigure_restitution_acts_on_the_next_bounce(self):
        client = Client(NODE, timeout=20)
        self.assertEqual(rospy.get_param(NODE + "/restitution"), 0.5)  # written back at start
        client.update_configuration({"restitution": 0.9, "tilt_limit": 0.15})
        self.assertEqual(rospy.get_param(NODE + "/restitution"), 0.9)
        # The latched descriptions follow: a planner reading `maze` and a recorder reading `scene`
        # see the physics in force.
        maze = rospy.wait_for_message("/maze", MazeDescription, timeout=10)
        self.assertEqual((maze.restitution, maze.tilt_limit), (0.9, 0.15))
        scene = rospy.wait_for_message("/scene", SceneDescription, timeout=10)
        self.assertIn("restitution=0.9\n", scene.params)
        self.assertIn("tilt_limit=0.15\n", scene.params)
        refused = client.update_configuration({"restitution": 1.5})  # beyond [0, 1]
        self.assertEqual(refused["restitution"], 0.9)
        start = len(self.events.all)
        self.assertTrue(self.place(0.0, 0.0, RADIUS + 0.01).success)
        bounce = self.events.wait(lambda e: e.kind == MazeEvent.COLLISION and
                                  self.events.all.index(e) >= start)
        self.assertIsNotNone(bounce, "no bounce")
        after = self.states.wait(lambda m: m.header.stamp > bounce.header.stamp)
        dt = (after.header.stamp - bounce.header.stamp).to_sec()
        # Eq. (1) on a level board at rest: v' = e v, then gravity for dt.
        self.assertAlmostEqual(after.velocity.z, 0.9 * bounce.impact_speed - G * dt, delta=1e-6)
        # A value changed live holds over a maze loaded later, as the node's parameters do.
        loaded = call("load_maze", LoadMaze, rospy.get_param("~maze"))
        self.assertTrue(loaded.success, loaded.message)
        self.assertEqual(rospy.get_param(NODE + "/restitution"), 0.9)
        client.update_configuration({"restitution": 0.5, "tilt_limit": 0.17453292519943295})

    def test_6_diagnostics_and_odometry(self):
        status = self.diagnostics.wait(
            lambda a: any(any(kv.key == "real-time factor" for kv in s.values) for s in a.status),
            timeout=10)
        self.assertIsNotNone(status, "no real-time factor on /diagnostics")
        odom = self.odom.wait(lambda m: True)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ("world", "marble"))

    def test_8_a_step_too_costly_to_keep_up_with_leaves_the_node_answering(self):
        # A microsecond step of 1000 substeps, set live (within the documented ranges): a second
        # of ROS time is a billion substeps. The node takes at most a million a callback and
        # skips the rest with a warning, so that its services are answered (a pause took 1 min
        # 40 s when it caught up a second at a time); a `step` call of 2e7 substeps is refused.
        client = Client(NODE, timeout=20)
        client.update_configuration({"step": 1e-6, "substeps": 1000})
        try:
            time.sleep(1.0)
            begin = time.time()
            self.assertTrue(call("pause", Trigger).success)
            self.assertLess(time.time() - begin, 10)
            # Paused, a `step` call is held to the same work as a lockstep command: 1e7 substeps.
            begin = time.time()
            costly = call("step", Step, 20000)
            self.assertFalse(costly.success)
            self.assertIn("steps: 20000 steps are (of 1000 substeps each) more than 10000000 "
                          "substeps a command", costly.message)
            self.assertLess(time.time() - begin, 10)
            self.assertTrue(call("step", Step, 2).success)
            self.assertTrue(call("resume", Trigger).success)
            after = rospy.get_rostime() + rospy.Duration(1.0)
            behind = self.diagnostics.wait(
                lambda a: a.header.stamp > after and
                any("fell behind" in st.message for st in a.status), timeout=10)
            self.assertIsNotNone(behind, "/diagnostics does not say the node fell behind")
        finally:
            client.update_configuration({"step": 0.001, "substeps": 1})

    def test_7_bad_arguments_and_calls_at_the_wrong_moment(self):
        # Refused with the argument named, and the node runs on in a valid state.
        nan = float("nan")
        bad_velocity = self.place(0.03, 0.02, RADIUS, (nan, 0, 0))
        self.assertFalse(bad_velocity.success)
        self.assertIn("place_marble: velocity: not finite", bad_velocity.message)
        bad_spin = self.place(0.03, 0.02, RADIUS, (0, 0, 0), (0, nan, 0))
        self.assertFalse(bad_spin.success)
        self.assertIn("angular_velocity: not finite", bad_spin.message)
        fast = self.place(0.03, 0.02, RADIUS, (1e9, 0, 0))
        self.assertFalse(fast.success)
        self.assertIn("velocity", fast.message)
        spin = self.place(0.03, 0.02, RADIUS, (0, 0, 0), (0, 1e12, 0))
        self.assertFalse(spin.success)
        self.assertIn("angular_velocity", spin.message)
        endless = call("load_maze", LoadMaze, "/dev/zero")  # a device with no end
        self.assertFalse(endless.success)
        self.assertIn("load_maze: maze: /dev/zero: more than 16 MB", endless.message)
        empty = call("load_maze", LoadMaze, "")
        self.assertFalse(empty.success)
        self.assertIn("load_maze: maze: empty", empty.message)
        # Twice in a row, in every order: each answers, none breaks the next.
        for service in ("pause", "pause", "resume", "resume", "reset", "pause", "reset"):
            self.assertTrue(call(service, Trigger).success, service)
        placed = self.place(0.03, 0.02, RADIUS)  # while paused: it takes effect at once
        self.assertTrue(placed.success, placed.message)
        loaded = call("load_maze", LoadMaze, rospy.get_param("~maze"))  # while paused
        self.assertTrue(loaded.success, loaded.message)
        state = call("step", Step, 100).state
        for v in (state.position, state.velocity, state.angular_velocity):
            self.assertTrue(all(math.isfinite(c) for c in (v.x, v.y, v.z)))
        self.assertTrue(call("resume", Trigger).success)

    def test_9_steps_taken_while_paused_run_ahead_and_diagnostics_say_so(self):
        # Steps taken while paused keep their exact stamps, so they run ahead of ROS time: after
        # `resume` nothing new comes until ROS time has caught up, and /diagnostics says how far
        # ahead the simulation is (it said "running at 0.37 times real time").
        call("pause", Trigger)
        stepped = call("step", Step, 3000).state  # 3 s of simulated time at once
        self.assertGreater(stamp_ns(stepped) - rospy.get_rostime().to_nsec(), 2.5e9)
        self.assertTrue(call("resume", Trigger).success)
        ahead = self.diagnostics.wait(
            lambda a: any("ahead of ROS time" in st.message for st in a.status), timeout=5)
        self.assertIsNotNone(ahead, "/diagnostics does not say the simulation is ahead")
        caught_up = self.states.wait(lambda m: stamp_ns(m) > stamp_ns(stepped), timeout=10)
        self.assertIsNotNone(caught_up, "no new state after ROS time caught up")
        # Nor is the period that waited taken for a slow node (it warned "running at 0.40 times
        # real time" on the report after the catch-up).
        with self.diagnostics.lock:
            seen = len(self.diagnostics.all)
        time.sleep(2.5)
        with self.diagnostics.lock:
            said = [st.message for a in self.diagnostics.all[seen:] for st in a.status]
        self.assertTrue(said, "no /diagnostics after the catch-up")
        self.assertFalse([m for m in said if "below the" in m], said)

    def test_9b_a_command_stamped_ahead_keeps_its_stamp_across_a_new_step(self):
        # A tilt stamped 1 s ahead waits in the queue for its stamp's step; the step set to 2 ms
        # meanwhile (dynamic_reconfigure) moves it to its stamp's step of the new length: the
        # board turns from the stamp on, not 0.8 s late, as when it kept its step of the old.
        client = Client(NODE, timeout=20)
        try:
            ahead = rospy.get_rostime() + rospy.Duration(1.0)
            command = BoardTilt(roll=0.05)
            command.header.stamp = ahead
            self.tilt.publish(command)
            time.sleep(0.2)
            client.update_configuration({"step": 0.002})
            turned = self.states.wait(
                lambda m: m.header.stamp > ahead - rospy.Duration(0.5) and m.roll != 0.0,
                timeout=5)
            self.assertIsNotNone(turned, "the board never turned")
            late = (turned.header.stamp - ahead).to_sec()
            self.assertGreaterEqual(late, 0.0)
            self.assertLess(late, 0.1)  # (states come at ~publish_rate)
        finally:
            client.update_configuration({"step": 0.001})
            self.tilt.publish(BoardTilt())  # level again, at once

    def test_9c_commands_stamped_far_ahead_are_a_warning(self):
        # Twenty commands stamped a day ahead (a wall-time stamp sent to a node on simulated
        # time, say) wait for their steps: /diagnostics warns and says how long.
        try:
            for k in range(20):
                command = BoardTilt(roll=0.01)
                command.header.stamp = rospy.get_rostime() + rospy.Duration(86400 + k)
                self.tilt.publish(command)
            status = self.diagnostics.wait(
                lambda a: any("wait for their steps" in s.message for s in a.status), timeout=10)
            self.assertIsNotNone(status, "/diagnostics does not warn of commands held a day")
            values = {kv.key: kv.value for s in status.status for kv in s.values}
            self.assertGreater(float(values["seconds until the last queued command acts"]), 86000)
            self.assertEqual(values["commands queued"], "20")
        finally:
            call("reset", Trigger)  # (the queue goes with it)


if __name__ == "__main__":
    rospy.init_node("test_services")
    rostest.rosrun("marble_maze", "services", ServicesTest)
