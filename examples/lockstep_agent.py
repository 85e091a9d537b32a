#!/usr/bin/env python3
"""A gym-like agent loop over plain topics, for a node started with ~lockstep (e.g.
roslaunch marble_maze sim.launch lockstep:=0.02): each tilt command advances the simulation one
control period, and the state after it comes back. This agent steers the marble to a point of the
board (~x, ~y, m) for ~commands periods and prints how many steps a second of wall time it ran."""
import math
import threading
import time

import rosgraph
import rospy
from marble_maze.msg import BoardTilt, MarbleState


def wait_for_the_simulation(tilt, timeout=20.0):
    """Waits until the node that takes `tilt` and publishes marble_state has connected to the
    publisher: a command sent before would reach only the subscribers already there (a recorder
    started first), and no answer would come. False if the node is shut down meanwhile."""
    master = rosgraph.Master(rospy.get_name())
    state_topic = rospy.resolve_name("marble_state")
    deadline = time.time() + timeout
    while not rospy.is_shutdown() and time.time() < deadline:
        publishers, subscribers, _ = master.getSystemState()
        simulation = ({n for t, nodes in publishers if t == state_topic for n in nodes} &
                      {n for t, nodes in subscribers if t == tilt.resolved_name for n in nodes})
        if simulation and simulation <= {c.endpoint_id for c in tilt.impl.connections}:
            return True
        time.sleep(0.05)
    if rospy.is_shutdown():
        return False
    raise RuntimeError("no node publishing %s and subscribed to %s connected within %g s: is the "
                       "simulation running?" % (state_topic, tilt.resolved_name, timeout))


def run(x=0.05, y=0.03, commands=500, gain=(4.0, 3.0)):
    """Plays `commands` periods; returns the last state and the periods per second of wall time
    (None and 0 when the node was shut down before the simulation came)."""
    state, lock = [None], threading.Condition()

    def on_state(msg):
        with lock:
            state[0] = msg
            lock.notify()

    rospy.Subscriber("marble_state", MarbleState, on_state, queue_size=1)
    tilt = rospy.Publisher("tilt", BoardTilt, queue_size=1)
    if not wait_for_the_simulation(tilt):
        return None, 0.0
    with lock:  # (the state the node showed when it started, if it came)
        seen = state[0].header.stamp if state[0] is not None else rospy.Time()
    command, begin = BoardTilt(), time.time()
    for _ in range(commands):  # act, then observe: one control period each time
        # The answer is the first state stamped later than any seen: a state shown at once by a
        # reset, place or load (the stamp of the one before it) may still be on its way.
        with lock:
            state[0] = None
            tilt.publish(command)
            lock.wait_for(lambda: state[0] is not None and state[0].header.stamp > seen,
                          timeout=5.0)
            s = state[0]
        if s is None or s.header.stamp <= seen:
            raise RuntimeError("no marble_state within 5 s of a tilt command: is the node "
                               "running, with ~lockstep?")
        seen = s.header.stamp
        ax = gain[0] * (x - s.position_in_board.x) - gain[1] * s.velocity.x
        ay = gain[0] * (y - s.position_in_board.y) - gain[1] * s.velocity.y
        command = BoardTilt(pitch=math.asin(max(-0.17, min(0.17, ax / 7.0))),
                            roll=-math.asin(max(-0.17, min(0.17, ay / 7.0))))
    return s, commands / (time.time() - begin)


if __name__ == "__main__":
    rospy.init_node("lockstep_agent")
    last, rate = run(rospy.get_param("~x", 0.05), rospy.get_param("~y", 0.03),
                     rospy.get_param("~commands", 500))
    if last is not None:  # (None: shut down before the simulation came)
        print("marble at (%.3f, %.3f) m after %d periods: %.0f periods a second of wall time"
              % (last.position_in_board.x, last.position_in_board.y,
                 rospy.get_param("~commands", 500), rate))
