#!/usr/bin/env python3
"""An odometry relay as Gazebo car stacks ship them: /gazebo/link_states in, the pose and
twist of one link out as nav_msgs/Odometry (twist in the link's own frame, as a p3d plugin
gives it). Parameters: ~link (tianracer::base_link), ~frame_id (world), ~child_frame_id
(base_link). Publishes ~odom. It answers every link_states message (no queue drops either
way): a test finds its answer to a given one (test_gazebo_interface.py)."""
import rospy
from gazebo_msgs.msg import LinkStates
from nav_msgs.msg import Odometry
from tianracer_sim.sim_time import lossless


def rotate_into(q, v):
    """v (world) expressed in the frame whose orientation is q: R(q)^T v."""
    x, y, z, w = q.x, q.y, q.z, q.w
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [sum(r[i][j] * v[i] for i in range(3)) for j in range(3)]


class Relay(object):
    def __init__(self):
        self.link = rospy.get_param('~link', 'tianracer::base_link')
        self.frame_id = rospy.get_param('~frame_id', 'world')
        self.child_frame_id = rospy.get_param('~child_frame_id', 'base_link')
        self.pub = rospy.Publisher('~odom', Odometry, queue_size=1000)
        lossless(rospy.Subscriber('/gazebo/link_states', LinkStates, self.on_states))

    def on_states(self, msg):
        try:
            i = msg.name.index(self.link)
        except ValueError:
            rospy.logwarn_throttle(5.0, '%s is not in /gazebo/link_states', self.link)
            return
        odom = Odometry()
        odom.header.stamp = rospy.Time.now()
        odom.header.frame_id = self.frame_id
        odom.child_frame_id = self.child_frame_id
        odom.pose.pose = msg.pose[i]
        t = msg.twist[i]
        q = msg.pose[i].orientation
        lin = rotate_into(q, [t.linear.x, t.linear.y, t.linear.z])
        ang = rotate_into(q, [t.angular.x, t.angular.y, t.angular.z])
        odom.twist.twist.linear.x, odom.twist.twist.linear.y, odom.twist.twist.linear.z = lin
        odom.twist.twist.angular.x, odom.twist.twist.angular.y, odom.twist.twist.angular.z = ang
        self.pub.publish(odom)


if __name__ == '__main__':
    rospy.init_node('link_states_odometry_relay')
    Relay()
    rospy.spin()
