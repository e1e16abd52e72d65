#!/usr/bin/env python3
"""rostest: a car model written for Gazebo (test/data/models), loaded through sim.launch and
control.launch, drives from /cmd_vel through the cmd_vel node with the geometry the node measured
from its URDF, and publishes every sensor at its rate (sim time) with the right fields, frames
and encodings. The private parameter ~model picks the model:
  car_prefixed  (b): prefix:=car1 names, p3d, IMU model plugin, a bgr8 camera;
  car_meshes    (c): a plain URDF with relative meshes and a 16-beam 3D lidar.
A 0.5 m/s, 0.5 rad/s turn has a 1 m radius whatever the car: a wrong wheelbase from the URDF
turns it wider or tighter, a wrong wheel radius changes the speed.
"""
import math
import os
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs import point_cloud2
from sensor_msgs.msg import CameraInfo, Image, Imu, PointCloud2, PointField
from tianracer_sim.sim_time import Stream, drive_twist, wait_for

from sim_node_binary import startup_output

V, W = 0.5, 0.5

# Per model: its namespace, base link, a wheel link, and per topic (type, rate in Hz, frame_id).
MODELS = {
    'car_prefixed': {
        'ns': '/car1', 'base': 'car1/base_link', 'wheel': 'car1/left_front_wheel',
        'topics': {
            '/car1/p3d/odom': (Odometry, 50.0, 'world'),
            '/car1/imu/data': (Imu, 100.0, 'car1/imu_link'),
            '/car1/front_camera/image_raw': (Image, 15.0, 'car1/camera_link_optical_frame'),
            '/car1/front_camera/camera_info': (CameraInfo, 15.0, 'car1/camera_link_optical_frame'),
        },
    },
    'car_meshes': {
        'ns': '/car_meshes', 'base': 'base_link', 'wheel': 'right_front_wheel',
        'topics': {
            '/velodyne_points': (PointCloud2, 10.0, 'velodyne'),
        },
    },
}


def mean(xs):
    return sum(xs) / len(xs)


class CarModelTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_car_models')
        cls.name = rospy.get_param('~model')
        cls.model = MODELS[cls.name]
        ns = cls.model['ns']
        cls.truth = Stream(ns + '/ground_truth/odom', Odometry)
        cls.odom = Stream(ns + '/odom', Odometry)
        cls.msgs = {topic: Stream(topic, msg_type, buff_size=1 << 24)
                    for topic, (msg_type, _, _) in cls.model['topics'].items()}
        cls.cmd = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)

    def drive(self, seconds, v=V, w=W):
        """Publishes the command while `seconds` of sim time pass; returns (start, end)."""
        t0 = drive_twist(self.cmd, seconds, v, w)
        return t0, rospy.get_time()

    @staticmethod
    def between(stream, t0, t1):
        """Messages stamped t0 <= stamp < t1, once one stamped t1 or later has come."""
        stream.first_stamped(t1)
        return [m for m in stream.between(t0, t1) if m.header.stamp.to_sec() < t1]

    def test_a_drives_with_its_measured_geometry(self):
        self.truth.wait_count(1)
        self.odom.wait_count(1)
        self.drive(4.0)  # into the steady turn
        t0, t1 = self.drive(3.0)
        truth = self.between(self.truth, t0, t1)
        odom = self.between(self.odom, t0, t1)
        self.assertGreater(len(truth), 50)
        v = mean([m.twist.twist.linear.x for m in truth])
        w = mean([m.twist.twist.angular.z for m in truth])
        print("%s: v %.4f m/s, w %.4f rad/s, radius %.4f m" % (self.name, v, w, v / w))
        self.assertAlmostEqual(v, V, delta=0.03 * V)
        self.assertAlmostEqual(v / w, V / W, delta=0.03 * V / W)
        # Wheel odometry: in the model's base link, and it sees the same turn.
        self.assertGreater(len(odom), 20)
        self.assertEqual(odom[-1].header.frame_id, 'odom')
        self.assertEqual(odom[-1].child_frame_id, self.model['base'])
        w_odom = mean([m.twist.twist.angular.z for m in odom])
        self.assertAlmostEqual(w_odom, w, delta=0.03 * w)

    def test_b_wheels_in_tf(self):
        """robot_state_publisher listens to this robot's joint_states: its wheels are in TF."""
        self.truth.wait_count(1)
        wait_for(lambda: self.tf_buffer.can_transform(self.model['base'], self.model['wheel'],
                                                      rospy.Time()),
                 '%s -> %s in TF' % (self.model['base'], self.model['wheel']), poll=0.1)

    def test_c_sensors_at_their_rates(self):
        for stream in self.msgs.values():
            stream.wait_count(1)
        t0, t1 = self.drive(4.0)
        for topic, (_, rate, frame) in self.model['topics'].items():
            msgs = self.between(self.msgs[topic], t0, t1)
            # What the sim published in [t0, t1) (header.seq counts it).
            published = msgs[-1].header.seq - msgs[0].header.seq + 1
            n_expected = rate * (t1 - t0)
            rospy.loginfo('%s: %d messages published (%d received) in %.2f s of sim time (%.1f '
                          'expected)', topic, published, len(msgs), t1 - t0, n_expected)
            self.assertAlmostEqual(published, n_expected, delta=0.1 * n_expected + 1, msg=topic)
            self.assertEqual(msgs[-1].header.frame_id, frame, topic)
            self.check(topic, msgs[-1])

    def test_d_robot_name_unlike_the_models_namespace_is_named(self):
        """robot_name:=other for a model whose gazebo_ros_control says /car1: the node says
        where the controllers really are (a sim of its own, own master, paused)."""
        if self.name != 'car_prefixed':
            return
        model = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'data',
                             'models', 'car_prefixed.xacro')
        out = startup_output(['_model:=' + model, '_robot_name:=other', '_paused:=true',
                              '_disable_sensors:=camera'],
                             ['~robot_name is', "robot 'other': 5 plugins and sensors"],
                             'robot_name_check')
        self.assertIn("~robot_name is 'other' but the model's gazebo_ros_control robotNamespace "
                      "is '/car1'", out)
        self.assertIn("robot 'other': 5 plugins and sensors", out)  # the start-up table

    def check(self, topic, m):
        if isinstance(m, Image):
            self.assertEqual(m.encoding, 'bgr8')
            self.assertEqual((m.width, m.height, m.step), (160, 120, 3 * 160))
            self.assertEqual(len(m.data), 3 * 160 * 120)
        elif isinstance(m, CameraInfo):
            self.assertEqual((m.width, m.height), (160, 120))
            # fx from the horizontal field of view: (w / 2) / tan(hfov / 2)
            self.assertAlmostEqual(m.K[0], 80.0 / math.tan(0.6), delta=1e-3)
        elif isinstance(m, Imu):
            self.assertGreater(abs(m.angular_velocity.z), 0.3)  # it is turning
        elif isinstance(m, Odometry):
            self.assertEqual(m.child_frame_id, 'car1/base_link')
        elif isinstance(m, PointCloud2):
            fields = [(f.name, f.datatype) for f in m.fields]
            self.assertEqual(fields[:4], [('x', PointField.FLOAT32), ('y', PointField.FLOAT32),
                                          ('z', PointField.FLOAT32),
                                          ('intensity', PointField.FLOAT32)])
            self.assertEqual(fields[4][0], 'ring')
            self.assertEqual(m.height * m.width * m.point_step, len(m.data))
            # In the empty world the downward beams (rings 0-7 of 16 from -15 to +15 degrees)
            # reach the ground, the others nothing: points only from rings 0..7.
            rings = {p[0] for p in point_cloud2.read_points(m, field_names=('ring',))}
            self.assertTrue(rings, 'empty cloud')
            self.assertLessEqual(rings, set(range(8)), rings)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'car_models', CarModelTest)
