#!/usr/bin/env python3
"""rostest of ~lockstep (run by lockstep.test, control period 0.02 s): each tilt command is
answered by a marble_state exactly one control period (20 steps) later in simulated time, with
the command in force; a burst of 300 commands is taken whole; a reset between commands is shown
at once, at the stamp of the state before it; a refused (NaN) command is answered by the state as
it stands, at the same stamp; paused, a command waits for the next step taken; between commands
/clock is said again at the time it stands at; and the example agent (examples/lockstep_agent.py)
brings the marble within 5 mm of its point, printing the steps per second of wall time it
reaches."""
import importlib.util
import math
import os
import threading
import time
import unittest

import rospy
import rostest

import lockstep_link

from marble_maze.msg import BoardTilt
from marble_maze.srv import Step
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Trigger

PERIOD_NS = 20 * 10**6
COMMANDS = 200


class LockstepTest(unittest.TestCase):
    def connect(self):
        return lockstep_link.connect()

    def test_each_command_advances_one_period(self):
        states, arrived, tilt = self.connect()
        begin = time.time()
        for k in range(COMMANDS):
            with arrived:
                before = len(states)
                tilt.publish(BoardTilt(roll=0.0, pitch=0.05))
                self.assertTrue(arrived.wait_for(lambda: len(states) > before, timeout=5),
                                "no state after command %d" % k)
        wall = time.time() - begin
        stamps = [s.header.stamp.to_nsec() for s in states[-COMMANDS:]]
        steps = [(b - a) for a, b in zip(stamps, stamps[1:])]
        self.assertEqual(set(steps), {PERIOD_NS})
        self.assertAlmostEqual(states[-1].pitch, 0.05, delta=1e-9)  # the command in force
        print("lockstep: %d commands in %.2f s of wall time: %.0f steps per second"
              % (COMMANDS, wall, COMMANDS * 20 / wall))

    def test_a_burst_of_commands_is_taken_whole(self):
        # 300 commands at once, each running its period before the next is read: every one is
        # taken (the node's queue was 100 deep, and the rest went without a word).
        states, arrived, burst = self.connect()
        with arrived:
            before = len(states)
        for _ in range(300):
            burst.publish(BoardTilt(roll=0.01, pitch=0.0))
        with arrived:
            self.assertTrue(arrived.wait_for(lambda: len(states) - before >= 300, timeout=30),
                            "%d states for 300 commands" % (len(states) - before))
            stamps = [s.header.stamp.to_nsec() for s in states[before:]]
        self.assertEqual({b - a for a, b in zip(stamps, stamps[1:])}, {PERIOD_NS})

    def answer_to(self, states, arrived, act, what):
        """Does `act` and returns the state that answers it (within 5 s)."""
        with arrived:
            before = len(states)
            act()
            self.assertTrue(arrived.wait_for(lambda: len(states) > before, timeout=5), what)
            return states[-1]

    def test_a_reset_is_shown_at_once_at_the_same_stamp(self):
        states, arrived, tilt = self.connect()
        moved = self.answer_to(states, arrived, lambda: tilt.publish(BoardTilt(pitch=0.08)),
                               "no state after a command")
        rospy.wait_for_service("reset", timeout=20)
        # No command since: time has not moved, and the reset state comes all the same.
        reset = rospy.ServiceProxy("reset", Trigger)
        shown = self.answer_to(states, arrived, lambda: self.assertTrue(reset().success),
                               "no state after the reset")
        self.assertEqual(shown.header.stamp, moved.header.stamp)
        self.assertEqual((shown.roll, shown.pitch), (0.0, 0.0))  # the board back level
        self.assertNotEqual(moved.pitch, 0.0)

    def test_a_refused_command_is_answered_by_the_state_as_it_stands(self):
        # A NaN tilt is refused; the agent waiting for its answer gets the state unchanged, at
        # the stamp of the one before (it got nothing, and its loop stopped at its timeout).
        states, arrived, tilt = self.connect()

        def command(roll, pitch):
            return lambda: tilt.publish(BoardTilt(roll=roll, pitch=pitch))

        last = self.answer_to(states, arrived, command(0.0, 0.03), "no state after a command")
        answer = self.answer_to(states, arrived, command(float("nan"), 0.0),
                                "no answer to a refused command")
        after = self.answer_to(states, arrived, command(0.0, 0.03), "the loop did not go on")
        self.assertEqual(answer.header.stamp, last.header.stamp)
        self.assertEqual((answer.position, answer.pitch), (last.position, last.pitch))
        self.assertEqual(after.header.stamp.to_nsec() - last.header.stamp.to_nsec(), PERIOD_NS)

    def test_paused_a_command_waits_for_the_next_step_taken(self):
        states, arrived, tilt = self.connect()
        rospy.wait_for_service("pause", timeout=20)
        self.assertTrue(rospy.ServiceProxy("pause", Trigger)().success)
        try:
            step = rospy.ServiceProxy("step", Step)
            base = step(1).state
            time.sleep(0.5)  # the step's own state comes
            with arrived:
                before = len(states)
            tilt.publish(BoardTilt(roll=0.03, pitch=-0.02))
            time.sleep(1.0)
            with arrived:  # no step taken: no state at all
                self.assertEqual(len(states), before)
                self.assertFalse([m for m in states if m.header.stamp > base.header.stamp])
            # One step taken: the command acts from it.
            after = step(1).state
            self.assertEqual(after.header.stamp.to_nsec() - base.header.stamp.to_nsec(), 10**6)
            self.assertGreater(after.roll, base.roll)
        finally:
            self.assertTrue(rospy.ServiceProxy("resume", Trigger)().success)

    def test_between_commands_the_clock_is_said_again(self):
        # A node started while no command comes learns the time: /clock is said again, at the
        # stamp of the last state (the time stands between commands).
        states, arrived, tilt = self.connect()
        with arrived:
            before = len(states)
            tilt.publish(BoardTilt(roll=0.01, pitch=0.0))
            self.assertTrue(arrived.wait_for(lambda: len(states) > before, timeout=5))
            last = states[-1].header.stamp
        time.sleep(0.3)  # no command meanwhile
        ticks, said = [], threading.Event()

        def on_clock(msg):
            ticks.append(msg.clock)
            if len(ticks) >= 3:
                said.set()

        clock = rospy.Subscriber("/clock", Clock, on_clock)
        try:
            self.assertTrue(said.wait(5), "/clock not said again within 5 s without a command")
        finally:
            clock.unregister()
        self.assertEqual(set(t.to_nsec() for t in ticks[:3]), {last.to_nsec()})

    def test_the_example_agent_reaches_its_point(self):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                            "lockstep_agent.py")
        spec = importlib.util.spec_from_file_location("lockstep_agent", path)
        agent = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(agent)
        last, rate = agent.run(x=-0.04, y=0.02, commands=400)  # 8 s of simulated time
        print("example agent: %.0f periods (x 20 steps) a second of wall time" % rate)
        off = math.hypot(last.position_in_board.x + 0.04, last.position_in_board.y - 0.02)
        self.assertLess(off, 0.005)


if __name__ == "__main__":
    rospy.init_node("test_lockstep")
    rostest.rosrun("marble_maze", "lockstep", LockstepTest)
