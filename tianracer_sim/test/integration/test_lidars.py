#!/usr/bin/env python3
"""rostest: a gpu_ray lidar publishes a LaserScan as a ray one does; a 16-ring ray sensor with
libgazebo_ros_velodyne_laser publishes velodyne_gazebo_plugins' PointCloud2 (x y z intensity
ring, 32 bytes a point) at its rate, every point inside the plugin's range limits."""
import math
import struct
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import LaserScan, PointCloud2, PointField


class Lidars(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lidars')
        cls.lock = threading.Lock()
        cls.scans, cls.clouds = [], []
        rospy.Subscriber('/gpu_scan', LaserScan, lambda m: cls._add(cls.scans, m), queue_size=50)
        rospy.Subscriber('/velodyne_points', PointCloud2, lambda m: cls._add(cls.clouds, m),
                         queue_size=50)

    @classmethod
    def _add(cls, store, msg):
        with cls.lock:
            store.append(msg)

    def collect(self, store, count, wall_timeout=60.0):
        end = time.time() + wall_timeout
        while time.time() < end:
            with self.lock:
                if len(store) >= count:
                    return list(store)
            time.sleep(0.05)
        self.fail('fewer than %d messages' % count)

    def test_gpu_ray_scan(self):
        scans = self.collect(self.scans, 5)
        s = scans[-1]
        self.assertEqual(s.header.frame_id, 'lidar')
        self.assertEqual(len(s.ranges), 360)
        self.assertAlmostEqual(s.angle_min, -3.14159, places=5)
        self.assertAlmostEqual(s.range_max, 8.0)
        self.assertGreater(sum(1 for r in s.ranges if math.isfinite(r)), 300)  # a closed room
        dt = (scans[-1].header.stamp - scans[-5].header.stamp).to_sec() / 4
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
        dt = (clouds[-1].header.stamp - clouds[-3].header.stamp).to_sec() / 2
        self.assertAlmostEqual(dt, 0.1, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lidars', Lidars)
