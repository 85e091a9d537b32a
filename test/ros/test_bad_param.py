#!/usr/bin/env python3
"""rostest of marble_maze_node's start-up checks (run by bad_param.test), and the replay's, the
autopilot's and the tilt program's; and that SIGTERM ends the node and the tilt program cleanly.

The test starts the node itself, as a child process under the rostest master, with one bad
private parameter at a time, and checks that it exits by itself (within EXIT_TIMEOUT of wall
time) with a non-zero status and a FATAL message naming the parameter. A control run with good
parameters must still be running after the same time, so that an exit is due to the parameter.
Every run has its own node name (and so its own private namespace), which is chosen not to
contain the words the messages are searched for.
"""
import os
import signal
import subprocess
import sys
import tempfile
import unittest

import roslib.packages
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

PKG = "marble_maze"
EXIT_TIMEOUT = 20.0  # s of wall time: generous, for a loaded machine
CONTROL_RUN = 3.0  # s: how long the control run must keep running


def node_path(node="marble_maze_node"):
    paths = roslib.packages.find_node(PKG, node)
    assert paths, node + " not found (is the workspace built and sourced?)"
    return paths[0]


class BadParamTest(unittest.TestCase):
    def start(self, name, *params, node="marble_maze_node"):
        args = [node_path(node), "__name:=" + name] + list(params)
        # A fresh process group, so that a node that does not exit can be ended with what it
        # started (rosconsole writes FATAL and ERROR to stderr: keep both streams).
        return subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, start_new_session=True)

    def stop(self, process):
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGINT)
            try:
                return process.communicate(timeout=10)[0]
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
        return process.communicate()[0]

    def check_refused(self, name, params, *words, node="marble_maze_node"):
        process = self.start(name, *params, node=node)
        try:
            output = process.communicate(timeout=EXIT_TIMEOUT)[0]
        except subprocess.TimeoutExpired:
            output = self.stop(process)
            self.fail("the node still runs %g s after starting with %s; output:\n%s"
                      % (EXIT_TIMEOUT, " ".join(params), output))
        self.assertNotEqual(process.returncode, 0,
                            "exit status 0 with %s; output:\n%s" % (" ".join(params), output))
        self.assertIn("FATAL", output, output)
        for word in words:
            self.assertIn(word, output, "the message does not name %r:\n%s" % (word, output))
        return output

    def check_runs(self, name, *params):
        """The node still runs CONTROL_RUN after starting with `params`; returns its output."""
        process = self.start(name, *params)
        try:
            process.wait(timeout=CONTROL_RUN)
            self.fail("the node exited (status %s) with %s; output:\n%s"
                      % (process.returncode, " ".join(params), process.communicate()[0]))
        except subprocess.TimeoutExpired:
            pass
        output = self.stop(process)
        self.assertNotIn("FATAL", output)
        return output

    def test_control_good_params_keep_running(self):
        output = self.check_runs("bp_control", "_restitution:=0.7", "_maze:=classic",
                                 "_preset:=fast", "_integrator:=rk4")
        # The preset set the step; the integrator set after it overrides the preset's.
        self.assertIn("integrator rk4, step 0.005 s", output)

    def test_restitution_out_of_range(self):
        output = self.check_refused("bp_one", ["_restitution:=2.0"], "restitution")
        self.assertIn("/bp_one/", output)  # named in full, in the node's private namespace
        # It stays on the parameter server after the node: the way to clear it is said.
        self.assertIn("rosparam delete /bp_one/restitution", output)

    def test_unknown_parameter(self):
        self.check_refused("bp_two", ["_restitushun:=1"], "restitushun", "unknown")

    def test_missing_maze_file(self):
        self.check_refused("bp_three", ["_maze:=/nonexistent.yaml"], "maze", "/nonexistent.yaml")

    def test_rate_out_of_range(self):
        self.check_refused("bp_four", ["_publish_rate:=-5"], "publish_rate")

    def test_unknown_model(self):
        self.check_refused("bp_five", ["_model:=wooden"], "model", "wooden")

    def test_unknown_integrator_lists_the_accepted_ones(self):
        self.check_refused("bp_six", ["_integrator:=leapfrog"], "integrator", "leapfrog",
                           "velocity_verlet", "rk4")

    # The settings that cannot be simulated, refused by the node as by the runner.
    def test_zero_step(self):
        self.check_refused("bp_seven", ["_step:=0.0"], "step")

    def test_nan_restitution(self):
        self.check_refused("bp_eight", ["_restitution:=nan"], "restitution")

    def test_a_velocity_the_sweep_cannot_resolve(self):
        self.check_refused("bp_nine", ["_start_velocity:=1e158,0,0"], "start_velocity")

    def test_slots_of_1e308_metres_name_the_file_line_and_column(self):
        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as maze:
            maze.write("grid:\n  x: [1e308, 1e308]\n  y: 0.01\n  z: 0.01\nlayout: |\n  S G\n")
        try:
            self.check_refused("bp_ten", ["_maze:=" + maze.name], maze.name + ":2:", "out of range")
        finally:
            os.unlink(maze.name)

    # Frames that would break tf, and a marble that cannot start where it is put.
    def test_a_board_frame_named_as_the_world_frame(self):
        self.check_refused("bp_eleven", ["_board_frame:=world"], "board_frame", "world_frame")

    def test_a_marble_frame_named_as_the_board_frame(self):
        self.check_refused("bp_twelve", ["_marble_frame:=board"], "marble_frame", "board_frame")

    def test_an_empty_world_frame(self):
        self.check_refused("bp_seventeen", ["_world_frame:="], "world_frame", "needs a name")

    def test_a_frame_with_a_leading_slash(self):
        self.check_refused("bp_thirteen", ["_world_frame:=/world"], "world_frame", "'/'")

    def test_a_frame_with_a_space(self):
        self.check_refused("bp_spaced", ["_marble_frame:=my marble"], "marble_frame", "a space")

    def test_a_second_clock_is_refused_naming_the_first(self):
        first = self.start("bp_first_clock", "_clock:=true")
        try:
            rospy.wait_for_message("/clock", Clock, timeout=EXIT_TIMEOUT)  # the first owns it
            self.check_refused("bp_second_clock", ["_clock:=true"], "/clock", "/bp_first_clock")
            self.assertIsNone(first.poll(), "the first clock's node must run on")
        finally:
            self.stop(first)

    def test_a_namespace_names_the_frames_and_a_second_authority_is_named(self):
        # A node in namespace tfa broadcasts tfa/board and tfa/marble under the shared world;
        # another told to broadcast the same frames is named by both.
        own = self.start("bp_tf_own", "__ns:=/tfa")
        other = self.start("bp_tf_other", "_board_frame:=tfa/board", "_marble_frame:=tfa/marble")
        try:
            seen = set()
            deadline = rospy.get_time() + EXIT_TIMEOUT
            while len(seen) < 2 and rospy.get_time() < deadline:
                for t in rospy.wait_for_message("/tf", TFMessage, timeout=EXIT_TIMEOUT).transforms:
                    if t.header.frame_id in ("world", "tfa/board"):
                        seen.add((t.header.frame_id, t.child_frame_id))
            self.assertEqual(seen, {("world", "tfa/board"), ("tfa/board", "tfa/marble")})
            rospy.sleep(3.0)  # each looks for other publishers of /tf every 2 s
        finally:
            own_output, other_output = self.stop(own), self.stop(other)
        self.assertIn("tf: /bp_tf_other broadcasts 'tfa/", own_output)
        self.assertIn("tf: /tfa/bp_tf_own broadcasts 'tfa/", other_output)

    def test_a_start_position_inside_a_wall(self):
        # The classic maze's centre is a wall's post: tile (10, 8, 1).
        self.check_refused("bp_fourteen", ["_start_position:=[0, 0, 0.006]"], "start_position",
                           "inside tile (10, 8, 1)")

    def test_a_marble_wider_than_its_start_cell(self):
        self.check_refused("bp_fifteen", ["_marble_radius:=0.015"], "marble_radius",
                           "does not fit the start cell")

    def test_a_lockstep_period_longer_than_a_minute(self):
        # (Taken in one callback, a period of 1e6 s held the node for minutes.)
        self.check_refused("bp_twentyone", ["_lockstep:=1000"], "lockstep", "out of range")
        # and one of more steps a command than a call may take
        self.check_refused("bp_twentythree", ["_lockstep:=60", "_step:=0.000001"], "/step",
                           "lockstep", "more than 10000000 steps a command")
        # or of more substeps (refused with the words a live change gets)
        self.check_refused("bp_twentyfour", ["_lockstep:=20", "_substeps:=1000"], "/step",
                           "lockstep", "(of 1000 substeps each) more than 10000000 substeps")

    def test_a_rate_above_one_message_a_step(self):
        self.check_refused("bp_twentyfive", ["_publish_rate:=2000"], "/step: 0.001 s makes",
                           "fewer than ~publish_rate's 2000 Hz")

    def test_a_misspelt_built_in_maze_lists_the_built_in_ones(self):
        self.check_refused("bp_twentytwo", ["_maze:=clasic"], "maze", "clasic",
                           "neither a built-in maze (classic, brio, prototype)")

    def test_a_flag_of_the_wrong_type(self):
        self.check_refused("bp_eighteen", ["_clock:=sometimes"], "clock", "true or false")

    def test_the_replay_the_autopilot_and_the_tilt_program_refuse_a_parameter_of_a_wrong_type(self):
        # (They took a word for a number, or a number for a flag, as their default, silently.)
        self.check_refused("bp_thirty", ["_bag:=/nonexistent.bag", "_rate:=fast"], "rate",
                           "expected a number", node="replay")
        self.check_refused("bp_thirtyone", ["_bag:=/nonexistent.bag", "_wait:=1"], "wait",
                           "true or false", node="replay")
        self.check_refused("bp_thirtytwo", ["_start_delay:=soon"], "start_delay",
                           "expected a number", node="autopilot")
        self.check_refused("bp_thirtythree", ["_program:=/nonexistent.csv", "_loop:=maybe"],
                           "loop", "true or false", node="tilt_program")

    def test_sigterm_ends_every_node_as_ctrl_c_does(self):
        # (kill, docker stop): through the destructors, with status 0, not killed by the signal.
        program = os.path.join(roslib.packages.get_pkg_dir(PKG), "config", "demo_tilt.csv")
        for name, node, params in [("bp_forty", "marble_maze_node", []),
                                   ("bp_fortyone", "tilt_program", ["_program:=" + program])]:
            process = self.start(name, *params, node=node)
            try:
                process.wait(timeout=CONTROL_RUN)
                self.fail("%s exited by itself: %s" % (node, process.communicate()[0]))
            except subprocess.TimeoutExpired:
                pass
            os.killpg(process.pid, signal.SIGTERM)
            try:
                output = process.communicate(timeout=EXIT_TIMEOUT)[0]
            except subprocess.TimeoutExpired:
                output = self.stop(process)
                self.fail("%s still runs after SIGTERM: %s" % (node, output))
            self.assertEqual(process.returncode, 0, "%s after SIGTERM:\n%s" % (node, output))

    def test_a_maze_file_of_garbage_and_one_of_twenty_megabytes(self):
        with tempfile.NamedTemporaryFile("wb", suffix=".yaml", delete=False) as garbage:
            garbage.write(bytes(range(256)) * 40)
        with tempfile.NamedTemporaryFile("wb", suffix=".yaml", delete=False) as huge:
            huge.write(b"# " + b"x" * (20 << 20) + b"\n")
        try:
            self.check_refused("bp_nineteen", ["_maze:=" + garbage.name], "maze", garbage.name)
            self.check_refused("bp_twenty", ["_maze:=" + huge.name], "maze", huge.name,
                               "more than 16 MB")
        finally:
            os.unlink(garbage.name)
            os.unlink(huge.name)

    def test_a_start_position_as_a_list_is_taken(self):
        # ROS's list form of a vector parameter: the start cell's centre, on the floor.
        self.check_runs("bp_sixteen", "_start_position:=[-0.12195, 0.098875, 0.006]")


if __name__ == "__main__":
    rospy.init_node("test_bad_param")
    rostest.rosrun(PKG, "bad_param", BadParamTest, sys.argv)
