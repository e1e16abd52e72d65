#!/usr/bin/env python3
"""rostest: the lane_track world's floor texture reaches the camera topic.

The car spawns on the start line of lane_track, looking along +x; the road's white edge lines
run at y = +-0.525 m there (tianracer_sim/scripts/make_lane_track.py). Each line point at a few
distances ahead is projected into /rrbot/camera1/image_raw with the published camera_info, the
car's ground truth (world -> base_link; sim.launch runs no wheel odometry) and the camera's optical
frame from TF (base_link -> camera_optical_frame); the image must be bright there and dark asphalt 30 px towards
the road's middle (luminance Rec. 601, the same contrast the renderer's gtest asks for).
"""
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image
from tianracer_sim.sim_time import Stream

IMAGE = '/rrbot/camera1/image_raw'
INFO = '/rrbot/camera1/camera_info'
GROUND_TRUTH = '/tianracer/ground_truth/odom'
LINE_Y = 0.525  # m, edge lines either side of the centreline at the start
FLOOR_Z = 0.002  # m, the textured floor's height


def quaternion_matrix(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


class LaneTrackCamera(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lane_track_camera')
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)

    def test_edge_lines_where_camera_info_projects_them(self):
        info = rospy.wait_for_message(INFO, CameraInfo, timeout=60)
        truth = Stream(GROUND_TRUTH, Odometry)
        # A frame after the car has settled on its wheels.
        images = Stream(IMAGE, Image, buff_size=1 << 24)
        msg = images.first_stamped(0.5 + 1e-6)
        images.unregister()
        self.assertEqual(msg.encoding, 'rgb8')
        img = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width * 3]
        img = img.reshape(msg.height, msg.width, 3).astype(float)
        lum = 0.299 * img[:, :, 0] + 0.587 * img[:, :, 1] + 0.114 * img[:, :, 2]
        # The car stands still: the ground truth after the frame is its pose at the frame.
        odom = truth.first_stamped(msg.header.stamp.to_sec())
        R_WB = quaternion_matrix(odom.pose.pose.orientation)
        p = odom.pose.pose.position
        t_WB = np.array([p.x, p.y, p.z])
        tf = self.tf_buffer.lookup_transform(msg.header.frame_id, odom.child_frame_id, rospy.Time(0),
                                             rospy.Duration(10.0))
        R_CB = quaternion_matrix(tf.transform.rotation)
        t_CB = np.array([tf.transform.translation.x, tf.transform.translation.y,
                         tf.transform.translation.z])
        # X_CW = X_CB X_BW
        R = R_CB.dot(R_WB.T)
        t = t_CB - R.dot(t_WB)
        fx, cx, fy, cy = info.K[0], info.K[2], info.K[4], info.K[5]
        checked = 0
        for ahead in (0.8, 1.0, 1.3):
            for side in (+1, -1):
                p_C = R.dot([ahead, side * LINE_Y, FLOOR_Z]) + t
                self.assertGreater(p_C[2], 0.0)
                u, v = fx * p_C[0] / p_C[2] + cx, fy * p_C[1] / p_C[2] + cy
                ui, vi = int(round(u)), int(round(v))
                if not (40 <= ui < msg.width - 40 and 0 <= vi < msg.height):
                    continue
                line = lum[vi, ui - 2:ui + 3].max()
                asphalt = lum[vi, ui + side * 30]  # +y is image left: the middle is to its right
                where = 'line y %+.3f at %.1f m ahead, pixel (%d, %d)' % (side * LINE_Y, ahead, ui, vi)
                self.assertGreater(line, 170, where)
                self.assertLess(asphalt, 90, where)
                self.assertGreater(line - asphalt, 100, where)
                checked += 1
        self.assertGreaterEqual(checked, 4, 'too few line points inside the image')


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lane_track_camera', LaneTrackCamera)
