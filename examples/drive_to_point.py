#!/usr/bin/env python3
"""Drives the marble to a point of the board (~x, ~y, m) and holds it there: a closed loop over
marble_state and tilt, the smallest controller that works. A rolling marble speeds up at
(5/7) g sin(tilt) down the slope: positive pitch lowers the board's +x edge, positive roll
raises its +y edge."""
import math

import rospy
from marble_maze.msg import BoardTilt, MarbleState

KP, KD = 4.0, 3.0  # 1/s^2, 1/s: the acceleration wanted per metre off and per m/s of speed
LIMIT = 0.17  # rad, within the board's tilt limit
PER_RADIAN = 5.0 / 7.0 * 9.81  # m/s^2 of acceleration per unit sin(tilt)


def tilt_for(acceleration):
    return max(-LIMIT, min(LIMIT, math.asin(max(-1.0, min(1.0, acceleration / PER_RADIAN)))))


def main():
    rospy.init_node("drive_to_point")
    x, y = rospy.get_param("~x", 0.0), rospy.get_param("~y", 0.0)
    tilt = rospy.Publisher("tilt", BoardTilt, queue_size=1)

    def on_state(s):
        command = BoardTilt()
        command.header.stamp = rospy.Time.now()
        command.pitch = tilt_for(KP * (x - s.position_in_board.x) - KD * s.velocity.x)
        command.roll = -tilt_for(KP * (y - s.position_in_board.y) - KD * s.velocity.y)
        try:
            tilt.publish(command)
        except rospy.ROSException:  # the publisher closes as the node shuts down (Ctrl-C)
            if not rospy.is_shutdown():
                raise

    rospy.Subscriber("marble_state", MarbleState, on_state, queue_size=1)
    rospy.spin()


if __name__ == "__main__":
    main()
