#!/usr/bin/env python3
"""rostest: a wideanglecamera publishes through gazebo_ros_camera as in Gazebo.

wide_angle_camera.world: TurtleBot3 autorace_2020's camera lens (custom: r = c1 f tan(theta /
c2), c1 1.05, c2 4, f scaled so that hfov/2 = 3.183/2 lands on the image's side edge) on a post,
a red ball 80 degrees to its left. The image is 320 x 240 rgb8 on /camera/image, camera_info is
gazebo_ros's pinhole K from the hfov (negative f beyond 180 degrees, as gazebo_ros computes it),
and the ball's pixels are centred where the lens maps 80 degrees.
"""
import math
import unittest

import rospy
import rostest
from tianracer_sim.sim_time import Stream, clock_stamp
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image

WALL_TIMEOUT = 120.0
W, H, HFOV, C1, C2 = 320, 240, 3.183, 1.05, 4.0


def lens_column(theta):
    """The column (0-based, centres at integers) of a point theta to the left on the centre row."""
    f = 1.0 / (C1 * math.tan(HFOV / 2 / C2))
    r = C1 * f * math.tan(theta / C2)
    return (1.0 - r) * W / 2 - 0.5


class WideAngleCameraTest(unittest.TestCase):
    def test_wide_angle_camera(self):
        rospy.init_node('test_wide_angle_camera')
        clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        image = Stream('/camera/image', Image, keep=1)
        info = Stream('/camera/camera_info', CameraInfo, keep=1)
        clock.wait_count(1, WALL_TIMEOUT)
        img = image.wait_count(1, WALL_TIMEOUT)
        self.assertEqual((img.width, img.height, img.encoding), (W, H, 'rgb8'))
        self.assertEqual(img.header.frame_id, 'camera_link_optical_frame')
        ci = info.wait_count(1, WALL_TIMEOUT)
        self.assertEqual((ci.width, ci.height), (W, H))
        self.assertAlmostEqual(ci.K[0], W / (2 * math.tan(HFOV / 2)), places=6)
        data = bytearray(img.data)
        us, vs = [], []
        for v in range(H):
            row = v * img.step
            for u in range(W):
                r, g = data[row + 3 * u], data[row + 3 * u + 1]
                if r > 2 * g + 20:
                    us.append(u)
                    vs.append(v)
        self.assertGreater(len(us), 10, 'the ball is not in the image')
        u_mean, v_mean = sum(us) / len(us), sum(vs) / len(vs)
        expected = lens_column(math.radians(80))
        rospy.loginfo('ball at (%.2f, %.2f), %d pixels; the lens says column %.2f',
                      u_mean, v_mean, len(us), expected)
        self.assertAlmostEqual(u_mean, expected, delta=2.0)
        self.assertAlmostEqual(v_mean, (H - 1) / 2.0, delta=2.0)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'wide_angle_camera', WideAngleCameraTest)
