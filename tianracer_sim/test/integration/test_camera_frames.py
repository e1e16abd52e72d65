#!/usr/bin/env python3
"""rostest (camera_frames.test): which frame a spawned robot's camera images are stamped in.

camera_frames.urdf has cameras on camera_frame naming, in <frameName>, the URDF's optical link
(camera_optical_frame, turned rpy -1.57 0 -1.57 as robots' URDFs write it), the plain link and
a link turned another way. The first publishes in camera_optical_frame, as Gazebo would, and
the simulator adds no frame for it (robot_state_publisher has it from the URDF); the other two
publish in "<frameName>_optical_frame", which the simulator puts on /tf_static.
Sim time throughout; wall time only bounds the waits.
"""
import unittest

import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image
from tf2_msgs.msg import TFMessage
from tianracer_sim.sim_time import Stream, wait_for

SPAWN_TIMEOUT = 120.0  # s of wall time for the spawned robot's first frames, under load


class CameraFramesTest(unittest.TestCase):
    def test_frames(self):
        rospy.init_node('test_camera_frames')
        static = {}

        def on_static(msg):
            for t in msg.transforms:
                static[t.child_frame_id] = t
        rospy.Subscriber('/tf_static', TFMessage, on_static)
        # openni_kinect's image is ir/image_raw by default.
        expected = {'/optical/image_raw': 'camera_optical_frame',
                    '/plain/image_raw': 'camera_frame_optical_frame',
                    '/turned/image_raw': 'camera_turned_optical_frame',
                    '/depth/ir/image_raw': 'camera_optical_frame',
                    '/depth/depth/image_raw': 'camera_optical_frame'}
        images = {topic: Stream(topic, Image, keep=1) for topic in expected}
        info = Stream('/optical/camera_info', CameraInfo, keep=1)
        for topic, frame in expected.items():
            msg = wait_for(lambda: images[topic].latest(), topic, SPAWN_TIMEOUT)
            self.assertEqual(msg.header.frame_id, frame, topic)
        self.assertEqual(wait_for(lambda: info.latest(), '/optical/camera_info').header.frame_id,
                         'camera_optical_frame')
        # The frames the simulator adds hang from the camera's link, z forward.
        for frame in ('camera_frame_optical_frame', 'camera_turned_optical_frame'):
            t = wait_for(lambda: static.get(frame), frame + ' on /tf_static')
            self.assertEqual(t.header.frame_id, 'camera_frame')
            self.assertAlmostEqual(abs(t.transform.rotation.w), 0.5, delta=1e-6)
        # None for the URDF's own optical link.
        self.assertNotIn('camera_optical_frame', static)
        self.assertNotIn('camera_optical_frame_optical_frame', static)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'camera_frames', CameraFramesTest)
