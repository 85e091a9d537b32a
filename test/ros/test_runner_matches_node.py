#!/usr/bin/env python3
"""rostest (runner_matches_node.test): a tilt program with a tilt timeout and an auto reset gives
the same trajectory, bit for bit, in the node and in simulate. The node runs in lockstep at its
step (1 ms), so that each command takes one step, as simulate commands each step that starts
within the program; after the program's last row no command comes, and the node is stepped
paused (the step service), as simulate steps on: the tilt timeout levels the board 0.2 s after
the last command, and the auto reset puts the marble back 0.3 s after the hole."""
import os
import subprocess
import tempfile
import unittest

import rospkg
import rospy
import rostest

import lockstep_link

from marble_maze.msg import BoardTilt
from marble_maze.srv import Step
from std_srvs.srv import Trigger

STEP = 0.001
# The board lowered towards +x over 0.1 s, held to 0.3 s: the marble rolls into the hole.
PROGRAM = [(0.0, 0.0, 0.0), (0.1, 0.0, 0.08), (0.3, 0.0, 0.08)]
DURATION = 1.5
CHUNK = 100  # steps a call of the step service takes after the program


def program_at(t):
    """The program's value at t, linear between rows (simulate's TiltSchedule)."""
    for (t0, r0, p0), (t1, r1, p1) in zip(PROGRAM, PROGRAM[1:]):
        if t0 <= t <= t1:
            s = (t - t0) / (t1 - t0)
            return r0 + s * (r1 - r0), p0 + s * (p1 - p0)
    return PROGRAM[-1][1:]


def simulate_rows(maze):
    """simulate's trajectory under the program, a row a step: (x, y, z, roll, pitch)."""
    with tempfile.TemporaryDirectory() as tmp:
        program = os.path.join(tmp, "program.csv")
        with open(program, "w") as f:
            f.writelines("%r,%r,%r\n" % row for row in PROGRAM)
        out = os.path.join(tmp, "trajectory.csv")
        subprocess.run(["rosrun", "marble_maze", "simulate", "--maze", maze,
                        "--tilt-csv", program, "--set", "initial_pitch=0",
                        "--tilt-timeout", "0.2", "--auto-reset", "0.3",
                        "--duration", str(DURATION), "--out", out, "--quiet"], check=True)
        with open(out) as f:
            lines = f.read().splitlines()[1:]
    rows = [[float(v) for v in line.split(",")[:12]] for line in lines]
    return [tuple(row[1:4] + row[10:12]) for row in rows]


def shown(state):
    p = state.position
    return (p.x, p.y, p.z, state.roll, state.pitch)


class RunnerMatchesNodeTest(unittest.TestCase):
    def test_the_same_program_gives_the_same_trajectory(self):
        maze = os.path.join(rospkg.RosPack().get_path("marble_maze"), "test", "ros",
                            "hole_beside.yaml")
        expected = simulate_rows(maze)
        rospy.wait_for_service("step")
        states, arrived, tilt = lockstep_link.connect()

        steps = 0
        while steps * STEP <= PROGRAM[-1][0] + 1e-12:
            roll, pitch = program_at(steps * STEP)
            with arrived:
                before = len(states)
                tilt.publish(BoardTilt(roll=roll, pitch=pitch))
                self.assertTrue(arrived.wait_for(lambda: len(states) > before, timeout=5),
                                "no state after command %d" % steps)
                steps += 1
                got = shown(states[-1])
            self.assertEqual(got, expected[steps], "at step %d" % steps)

        self.assertTrue(rospy.ServiceProxy("pause", Trigger)().success)
        step = rospy.ServiceProxy("step", Step)
        while steps < len(expected) - 1:
            chunk = min(CHUNK, len(expected) - 1 - steps)
            answer = step(chunk)
            self.assertTrue(answer.success, answer.message)
            steps += chunk
            self.assertEqual(shown(answer.state), expected[steps], "at step %d" % steps)
        # What the timed actions did: the board held its pitch to 0.5 s, then levelled; the
        # marble fell into the hole and was put back on the start.
        pitch = [row[4] for row in expected]
        self.assertGreater(pitch[500], pitch[490])  # still following the last command
        self.assertLess(pitch[520], pitch[500] - 0.01)  # levelling under the servo's lag
        self.assertLess(pitch[-1], 1e-6)
        heights = [row[2] for row in expected]
        fell = next(n for n, z in enumerate(heights) if z < 0)
        self.assertTrue(any(z > 0 for z in heights[fell:]), "never put back")
        print("runner and node: %d steps bit for bit; in the hole at step %d" % (steps, fell))


if __name__ == "__main__":
    rospy.init_node("test_runner_matches_node")
    rostest.rosrun("marble_maze", "runner_matches_node", RunnerMatchesNodeTest)
