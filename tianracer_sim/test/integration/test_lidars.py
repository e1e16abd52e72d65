#!/usr/bin/env python3
"""rostest: a gpu_ray lidar publishes a LaserScan as a ray one does; a 16-ring ray sensor with
libgazebo_ros_velodyne_laser publishes velodyne_gazebo_plugins' PointCloud2 (x y z intensity
ring, 32 bytes a point) at its rate, every point inside the plugin's range limits."""
import math
import struct
import unittest

import rospy
import rostest
from sensor_msgs.msg import LaserScan, PointCloud2, PointField
from tianracer_sim.sim_time import Stream, published_rate


class Lidars(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lidars')
        cls.scans = Stream('/gpu_scan', LaserScan)
        cls.clouds = Stream('/velodyne_points', PointCloud2, buff_size=1 << 24)

    @staticmethod
    def collect(stream, count):
        stream.wait_count(count)
        return stream.messages()

    def test_gpu_ray_scan(self):
        scans = self.collect(self.scans, 5)
        s = scans[-1]
        self.assertEqual(s.header.frame_id, 'lidar')
        self.assertEqual(len(s.ranges), 360)
        self.assertAlmostEqual(s.angle_min, -3.14159, places=5)
        self.assertAlmostEqual(s.range_max, 8.0)
        self.assertGreater(sum(1 for r in s.ranges if math.isfinite(r)), 300)  # a closed room
        dt = 1.0 / published_rate(scans[-5:])  # header.seq counts what the sim published
        self.assertAlmostEqual(dt, 1 / 20.0, delta=0.002)

    def test_velodyne_cloud(self):
        clouds = self.collect(self.clouds, 3)
        c = clouds[-1]
        self.assertEqual(c.header.frame_id, 'lidar')
        self.assertEqual([(f.name, f.offset, f.datatype) for f in c.fields],
                         [('x', 0, PointField.FLOAT32), ('y', 4, PointField.FLOAT32),
                          ('z', 8, PointField.FLOAT32), ('intensity', 16, PointField.FLOAT32),
                          ('ring', 20, PointField.UINT16)])
        self.assertEqual(c.point_step, 32)
        self.assertEqual(c.height, 1)
        self.assertEqual(len(c.data), c.width * 32)
        self.assertTrue(c.is_dense)
        self.assertGreater(c.width, 0.9 * 16 * 1800)  # the room's walls and floor
        rings = set()
        for k in range(0, c.width, 7):
            x, y, z = struct.unpack_from('<fff', c.data, k * 32)
            ring, = struct.unpack_from('<H', c.data, k * 32 + 20)
            r = math.sqrt(x * x + y * y + z * z)
            self.assertTrue(0.9 < r < 130.0, r)
            self.assertLess(abs(math.asin(z / r) - (-0.2617993878 + ring * 0.5235987756 / 15)), 0.02)
            rings.add(ring)
        self.assertEqual(rings, set(range(16)))
        dt = 1.0 / published_rate(clouds[-3:])
        self.assertAlmostEqual(dt, 0.1, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lidars', Lidars)
