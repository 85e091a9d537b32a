#!/usr/bin/env python3
"""rostest (reconfigure.test): the description the node serves to dynamic_reconfigure, decoded
by dynamic_reconfigure's own client and encoding as rqt_reconfigure and dynparam decode it. Every
live key is there with its type, its range and its default as the key table has them (read from
`simulate --help`, which prints the same table), a choice key with its names as an enum that
the node accepts one by one, and a value beyond a range is refused."""
import ast
import re
import subprocess
import unittest

import rospy
import rostest
from dynamic_reconfigure import DynamicReconfigureParameterException
from dynamic_reconfigure.client import Client

NODE = "/marble_maze"
# The keys that change while the node runs (doc/node.md, "Live tuning"); real_time_factor
# only with ~clock (clock.test sets it live), and this node follows ROS time.
LIVE = {"restitution", "friction", "rolling_resistance", "drag_coefficient", "model",
        "integrator", "step", "substeps", "tilt_limit", "tilt_rate_limit", "tilt_response_time"}


def key_table():
    """The key table as `simulate --help` prints it: key -> (range or None, default text)."""
    text = subprocess.run(["rosrun", "marble_maze", "simulate", "--help"], capture_output=True,
                          text=True, check=True).stdout
    table = {}
    for line in text.split("Keys for --set")[1].splitlines():
        m = re.match(r"  (\w+)(?: \[[^\]]*\])? +(.*) \(default (.*)\)$", line)
        if m:
            bounds = re.search(r", in \[([^,]+), ([^\]]+)\]$", m.group(2))
            table[m.group(1)] = (tuple(map(float, bounds.groups())) if bounds else None,
                                 m.group(3))
    return table


class ReconfigureTest(unittest.TestCase):
    def test_every_live_key_is_described_as_the_key_table_says(self):
        client = Client(NODE, timeout=20)
        descriptions = {d["name"]: d for d in client.get_parameter_descriptions()}
        self.assertEqual(set(descriptions), LIVE)
        table = key_table()
        for name, d in descriptions.items():
            bounds, default = table[name]
            if d["edit_method"]:  # a choice: an enum of strings
                self.assertEqual(d["type"], "str", name)
                choices = [e["value"] for e in ast.literal_eval(d["edit_method"])["enum"]]
                self.assertIn(default, choices, name)
                for choice in choices:  # each one accepted, as the node's parameter
                    self.assertEqual(client.update_configuration({name: choice})[name], choice)
                client.update_configuration({name: default})
                continue
            self.assertIsNotNone(bounds, name)
            self.assertEqual(d["type"], "int" if name == "substeps" else "double", name)
            self.assertEqual((d["min"], d["max"]), bounds, name)
            self.assertEqual(float(d["default"]), float(default), name)
        # Beyond its range, a value is refused and the one in force stays.
        before = client.get_configuration(timeout=10)["restitution"]
        after = client.update_configuration({"restitution": 1.5})["restitution"]
        self.assertEqual(after, before)
        # A key this node does not change live is not described, so the client refuses it.
        with self.assertRaisesRegex(DynamicReconfigureParameterException, "real_time_factor"):
            client.update_configuration({"real_time_factor": 5.0})


if __name__ == "__main__":
    rospy.init_node("test_reconfigure")
    rostest.rosrun("marble_maze", "reconfigure", ReconfigureTest)
