#!/usr/bin/env python3
"""rostest of marble_maze_node under a simulated clock (run by sim_time.test, /use_sim_time true).

This test is the clock: it publishes /clock itself, from 100 s on in 10 ms ticks, at HALF the
speed of the wall clock (one tick per 20 ms of wall time), so that a node timing itself by the
wall clock would be caught by its rates and distances. It checks that
  - before the clock starts, the node publishes no marble_state, and says once that it waits;
  - marble_state stamps are never ahead of the clock (exact, in nanoseconds), the latest one is
    within one publish period and a step of it, and there are 50 per second of clock time;
  - under a tilt stamped on the clock, the marble rolls as the clock advances, exactly as the
    physics says for clock time: after the step in which the board snaps to the tilt, board
    y = y0 - (a'h^2/2 + a'h t' + a t'^2/2) and speed a'h + a t', with t' = t - h, a = 5/7 g
    sin(roll) (a rolling solid sphere; the default integrator, velocity Verlet, is exact on an
    incline) and a' the same at roll / 2 (the snapping step's forces act at its middle, the
    midpoint rule; what the board turning at 10 rad/s in that step gives the marble besides is
    measured, within 3e-6 m/s), within 1e-6 m and
    1e-6 m/s;
  - while the clock stands still for a second of wall time, no marble_state comes and nothing
    moves; when it goes on, so does the marble, as if there had been no pause (same formula);
  - when the clock restarts below the simulated time, the node follows it and keeps running.
rospy in this process follows /clock too, so waits here use time.sleep (wall time).
"""
import math
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from rosgraph_msgs.msg import Clock, Log

from marble_maze.msg import BoardTilt, MarbleState

PKG = "marble_maze"
NODE = "/marble_maze"
START_NS = 100 * 10**9  # the clock's first value
TICK_NS = 10 * 10**6  # the clock's step
TICK_WALL = 0.02  # s of wall time per tick: the clock runs at half speed
STEP = 0.001  # s: the node's simulation step (default)
PUBLISH_PERIOD = 0.02  # s: 1 / publish_rate (default 50 Hz)
ROLL = 0.01  # rad: the tilt of the motion test
G = 9.81
WAIT = 10.0  # s of wall time: the longest wait for anything that should happen
# The closed form below is exact for the default integrator but for the marble's small settling
# into the floor at the tilt (it matches to ~2e-8 m): these tolerances are tight enough that a
# tilt applied one step (1 ms) late or early, about 7e-5 m and 7e-5 m/s off after a second, fails.
POS_TOL = 1e-6  # m
SPEED_TOL = 1e-6  # m/s


def ns(stamp):
    return stamp.secs * 10**9 + stamp.nsecs


class Clock_:
    """Publishes /clock: nothing until started, then ticks up to a target and holds there
    (republishing the held value, which must not make the node step)."""

    def __init__(self):
        self.pub = rospy.Publisher("/clock", Clock, queue_size=10)
        self.lock = threading.Lock()
        self.started = False
        self.now_ns = START_NS
        self.target_ns = START_NS
        self.published_ns = None  # the latest value published: the node cannot know a later one
        self.tick_ns = TICK_NS
        threading.Thread(target=self._run, daemon=True).start()

    def _run(self):
        while not rospy.is_shutdown():
            with self.lock:
                if self.started:
                    if self.now_ns + self.tick_ns <= self.target_ns:
                        self.now_ns += self.tick_ns
                    self.published_ns = self.now_ns
                    value = self.now_ns
                else:
                    value = None
            if value is not None:
                self.pub.publish(Clock(clock=rospy.Time(0, value)))
            time.sleep(TICK_WALL)

    def start(self):
        with self.lock:
            self.started = True

    def now(self):
        with self.lock:
            return self.now_ns

    def published(self):
        with self.lock:
            return self.published_ns

    def set_tick(self, tick_ns):
        """Each tick (of TICK_WALL of wall time) advances the clock by tick_ns."""
        with self.lock:
            self.tick_ns = tick_ns

    def restart(self, at_ns):
        """Jumps back to at_ns (a restarted simulator, a looping bag) and holds there."""
        with self.lock:
            self.now_ns = self.target_ns = at_ns

    def advance_to(self, target_ns):
        """Ticks up to target_ns and returns when the clock is there (it then holds)."""
        with self.lock:
            self.target_ns = target_ns
        deadline = time.time() + WAIT + 2 * TICK_WALL * (target_ns - self.now()) / self.tick_ns
        while self.now() < target_ns:
            assert time.time() < deadline, "the clock thread does not tick"
            time.sleep(0.005)


class SimTimeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lock = threading.Lock()
        cls.states = []
        cls.ahead = []  # (stamp, clock) of states stamped ahead of the clock published so far
        cls.clock = Clock_()
        cls.tilt_pub = rospy.Publisher("tilt", BoardTilt, queue_size=10)
        rospy.Subscriber("marble_state", MarbleState, cls._on_state, queue_size=1000)
        cls.said = []  # what the node says on /rosout, from its start
        rospy.Subscriber("/rosout", Log, lambda m: m.name == NODE and cls.said.append(m.msg),
                         queue_size=100)
        # Wait (wall time) until the node is up, and connected to our tilt publisher.
        master = rosgraph.Master(rospy.get_name())
        deadline = time.time() + 30
        while time.time() < deadline:
            _, subs, _ = master.getSystemState()
            if NODE in dict(subs).get("/tilt", []) and cls.tilt_pub.get_num_connections() > 0:
                break
            time.sleep(0.1)
        else:
            raise AssertionError("%s did not subscribe tilt within 30 s" % NODE)

    @classmethod
    def _on_state(cls, msg):
        clock = cls.clock.published()
        with cls.lock:
            if clock is None or ns(msg.header.stamp) > clock:
                cls.ahead.append((ns(msg.header.stamp), clock))
            cls.states.append(msg)

    def count(self):
        with self.lock:
            return len(self.states)

    def since(self, index):
        with self.lock:
            return list(self.states[index:])

    def settle(self):
        """Gives the node (wall) time to act on the clock's latest value."""
        time.sleep(0.5)

    def check_not_ahead(self):
        with self.lock:
            self.assertFalse(self.ahead, "states stamped ahead of the clock (stamp, clock) ns: %s"
                             % self.ahead[:5])

    def check_latest_follows_clock(self):
        """The latest state is stamped within one publish period and a step of the clock."""
        latest = self.since(-1)[0]
        lag = (self.clock.now() - ns(latest.header.stamp)) * 1e-9
        self.assertGreaterEqual(lag, 0.0)
        self.assertLessEqual(lag, PUBLISH_PERIOD + STEP + 1e-9,
                             "latest stamp %.3f s behind the clock" % lag)

    # The step from T0 turns the board by ROLL at once, at 10 rad/s: what its turning surface gives
    # the marble through friction in that one step depends on how a turn within a step is taken
    # (about 1e-6 m/s). So the speed it leaves is measured on the first state, within SNAP_TOL of
    # the midpoint rule's, and after it the marble is held to the closed form.
    SNAP_TOL = 3e-6  # m/s
    kick = None

    def expected(self, stamp):
        """Board y and speed of the marble at `stamp` under ROLL from T0 (see the module's
        docstring). The step from T0 turns the board from level to ROLL, and velocity Verlet
        takes its forces at the step's middle (the midpoint rule): it rolls at ROLL / 2's
        acceleration for that step (and the kick measured), then at ROLL's."""
        t = max(0.0, (ns(stamp) - self.__class__.t0_ns) * 1e-9 - STEP)
        a = 5.0 / 7.0 * G * math.sin(ROLL)
        a_mid = 5.0 / 7.0 * G * math.sin(ROLL / 2)
        v1 = a_mid * STEP + (self.__class__.kick or 0.0)
        y = 0.5 * a_mid * STEP * STEP + v1 * t + 0.5 * a * t * t
        return self.__class__.y0 - y, v1 + a * t

    def check_motion(self, states):
        checked, worst_y, worst_v = 0, 0.0, 0.0
        for m in states:
            t = (ns(m.header.stamp) - self.__class__.t0_ns) * 1e-9
            if t <= 0:
                continue
            checked += 1
            self.assertAlmostEqual(m.roll, ROLL, delta=1e-12)
            self.assertAlmostEqual(m.position_in_board.x, 0.0, delta=1e-9)
            speed = math.hypot(m.velocity.y, m.velocity.z)
            if self.__class__.kick is None:
                self.__class__.kick = speed - self.expected(m.header.stamp)[1]
                print("the snapping step's kick: %.3g m/s" % self.__class__.kick)
                self.assertLess(abs(self.__class__.kick), self.SNAP_TOL)
            want, want_speed = self.expected(m.header.stamp)
            self.assertAlmostEqual(m.position_in_board.y, want, delta=POS_TOL,
                                   msg="board y at %.3f s after the tilt" % t)
            self.assertAlmostEqual(speed, want_speed, delta=SPEED_TOL,
                                   msg="speed at %.3f s after the tilt" % t)
            worst_y = max(worst_y, abs(m.position_in_board.y - want))
            worst_v = max(worst_v, abs(speed - want_speed))
        print("%d states checked: board y off by %.3g m at most, speed by %.3g m/s"
              % (checked, worst_y, worst_v))
        return checked

    def test_1_nothing_before_the_clock(self):
        time.sleep(1.0)
        self.assertEqual(self.count(), 0, "marble_state published before /clock started")
        self.assertTrue(rospy.get_param("/use_sim_time"))
        self.assertEqual(rospy.Time.now(), rospy.Time(0))
        # It says so, once, 2 s of wall time after its start (it said nothing: its check ran on
        # a timer of ROS time, which stands still until a clock comes).
        deadline = time.time() + WAIT

        def waiting():
            return [s for s in self.said if "waiting for /clock" in s]

        while not waiting() and time.time() < deadline:
            time.sleep(0.1)
        self.assertEqual(len(waiting()), 1, "said: %s" % self.said)
        self.assertEqual(self.count(), 0)

    def test_2_stamps_follow_the_clock(self):
        self.clock.start()
        deadline = time.time() + WAIT
        while self.count() == 0:
            self.assertLess(time.time(), deadline, "no marble_state after /clock started")
            time.sleep(0.01)
        first = self.since(0)[0]
        self.assertGreaterEqual(ns(first.header.stamp), START_NS)
        begin = self.clock.now()
        self.clock.advance_to(begin + 50 * TICK_NS)  # 0.5 s of clock time, 1 s of wall time
        self.settle()
        states = self.since(0)
        stamps = [ns(m.header.stamp) for m in states]
        self.assertTrue(all(b > a for a, b in zip(stamps, stamps[1:])), "stamps not increasing")
        # 50 states per second of clock time (not of wall time, which would make 100 here).
        window = [s for s in stamps if s > begin]
        rate = len(window) / ((self.clock.now() - begin) * 1e-9)
        self.assertGreater(rate, 40.0)
        self.assertLess(rate, 51.0)
        self.check_latest_follows_clock()
        self.check_not_ahead()
        # The marble rests at the start of a level board meanwhile.
        for m in states:
            self.assertEqual((m.roll, m.pitch), (0.0, 0.0))
            self.assertEqual((m.position_in_board.x, m.position_in_board.y), (0.0, 0.0))

    def test_3_rolls_as_the_clock_advances(self):
        # A tilt stamped 0.2 s of clock time ahead: applied at exactly that step.
        t0_ns = self.clock.now() + 20 * TICK_NS
        self.__class__.t0_ns = t0_ns
        # The step starting at T0 tilts the board at once (no rate limit): the marble's centre,
        # 6 mm above the pivot, is then 6 mm x sin(roll) along the board's y.
        self.__class__.y0 = 0.006 * math.sin(ROLL)
        msg = BoardTilt(roll=ROLL, pitch=0.0)
        msg.header.stamp = rospy.Time(0, t0_ns)
        for _ in range(3):
            self.tilt_pub.publish(msg)
            time.sleep(0.02)
        self.clock.advance_to(t0_ns)
        self.settle()
        before = self.since(0)
        self.assertEqual(before[-1].roll, 0.0, "the tilt was applied before its stamp")
        index = self.count()
        self.clock.advance_to(t0_ns + 80 * TICK_NS)  # 0.8 s of clock time
        self.settle()
        states = self.since(index)
        self.assertGreater(self.check_motion(states), 30)
        self.assertLess(states[-1].position_in_board.y, -0.02)  # it did roll, about 22 mm
        self.check_latest_follows_clock()
        self.check_not_ahead()

    def test_4_clock_stands_still(self):
        held = self.clock.now()
        self.settle()
        index = self.count()
        last = self.since(-1)[0]
        time.sleep(1.0)  # the clock holds (republished) for a second of wall time
        new = self.since(index)
        self.assertEqual(new, [], "marble_state while the clock stood still: stamps %s"
                         % [m.header.stamp.to_sec() for m in new])
        self.assertEqual(self.clock.now(), held)
        self.assertLessEqual(ns(last.header.stamp), held)
        self.check_latest_follows_clock()
        # /diagnostics goes on counting what comes meanwhile (its figures were set only when the
        # node stepped, and said 0 commands a second). The command is the one in force: the
        # motion checked next does not change.
        reports = []
        sub = rospy.Subscriber("/diagnostics", DiagnosticArray, reports.append, queue_size=100)
        for _ in range(40):
            self.tilt_pub.publish(BoardTilt(roll=ROLL, pitch=0.0))
            time.sleep(0.05)
        sub.unregister()
        rates = [float(v.value) for a in reports for st in a.status for v in st.values
                 if v.key == "tilt commands per second"]
        self.assertTrue(rates, "no /diagnostics while the clock stood still")
        self.assertGreater(max(rates), 5.0, rates)
        self.assertEqual(self.since(index), [])

    def test_5_clock_goes_on(self):
        held = self.clock.now()
        last = self.since(-1)[0]
        index = self.count()
        self.clock.advance_to(held + 40 * TICK_NS)  # 0.4 s more
        self.settle()
        states = self.since(index)
        self.assertTrue(states, "no marble_state after the clock went on")
        self.assertGreater(ns(states[0].header.stamp), held)
        self.assertLess(states[-1].position_in_board.y, last.position_in_board.y - 0.005)
        # As if the clock had never stopped: the same trajectory in clock time.
        self.assertGreater(self.check_motion(states), 15)
        self.check_latest_follows_clock()
        self.check_not_ahead()

    def test_6_clock_restarts_below_the_simulated_time(self):
        # The clock jumps back from about 101 s to 1 s: the node follows it and keeps running.
        self.clock.restart(1 * 10**9)
        time.sleep(0.5)
        index = self.count()
        self.clock.advance_to(1 * 10**9 + 30 * TICK_NS)
        self.settle()
        states = self.since(index)
        self.assertTrue(states, "no marble_state after the clock went back")
        for m in states[-10:]:
            self.assertLessEqual(ns(m.header.stamp), self.clock.now())
            self.assertGreaterEqual(ns(m.header.stamp), 1 * 10**9)
            self.assertTrue(math.isfinite(m.position_in_board.y))
        self.check_latest_follows_clock()

    def test_7_a_tilt_stamped_with_wall_time_is_held_and_said_so(self):
        # A tilt stamped with the wall clock (about 1.8e9 s) into a node on the simulated clock
        # (about 1 s) is held until the clock gets there: the node must say so at once, naming
        # the topic and how long it holds it, and meanwhile keep the tilt it has.
        warnings, heard = [], threading.Event()

        def on_log(msg):
            if msg.name == NODE and msg.level == Log.WARN and "held" in msg.msg:
                warnings.append(msg.msg)
                heard.set()

        rospy.Subscriber("/rosout", Log, on_log, queue_size=100)
        time.sleep(0.5)
        before = self.count()
        msg = BoardTilt(roll=-0.05, pitch=0.0)
        msg.header.stamp = rospy.Time.from_sec(time.time())  # wall time: the mistake
        self.tilt_pub.publish(msg)
        self.clock.advance_to(self.clock.now() + 20 * TICK_NS)
        self.assertTrue(heard.wait(WAIT), "no warning about the held tilt on /rosout")
        self.assertIn("/tilt", warnings[0])
        held = float(warnings[0].split(" is held ")[1].split(" s")[0])
        self.assertGreater(held, 1e9, warnings[0])  # about the wall clock's seconds since 1970
        self.settle()
        for m in self.since(before):
            self.assertNotAlmostEqual(m.roll, -0.05, delta=1e-6, msg="the held tilt acted")

    def test_7b_commands_act_in_stamp_order_and_a_past_stamp_at_once(self):
        # Two tilts ahead of the clock, sent latest first: they act in the order of their
        # stamps. Then one stamped a second in the past acts at the next step.
        now = self.clock.now()
        late, early = BoardTilt(roll=0.03), BoardTilt(roll=0.02)
        late.header.stamp = rospy.Time(0, now + 40 * TICK_NS)
        early.header.stamp = rospy.Time(0, now + 20 * TICK_NS)
        self.tilt_pub.publish(late)
        self.tilt_pub.publish(early)
        time.sleep(0.5)
        index = self.count()
        self.clock.advance_to(now + 60 * TICK_NS)
        self.settle()
        rolls = [m.roll for m in self.since(index)]
        first_early = next(i for i, r in enumerate(rolls) if abs(r - 0.02) < 1e-9)
        first_late = next(i for i, r in enumerate(rolls) if abs(r - 0.03) < 1e-9)
        self.assertLess(first_early, first_late, rolls)
        past = BoardTilt(roll=0.01)
        past.header.stamp = rospy.Time(0, self.clock.now() - 10**9)
        self.tilt_pub.publish(past)
        time.sleep(0.5)
        index = self.count()
        self.clock.advance_to(self.clock.now() + 3 * TICK_NS)
        self.settle()
        self.assertTrue(any(abs(m.roll - 0.01) < 1e-9 for m in self.since(index)),
                        "a command stamped in the past did not act")

    def test_8_clock_jumps_an_hour_forward(self):
        # The node skips the hour (a stalled simulator, a bag played from later on) instead of
        # replaying 3.6 million steps in a burst, and follows the clock from there.
        index = self.count()
        jumped_from = self.clock.now()
        self.clock.restart(jumped_from + 3600 * 10**9)
        self.clock.advance_to(self.clock.now() + 30 * TICK_NS)
        self.settle()
        states = self.since(index)
        self.assertTrue(states, "no marble_state after the jump")
        within = [m for m in states if jumped_from < ns(m.header.stamp) < self.clock.now() - 10**9]
        self.assertLess(len(within), 100, "the jumped hour was replayed: %d states" % len(within))
        self.check_latest_follows_clock()
        self.check_not_ahead()

    def test_9_clock_a_thousand_times_faster(self):
        # 20 s of clock per 20 ms of wall time for 2 s: the node keeps up or skips ahead, never
        # runs ahead of the clock, and its marble stays finite.
        index = self.count()
        self.clock.set_tick(int(1000 * TICK_WALL * 10**9))  # 1000 x real time
        try:
            self.clock.advance_to(self.clock.now() + 2000 * 10**9)
        finally:
            self.clock.set_tick(TICK_NS)
        self.clock.advance_to(self.clock.now() + 30 * TICK_NS)
        self.settle()
        states = self.since(index)
        self.assertGreater(len(states), 20)
        for m in states:
            self.assertTrue(math.isfinite(m.position_in_board.x + m.velocity.x), m)
        self.check_latest_follows_clock()
        self.check_not_ahead()


if __name__ == "__main__":
    rospy.init_node("test_sim_time")
    rostest.rosrun(PKG, "sim_time", SimTimeTest, sys.argv)
