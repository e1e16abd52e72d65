#!/usr/bin/env python3
"""rostest: the IMUs and the p3d ground truth plugin of tianracer_imu.xacro in a steady turn (0.5 m/s, 0.5 rad/s through
/cmd_vel and the cmd_vel node) against the sim's ground truth, and the bad IMUs left out.

The sensor's plugin has no robotNamespace, so it publishes under the model's name
(/tianracer/imu), as Gazebo does. Ground truth is base_link's pose in the world and its twist in base_link; both IMUs sit on
base_link with no offset, so in a steady turn the yaw rate is the truth's, the lateral specific
force is v_x * w (centripetal), and the orientation's yaw is the truth's. Everything is sim time.
"""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty
from tianracer_sim.rotation import yaw_from_quaternion as yaw_of
from tianracer_sim.sim_time import Stream, drive_twist

from sim_node_binary import sensor_startup_output

V, W = 0.5, 0.5


def mean(xs):
    return sum(xs) / len(xs)


def stamp_key(msg):
    return round(msg.header.stamp.to_sec(), 6)


def same_stamps(samples, truth):
    """[(sample, the truth message with the same stamp)] for the samples that have one."""
    by_stamp = {stamp_key(m): m for m in truth}
    return [(m, by_stamp[stamp_key(m)]) for m in samples if stamp_key(m) in by_stamp]


class ImuTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_imu')
        cls.p3d = Stream('/tianracer/p3d/odom', Odometry)
        cls.truth = Stream('/tianracer/ground_truth/odom', Odometry)
        cls.imu = Stream('/tianracer/imu', Imu)
        cls.imu_model = Stream('/tianracer/imu_model', Imu)
        cls.cmd = rospy.Publisher('/cmd_vel', Twist, queue_size=10)

    def drive(self, seconds):
        """Publishes the turn command while `seconds` of sim time pass; returns (start, end)."""
        t0 = drive_twist(self.cmd, seconds, V, W)
        return t0, rospy.get_time()

    @staticmethod
    def between(stream, t0, t1):
        """Messages stamped t0..t1, once one stamped t1 or later has come."""
        stream.first_stamped(t1)
        return stream.between(t0, t1)

    def test_a_steady_turn(self):
        for stream in (self.truth, self.imu, self.imu_model):
            stream.wait_count(1)
        self.drive(4.0)  # into the steady turn
        t0, t1 = self.drive(4.0)
        truth = self.between(self.truth, t0, t1)
        imus = {'/tianracer/imu': self.between(self.imu, t0, t1),
                '/tianracer/imu_model': self.between(self.imu_model, t0, t1)}
        self.assertGreater(len(truth), 100)
        wz_true = mean([m.twist.twist.angular.z for m in truth])
        vx_true = mean([m.twist.twist.linear.x for m in truth])
        rospy.loginfo('truth: v_x %.4f m/s, w %.4f rad/s', vx_true, wz_true)
        self.assertGreater(wz_true, 0.4, 'the car is not turning')
        for topic, samples in imus.items():
            self.assertGreater(len(samples), 100, topic)
            self.assertEqual(samples[0].header.frame_id, 'base_link', topic)
            wz = mean([m.angular_velocity.z for m in samples])
            ay = mean([m.linear_acceleration.y for m in samples])
            az = mean([m.linear_acceleration.z for m in samples])
            rospy.loginfo('%s: w %.5f (truth %.5f), a_y %.5f (v w %.5f), a_z %.4f', topic, wz,
                          wz_true, ay, vx_true * wz_true, az)
            self.assertAlmostEqual(wz, wz_true, delta=0.01 * abs(wz_true), msg=topic)
            self.assertAlmostEqual(ay, vx_true * wz_true, delta=0.03 * vx_true * wz_true,
                                   msg=topic)
            self.assertAlmostEqual(az, 9.8, delta=0.05, msg=topic)
            matched = same_stamps(samples, truth)
            for m, t in matched:
                err = math.atan2(math.sin(yaw_of(m.orientation) - yaw_of(t.pose.pose.orientation)),
                                 math.cos(yaw_of(m.orientation) - yaw_of(t.pose.pose.orientation)))
                self.assertLess(abs(math.degrees(err)), 0.1, '%s at %.3f' % (topic, t.header.stamp.to_sec()))
            self.assertGreater(len(matched), 50, topic)
            cov = samples[-1].angular_velocity_covariance
            self.assertEqual(list(cov), [0.0] * 9, topic)  # noise off

    def test_ab_p3d_equals_ground_truth(self):
        """libgazebo_ros_p3d with noise off: the sim's ground truth at the same stamps, its twist
        in the world frame (p3d's convention) where ground_truth/odom has it in base_link."""
        self.p3d.wait_count(1)
        _, t1 = self.drive(1.0)
        self.truth.first_stamped(t1)
        truth = self.truth.messages()
        matched = same_stamps(self.between(self.p3d, 0.0, t1), truth)
        for m, t in matched:
            self.assertEqual(m.header.frame_id, 'world')
            self.assertEqual(m.child_frame_id, 'base_link')
            a, b = m.pose.pose, t.pose.pose
            for u, v in ((a.position.x, b.position.x), (a.position.y, b.position.y),
                         (a.position.z, b.position.z), (a.orientation.x, b.orientation.x),
                         (a.orientation.y, b.orientation.y), (a.orientation.z, b.orientation.z),
                         (a.orientation.w, b.orientation.w)):
                self.assertAlmostEqual(u, v, delta=1e-9)
            q = b.orientation
            yaw = yaw_of(q)
            vb = t.twist.twist.linear  # body frame; the car is level to within a fraction of a degree
            vx_w = math.cos(yaw) * vb.x - math.sin(yaw) * vb.y
            vy_w = math.sin(yaw) * vb.x + math.cos(yaw) * vb.y
            self.assertAlmostEqual(m.twist.twist.linear.x, vx_w, delta=2e-3)
            self.assertAlmostEqual(m.twist.twist.linear.y, vy_w, delta=2e-3)
            self.assertAlmostEqual(m.twist.twist.angular.z, t.twist.twist.angular.z, delta=2e-3)
            self.assertEqual(list(m.twist.covariance), [0.0] * 36)
        self.assertGreater(len(matched), 50)

    def test_b_bad_imus_left_out(self):
        """The bad IMUs are left out and the others publish (this sim)."""
        self.imu.wait_count(1)
        published = dict(rospy.get_published_topics())
        for topic in ('/tianracer/imu_bad_noise', '/tianracer/imu_bad_rate', '/imu_nowhere'):
            self.assertNotIn(topic, published)
        rospy.wait_for_service('/tianracer/imu_model/calibrate', timeout=10.0)
        rospy.ServiceProxy('/tianracer/imu_model/calibrate', Empty)()

    def test_c_bad_imu_messages(self):
        """What the node says about them: the same model in a sim of its own (own master), so
        that its start-up output can be read."""
        out = sensor_startup_output('tianracer_imu.xacro',
                                    ["'laplace'", "'-5'", 'no_such_link', "IMU 'imu_sensor'"],
                                    'imu_bad_input')
        expected = [('imu_bad_noise', "'laplace'"), ('imu_bad_rate', "'-5'"),
                    ('imu_nowhere', 'no_such_link')]
        for name, value in expected:
            lines = [l for l in out.splitlines() if name in l and value in l and
                     "robot 'tianracer'" in l and 'left out' in l]
            self.assertTrue(lines, 'no message naming %s and %s in:\n%s' % (name, value, out))
        self.assertIn("IMU 'imu_sensor'", out)  # the good one is set up in the same run


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'imu', ImuTest)
