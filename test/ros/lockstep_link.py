"""What a test in lockstep with the node needs (test_lockstep.py, test_runner_matches_node.py):
the states as they come and the tilt publisher, connected to the node."""
import threading
import time

import rospy

from marble_maze.msg import BoardTilt, MarbleState


def connect():
    """The states as they come (a list, and a condition notified on each), and the tilt
    publisher, connected to the node. Its queue holds a whole burst: rospy shares one connection
    among a process's publishers of a topic, with the queue of the first."""
    states, arrived = [], threading.Condition()

    def on_state(msg):
        with arrived:
            states.append(msg)
            arrived.notify()

    rospy.Subscriber("marble_state", MarbleState, on_state, queue_size=1000)
    tilt = rospy.Publisher("tilt", BoardTilt, queue_size=1000)
    deadline = time.time() + 20
    while tilt.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)  # (a fresh publisher's first message reaches only those connected)
    return states, arrived, tilt
