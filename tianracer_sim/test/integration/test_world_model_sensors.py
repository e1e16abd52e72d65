#!/usr/bin/env python3
"""rostest: sensors on world models publish as gazebo_ros plugins do on them.

world_model_sensors.world has no robot: a static post at the origin with a lidar, a camera and
a depth camera looking at a red box whose near face is 2.5 m ahead, and a box falling from 2 m
with a downward beam, a bumper and a ground truth plugin. Each publishes on its plugin's topic under its
robotNamespace (none: "/") with its frameName (a camera's optical frame, as a robot's), and
sees the world. A model spawned through
/gazebo/spawn_sdf_model brings its lidar; delete_model takes it away, and the same model can be
spawned again.
Sim time throughout; wall time only bounds the waits.
"""
import math
import unittest

import rospy
import rostest
from tianracer_sim.sim_time import Stream, clock_stamp, connect_gazebo, wait_for
from gazebo_msgs.msg import ContactsState
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, LaserScan
from tf2_msgs.msg import TFMessage
import struct

WALL_TIMEOUT = 120.0

SPAWNED = """<sdf version='1.6'><model name='spawned'><static>true</static><link name='l'>
<sensor type='ray' name='side'><update_rate>10</update_rate><ray><scan><horizontal>
<samples>3</samples><min_angle>-0.01</min_angle><max_angle>0.01</max_angle></horizontal></scan>
<range><min>0.1</min><max>10</max></range></ray>
<plugin name='p' filename='libgazebo_ros_laser.so'><robotNamespace>spawned</robotNamespace>
<topicName>scan</topicName><frameName>spawned_laser</frameName></plugin></sensor>
</link></model></sdf>"""


class WorldModelSensorsTest(unittest.TestCase):
    def test_world_model_sensors(self):
        rospy.init_node('test_world_model_sensors')
        clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        scan = Stream('/post/scan', LaserScan, keep=1)
        image = Stream('/post_camera/image_raw', Image, keep=1)
        info = Stream('/post_camera/camera_info', CameraInfo, keep=1)
        depth = Stream('/post_depth/depth/image_raw', Image, keep=1)
        beam = Stream('/faller/beam', LaserScan, keep=1)
        truth = Stream('/faller/odom', Odometry, keep=1)
        bumper = Stream('/faller/bumper', ContactsState, keep=1)
        static_frames = {}

        def on_static(msg):
            for t in msg.transforms:
                static_frames[t.child_frame_id] = t
        rospy.Subscriber('/tf_static', TFMessage, on_static)
        clock.wait_count(1, WALL_TIMEOUT)

        # The post's lidar: the box's near face 2.5 m straight ahead.
        msg = scan.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'post_laser')
        self.assertEqual(len(msg.ranges), 181)
        self.assertAlmostEqual(msg.ranges[90], 2.5, delta=0.05)

        # Its camera: the red box in the middle of the image.
        msg = image.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'post_camera_frame_optical_frame')
        self.assertEqual((msg.width, msg.height, msg.encoding), (160, 120, 'rgb8'))
        mid = (msg.height // 2) * msg.step + (msg.width // 2) * 3
        r, g, b = bytearray(msg.data[mid:mid + 3])
        self.assertGreater(r, 2 * g, 'red box in the middle: %d %d %d' % (r, g, b))
        self.assertGreater(r, 2 * b, 'red box in the middle: %d %d %d' % (r, g, b))
        msg = info.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'post_camera_frame_optical_frame')
        self.assertEqual((msg.width, msg.height), (160, 120))

        # As a robot's camera, the image is in "<frameName>_optical_frame" (z forward); a world
        # model's link is on no TF tree, so that frame hangs from the frameName.
        t = wait_for(lambda: static_frames.get('post_camera_frame_optical_frame'),
                     'the optical frame on /tf_static', WALL_TIMEOUT)
        self.assertEqual(t.header.frame_id, 'post_camera_frame')
        q = t.transform.rotation
        self.assertAlmostEqual(abs(q.w), 0.5, delta=1e-6)  # rpy(-pi/2, 0, -pi/2)
        self.assertAlmostEqual(t.transform.translation.x, 0.0, delta=1e-9)

        # Its depth camera: 2.5 m in the middle.
        msg = depth.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'post_depth_frame_optical_frame')
        self.assertEqual(msg.encoding, '32FC1')
        mid = (msg.height // 2) * msg.step + (msg.width // 2) * 4
        (d,) = struct.unpack_from('<f', bytes(msg.data), mid)
        self.assertAlmostEqual(d, 2.5, delta=0.05)

        # The falling box's beam, under its robotNamespace, ends with the box at rest.
        msg = beam.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'faller_beam')
        wait_for(lambda: clock.latest().clock.to_sec() > 2.5, '2.5 s of sim time', WALL_TIMEOUT)
        t = clock.latest().clock.to_sec()
        msg = wait_for(lambda: beam.latest() if beam.latest().header.stamp.to_sec() >= t else None,
                       'a beam after the fall', WALL_TIMEOUT)
        self.assertAlmostEqual(msg.ranges[0], 0.1, delta=0.02)
        # Its ground truth plugin (libgazebo_ros_p3d on the world model) agrees.
        msg = truth.wait_count(1, WALL_TIMEOUT)
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('world', 'body'))
        self.assertAlmostEqual(msg.pose.pose.position.z, 0.1, delta=0.02)
        # Its bumper: the ground holds the 1 kg box up with m g.
        msg = wait_for(lambda: bumper.latest() if bumper.latest() is not None and
                       bumper.latest().header.stamp.to_sec() >= t else None,
                       'a bumper message after the fall', WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'world')
        self.assertEqual([s.collision2_name for s in msg.states], ['ground_plane'], msg)
        self.assertAlmostEqual(msg.states[0].total_wrench.force.z, 9.8, delta=0.3)

        # A spawned model's lidar: 1 m from the box's side; gone with the model, back with it.
        connect_gazebo(self, {'spawn_sdf_model': SpawnModel, 'delete_model': DeleteModel},
                       WALL_TIMEOUT)
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = 3.0, -1.5, 0.5
        pose.orientation.z, pose.orientation.w = math.sin(math.pi / 4), math.cos(math.pi / 4)
        for attempt in range(2):
            spawned = Stream('/spawned/scan', LaserScan, keep=1)
            res = self.spawn_sdf_model(model_name='spawned', model_xml=SPAWNED,
                                       robot_namespace='', initial_pose=pose,
                                       reference_frame='world')
            self.assertTrue(res.success, res.status_message)
            msg = wait_for(lambda: spawned.latest(),
                           '/spawned/scan (spawn %d)' % attempt, WALL_TIMEOUT)
            self.assertEqual(msg.header.frame_id, 'spawned_laser')
            self.assertAlmostEqual(msg.ranges[1], 1.0, delta=0.05)
            spawned.unregister()
            res = self.delete_model(model_name='spawned')
            self.assertTrue(res.success, res.status_message)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'world_model_sensors', WorldModelSensorsTest)
