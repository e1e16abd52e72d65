#!/usr/bin/env python3
"""rostest: tianracer.launch end to end.

- The TF tree is complete: every link of robot_description, the lidar's frame and both
  cameras' optical frames chain up to odom, and odom to world; no frame has two publishers or
  two parents.
- /cmd_vel drives the car: 0.5 m/s with a yaw rate of 0.1 rad/s for 3 s of sim time moves the
  ground truth forward along the racetrack's start straight and turns it left by about 0.3 rad
  (a 5 m radius keeps it off the inner wall, 0.5 m to the left).
"""
import math
import os
import sys

import rospy
import rostest
from sensor_msgs.msg import CameraInfo
from tianracer_sim.sim_time import Stream

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tf_check  # noqa: E402


class Bringup(tf_check.CarTestCase):
    node_name, ns = 'test_bringup', '/tianracer'

    @classmethod
    def streams(cls):
        return {'scan': tf_check.scans('/scan'),
                'camera_info': Stream('/rrbot/camera1/camera_info', CameraInfo),
                'depth_info': Stream('/real_sense/depth/camera_info', CameraInfo)}

    def test_a_tf_tree_complete_without_duplicates(self):
        frames = tf_check.urdf_links() + [self.scan.latest().header.frame_id,
                                          self.camera_info.latest().header.frame_id,
                                          self.depth_info.latest().header.frame_id]
        self.assertIn('camera_optical_frame', frames)
        self.assertIn('real_sense_optical_frame', frames)
        for frame in frames:
            chain = self.tf.chain(frame, 'odom')
            self.assertIsNotNone(chain, '%s does not chain up to odom (parents: %s)' %
                                 (frame, self.tf.parent))
            self.assertIn('base_link', chain)
        self.assertEqual(self.tf.chain('odom', 'world'), ['odom', 'world'])
        self.assertEqual(self.tf.duplicates(), {})
        # Who publishes what: wheel odometry the moving odom -> base_link, the simulator the
        # optical frames and world -> odom, robot_state_publisher the links.
        self.assertEqual(self.tf.publishers['base_link'], {'/wheel_odometry_node'})
        self.assertEqual(self.tf.publishers['odom'], {'/tianracer_sim'})
        self.assertEqual(self.tf.publishers['camera_optical_frame'], {'/tianracer_sim'})
        self.assertEqual(self.tf.publishers['lidar'], {'/robot_state_publisher'})

    def test_b_cmd_vel_drives_the_car(self):
        t0, t1 = tf_check.drive('/cmd_vel', 0.5, 0.1, 3.0)
        p0 = self.truth.first_stamped(t0).pose.pose
        p1 = self.truth.first_stamped(t1).pose.pose
        yaw0, yaw1 = tf_check.yaw_of(p0.orientation), tf_check.yaw_of(p1.orientation)
        dx, dy = p1.position.x - p0.position.x, p1.position.y - p0.position.y
        forward = math.cos(yaw0) * dx + math.sin(yaw0) * dy
        left = -math.sin(yaw0) * dx + math.cos(yaw0) * dy
        turned = math.atan2(math.sin(yaw1 - yaw0), math.cos(yaw1 - yaw0))
        elapsed = t1 - t0
        rospy.loginfo('drove %.3f s: forward %.3f m, left %.3f m, turned %.3f rad', elapsed,
                      forward, left, turned)
        # An arc of radius v / w = 5 m over 0.3 rad: 1.48 m ahead, 0.22 m to the left, less
        # what the start from rest costs.
        self.assertGreater(forward, 1.2)
        self.assertGreater(left, 0.1)
        self.assertLess(left, 0.3)
        self.assertAlmostEqual(turned, 0.1 * 3.0, delta=0.08)


if __name__ == '__main__':
    rostest.rosrun('tianracer_bringup', 'bringup', Bringup)
