#!/usr/bin/env python3
"""rostest: tianracer.launch robot_name:=other. Every node follows the name: the simulator
serves the controllers and joint_states under /other, robot_state_publisher listens to
/other/joint_states (so the wheels are in TF), the cmd_vel node commands /other's controllers
(so /cmd_vel drives the car) and wheel odometry reads /other/joint_states into /other/odom.
Nothing is left under /tianracer.
"""
import math
import os
import sys

import rospy
import rostest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from tianracer_sim.sim_time import Stream

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tf_check  # noqa: E402


class RobotName(tf_check.CarTestCase):
    node_name, ns = 'test_robot_name', '/other'

    @classmethod
    def streams(cls):
        return {'joints': Stream('/other/joint_states', JointState),
                'odom': Stream('/other/odom', Odometry)}

    def test_a_wheels_in_tf(self):
        for link in tf_check.urdf_links():
            chain = self.tf.chain(link, 'odom')
            self.assertIsNotNone(chain, '%s does not chain up to odom (parents: %s)' %
                                 (link, self.tf.parent))
        for wheel in ('left_rear_wheel', 'right_rear_wheel', 'left_front_wheel',
                      'right_front_wheel'):
            self.assertEqual(self.tf.publishers[wheel], {'/robot_state_publisher'}, wheel)
        self.assertEqual(self.odom.latest().child_frame_id, 'base_link')

    def test_b_cmd_vel_drives_the_car(self):
        t0, t1 = tf_check.drive('/cmd_vel', 0.5, 0.0, 2.0)
        p0 = self.truth.first_stamped(t0).pose.pose
        p1 = self.truth.first_stamped(t1).pose.pose
        moved = math.hypot(p1.position.x - p0.position.x, p1.position.y - p0.position.y)
        rospy.loginfo('drove %.3f m', moved)
        self.assertGreater(moved, 0.7)  # 1 m less what the start from rest costs
        self.assertGreater(self.odom.first_stamped(t1).pose.pose.position.x, 0.7)

    def test_c_nothing_under_the_default_name(self):
        topics = [t for t, _ in rospy.get_published_topics()]
        self.assertEqual([t for t in topics if t.startswith('/tianracer/')], [])


if __name__ == '__main__':
    rostest.rosrun('tianracer_bringup', 'robot_name', RobotName)
