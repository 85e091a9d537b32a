"""Unit tests of teleop_key's key handling: which way each key tilts the board, and the limits;
and its parameters: one that is not a positive number is refused by name.

Plain unittest, no ROS master: python3 test/ros/test_teleop_keys.py, or
python3 -m unittest discover -s test/ros (not "-m unittest test/ros/...": the standard library's own
`test` package shadows this folder). With --gtest_output=xml:FILE it writes JUnit XML for catkin.
"""
import importlib.machinery
import importlib.util
import os
import sys
import unittest

NODE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "nodes", "teleop_key")


def load_teleop():
    # The node has no .py extension, so its loader must be named; bytecode is not written beside
    # it so that the test leaves the source tree as it found it.
    loader = importlib.machinery.SourceFileLoader("teleop_key", NODE)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    dont_write_bytecode, sys.dont_write_bytecode = sys.dont_write_bytecode, True
    try:
        loader.exec_module(module)
    finally:
        sys.dont_write_bytecode = dont_write_bytecode
    return module


teleop = load_teleop()
STEP, LIMIT = 0.01, 0.1745


def press(*keys, roll=0.0, pitch=0.0):
    for key in keys:
        roll, pitch = teleop.next_target(key, roll, pitch, STEP, LIMIT)
    return roll, pitch


class NextTargetTest(unittest.TestCase):
    def test_right_raises_pitch_so_the_marble_rolls_to_plus_x(self):
        # Positive pitch lowers the board's +x side.
        self.assertEqual(press(teleop.RIGHT), (0.0, STEP))

    def test_left_lowers_pitch_so_the_marble_rolls_to_minus_x(self):
        self.assertEqual(press(teleop.LEFT), (0.0, -STEP))

    def test_up_lowers_roll_so_the_marble_rolls_to_plus_y(self):
        # Positive roll raises the board's +y side.
        self.assertEqual(press(teleop.UP), (-STEP, 0.0))

    def test_down_raises_roll_so_the_marble_rolls_to_minus_y(self):
        self.assertEqual(press(teleop.DOWN), (STEP, 0.0))

    def test_steps_add_up_and_opposite_keys_cancel(self):
        roll, pitch = press(teleop.RIGHT, teleop.RIGHT, teleop.RIGHT, teleop.UP)
        self.assertAlmostEqual(pitch, 3 * STEP)
        self.assertAlmostEqual(roll, -STEP)
        roll, pitch = press(teleop.LEFT, teleop.LEFT, teleop.LEFT, teleop.DOWN,
                            roll=roll, pitch=pitch)
        self.assertAlmostEqual(pitch, 0.0)
        self.assertAlmostEqual(roll, 0.0)

    def test_targets_are_clamped_to_the_limit(self):
        self.assertEqual(press(*[teleop.RIGHT] * 30), (0.0, LIMIT))
        self.assertEqual(press(*[teleop.LEFT] * 30), (0.0, -LIMIT))
        self.assertEqual(press(*[teleop.DOWN] * 30), (LIMIT, 0.0))
        self.assertEqual(press(*[teleop.UP] * 30), (-LIMIT, 0.0))

    def test_a_target_beyond_a_new_limit_is_pulled_back(self):
        self.assertEqual(press(teleop.UP, roll=0.5, pitch=-0.5), (LIMIT, -LIMIT))

    def test_space_levels_the_board(self):
        self.assertEqual(press(teleop.LEVEL, roll=0.1, pitch=-0.05), (0.0, 0.0))

    def test_other_keys_change_nothing(self):
        for key in ("x", "r", "q", "\x1b"):
            self.assertEqual(press(key, roll=0.03, pitch=-0.02), (0.03, -0.02))


class ParametersTest(unittest.TestCase):
    def test_a_parameter_that_is_not_a_positive_number_is_named(self):
        from unittest import mock
        for value in ("abc", True, 0, -0.01, [1]):
            with mock.patch.object(teleop.rospy, "get_param", return_value=value):
                with self.assertRaisesRegex(ValueError, "step: expected a positive number"):
                    teleop.positive("~step", 0.01)
        with mock.patch.object(teleop.rospy, "get_param", return_value=2):
            self.assertEqual(teleop.positive("~rate", 10.0), 2.0)


class DecodeKeysTest(unittest.TestCase):
    def test_arrow_sequences_in_normal_and_application_mode(self):
        self.assertEqual(teleop.decode_keys(b"\x1b[A\x1b[B\x1b[C\x1b[D"),
                         [teleop.UP, teleop.DOWN, teleop.RIGHT, teleop.LEFT])
        self.assertEqual(teleop.decode_keys(b"\x1bOA\x1bOD"), [teleop.UP, teleop.LEFT])

    def test_plain_characters_between_arrows(self):
        self.assertEqual(teleop.decode_keys(b" \x1b[Cr q"),
                         [" ", teleop.RIGHT, "r", " ", "q"])

    def test_nothing_read_gives_no_keys(self):
        self.assertEqual(teleop.decode_keys(b""), [])


if __name__ == "__main__":
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import xml_results
    xml_results.main()
