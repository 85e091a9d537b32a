#!/usr/bin/env python3
"""A tf listener for test_record_replay.py: looks up world -> marble at 20 Hz of wall time and
prints each failure; tf2's own warnings (TF_REPEATED_DATA, TF_OLD_DATA) go to its stderr."""
import time

import rospy
import tf2_ros

rospy.init_node("tf_listener", anonymous=True)
buffer = tf2_ros.Buffer()
listener = tf2_ros.TransformListener(buffer)
lookups = 0
while not rospy.is_shutdown():
    try:
        buffer.lookup_transform("world", "marble", rospy.Time(0))
        lookups += 1
    except (tf2_ros.LookupException, tf2_ros.ExtrapolationException,
            tf2_ros.ConnectivityException):
        pass
    time.sleep(0.05)
print("lookups %d" % lookups, flush=True)
