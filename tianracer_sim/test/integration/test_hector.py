#!/usr/bin/env python3
"""rostest: hector_gazebo_plugins' four sensors on hector_bot.urdf, at rest before a wall.

The IMU (namespace hector_bot, 100 Hz, frame base_link): +9.8 m/s^2 up, rates near 0 but for its
offset and drift, the bias topic, and its calibrate service setting the rate drift to 0 (the rate
bias is then the rateOffset). The GPS (10 Hz, frame base_link): at the origin the reference
latitude and longitude, the reference altitude, velocity 0. The magnetometer (50 Hz,
MagneticField): |B| 0.5 and 60 degrees of inclination (B_z = -0.5 sin 60). The sonar (ray
sensor at 20 Hz, the plugin's default 10 Hz): the wall 1.85 m ahead. Rates from header stamps
and seq numbers, in sim time. hector_bad.urdf (started apart, on a private master): each bad
plugin is left out with a message naming the file, line, plugin, element and value, and the
good magnetometer is simulated. Last, dynamic_reconfigure as upstream serves it: the
magnetometer's model (a vector model shows the mean of its components, a change sets all three)
and the GPS status.
"""
import os
import math
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
from geometry_msgs.msg import Vector3Stamped
from sensor_msgs.msg import Imu, MagneticField, NavSatFix, NavSatStatus, Range
from std_srvs.srv import Empty
from tianracer_sim.sim_time import Stream, published_rate, sim_sleep

from sim_node_binary import TEST_URDF, startup_output

WALL_TIMEOUT = 120.0


def mean(xs):
    return sum(xs) / len(xs)


class HectorTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_hector')
        cls.imu = Stream('/hector_bot/imu', Imu)
        cls.bias = Stream('/hector_bot/imu/bias', Imu)
        cls.fix = Stream('/gps/fix', NavSatFix)
        cls.vel = Stream('/gps/fix_velocity', Vector3Stamped)
        cls.mag = Stream('/hector_bot/magnetic', MagneticField)
        cls.sonar = Stream('/sonar', Range)
        for s in (cls.imu, cls.bias, cls.fix, cls.vel, cls.mag, cls.sonar):
            s.wait_count(1, WALL_TIMEOUT)
        sim_sleep(2.0)  # settled on the ground; two seconds of every topic

    def window(self, stream, seconds=1.0):
        """The messages of the last `seconds` of sim time received so far."""
        msgs = stream.messages()
        t1 = msgs[-1].header.stamp.to_sec()
        return [m for m in msgs if m.header.stamp.to_sec() >= t1 - seconds]

    def check_rate(self, stream, hz, frame):
        msgs = self.window(stream)
        self.assertGreater(len(msgs), 2, stream.topic)
        self.assertAlmostEqual(published_rate(msgs), hz, delta=0.01 * hz, msg=stream.topic)
        for m in msgs:
            self.assertEqual(m.header.frame_id, frame, stream.topic)
        return msgs

    def test_imu(self):
        msgs = self.check_rate(self.imu, 100.0, 'base_link')
        self.check_rate(self.bias, 100.0, 'base_link')
        az = mean([m.linear_acceleration.z for m in msgs])
        self.assertAlmostEqual(az, 9.8, delta=0.05)  # the specific force, up, at rest
        for axis in 'xy':
            self.assertAlmostEqual(mean([getattr(m.linear_acceleration, axis) for m in msgs]), 0.0,
                                   delta=0.05)
        q = msgs[-1].orientation
        self.assertAlmostEqual(q.x ** 2 + q.y ** 2 + q.z ** 2 + q.w ** 2, 1.0, places=6)
        self.assertGreater(abs(q.w), 0.99)  # upright, within the small heading error
        self.assertAlmostEqual(msgs[-1].linear_acceleration_covariance[0], 1e-4, places=10)
        # The rate drift drawn at start (rateDrift 0.1) is gone after calibrate: the bias is the
        # rateOffset (0.01 0.02 0.03) again, and so are the rates' means (noise 0.005).
        offset = (0.01, 0.02, 0.03)
        before = self.bias.latest().angular_velocity
        self.assertGreater(max(abs(before.x - offset[0]), abs(before.y - offset[1]),
                               abs(before.z - offset[2])), 1e-3)
        rospy.wait_for_service('/hector_bot/imu/calibrate', WALL_TIMEOUT)
        rospy.ServiceProxy('/hector_bot/imu/calibrate', Empty)()
        t = rospy.get_time()
        after = self.bias.first_stamped(t + 0.05).angular_velocity
        for got, want in zip((after.x, after.y, after.z), offset):
            self.assertAlmostEqual(got, want, delta=1e-3)
        sim_sleep(1.0)
        rates = self.window(self.imu, 0.9)
        for axis, want in zip('xyz', offset):
            self.assertAlmostEqual(mean([getattr(m.angular_velocity, axis) for m in rates]), want,
                                   delta=2e-3)

    def test_gps(self):
        msgs = self.check_rate(self.fix, 10.0, 'base_link')
        self.check_rate(self.vel, 10.0, 'base_link')
        m = msgs[-1]
        self.assertEqual(m.status.status, NavSatStatus.STATUS_FIX)
        self.assertEqual(m.position_covariance_type, NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN)
        self.assertAlmostEqual(m.position_covariance[0], 1e-8 + 1e-4, places=12)
        # At the origin: the reference; 0.1 m of noise is 1e-6 degrees.
        self.assertAlmostEqual(mean([x.latitude for x in msgs]), 47.3769, delta=1e-6)
        self.assertAlmostEqual(mean([x.longitude for x in msgs]), 8.5417, delta=1e-6)
        self.assertAlmostEqual(mean([x.altitude for x in msgs]), 408.0, delta=0.05)
        v = self.vel.latest().vector
        self.assertAlmostEqual(math.sqrt(v.x ** 2 + v.y ** 2 + v.z ** 2), 0.0, delta=1e-3)

    def test_magnetic(self):
        msgs = self.check_rate(self.mag, 50.0, 'base_link')
        bx = mean([m.magnetic_field.x for m in msgs])
        by = mean([m.magnetic_field.y for m in msgs])
        bz = mean([m.magnetic_field.z for m in msgs])
        self.assertAlmostEqual(math.sqrt(bx * bx + by * by + bz * bz), 0.5, delta=2e-3)
        self.assertAlmostEqual(bz, -0.5 * math.sin(math.radians(60)), delta=2e-3)
        self.assertAlmostEqual(bx, 0.25, delta=2e-3)  # north, the robot facing north (+x)

    def test_sonar(self):
        msgs = self.check_rate(self.sonar, 10.0, 'sonar_link')
        m = msgs[-1]
        self.assertEqual(m.radiation_type, Range.ULTRASOUND)
        self.assertAlmostEqual(m.min_range, 0.03, places=5)
        self.assertAlmostEqual(m.max_range, 4.0, places=5)
        self.assertAlmostEqual(m.field_of_view, 0.1, places=5)  # min(0.2, 0.1)
        self.assertAlmostEqual(mean([x.range for x in msgs]), 1.85, delta=0.01)

    def test_bad_input(self):
        expected = [
            ("hector_bad.urdf:11: hector IMU plugin 'imu_one_number'",
             "<accelGaussianNoise> '0.1' is not 3 numbers"),
            ("hector_bad.urdf:14: hector GPS plugin 'gps_at_the_pole'",
             '<referenceLatitude> 95 must be within (-90, 90) degrees'),
            ("hector_bad.urdf:17: hector magnetic plugin 'magnetometer_nowhere' of model "
             "'hector_bad'", "<bodyName> 'no_such_link' is not a link of the model"),
            ("hector_bad.urdf:25: sensor 'sonar_on_gpu_ray' of type 'gpu_ray'",
             'needs a ray sensor'),
        ]
        out = startup_output(['_model:=' + os.path.join(TEST_URDF, 'hector_bad.urdf'),
                              '_paused:=true'],
                             [e[1] for e in expected] + ['1 simulated'], 'hector_bad')
        for place, what in expected:
            lines = [l for l in out.splitlines() if place in l and what in l]
            self.assertTrue(lines, 'no message naming %s and %s in:\n%s' % (place, what, out))
        rows = [l for l in out.splitlines() if 'libhector_gazebo_ros_magnetic.so' in l]
        self.assertTrue(any('magnetometer ' in l and l.rstrip().endswith('simulated')
                            for l in rows), out)
        self.assertIn('5 plugins and sensors: 1 simulated, 0 with differences, 4 left out', out)

    def test_z_reconfigure(self):
        """Last: it changes the sensors."""
        client = dynamic_reconfigure.client.Client('/hector_bot/magnetic', timeout=30)
        config = client.get_configuration(timeout=30)
        self.assertAlmostEqual(config['gaussian_noise'], 0.001)
        self.assertAlmostEqual(config['scale_error'], 1.0)
        self.assertAlmostEqual(config['drift_frequency'], 1.0 / 3600.0)
        self.assertEqual(rospy.get_param('/hector_bot/magnetic/gaussian_noise'), 0.001)
        config = client.update_configuration({'offset': 0.1, 'gaussian_noise': 0.0})
        self.assertAlmostEqual(config['offset'], 0.1)
        t = rospy.get_time()
        self.mag.first_stamped(t + 0.1)
        msgs = [m for m in self.mag.messages() if m.header.stamp.to_sec() > t + 0.05]
        m = msgs[-1].magnetic_field
        self.assertAlmostEqual(m.x, 0.25 + 0.1, delta=1e-3)  # the offset on every component
        self.assertAlmostEqual(m.y, 0.1, delta=1e-3)
        self.assertAlmostEqual(m.z, -0.5 * math.sin(math.radians(60)) + 0.1, delta=1e-3)
        # Out of the cfg's range: clamped (offset -10..10).
        self.assertAlmostEqual(client.update_configuration({'offset': 50.0})['offset'], 10.0)

        status = dynamic_reconfigure.client.Client('/gps/fix/status', timeout=30)
        # At start the values are the plugin's: STATUS_FIX, service 0.
        config = status.get_configuration(timeout=30)
        self.assertTrue(config['STATUS_FIX'])
        self.assertFalse(config['SERVICE_GPS'])
        status.update_configuration({'STATUS_FIX': False, 'SERVICE_GALILEO': True})
        t = rospy.get_time()
        fix = self.fix.first_stamped(t + 0.2)
        self.assertEqual(fix.status.status, NavSatStatus.STATUS_NO_FIX)
        self.assertEqual(fix.status.service, NavSatStatus.SERVICE_GALILEO)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'hector', HectorTest)
