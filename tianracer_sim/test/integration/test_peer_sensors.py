#!/usr/bin/env python3
"""rostest: the gazebo_plugins sensors of gazebo_ros_pkgs' own tests, wired.

peer_sensors.world (no robot) has, on world models: a libgazebo_ros_range infrared grid 0.225 m
from a 5 cm box; a libgazebo_ros_block_laser looking down from 0.8 m onto a floor; a
libgazebo_ros_triggered_camera; an R16G16B16 camera; a Bayer camera with barrel distortion and
autoDistortion. A URDF robot spawned through /gazebo/spawn_urdf_model carries a range sensor
looking down at its own box. Sim time throughout; wall time only bounds the waits.
"""
import math
import unittest

import rospy
import rostest
from tianracer_sim.sim_time import Stream, clock_stamp, connect_gazebo, wait_for
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, PointCloud, Range
from std_msgs.msg import Empty

WALL_TIMEOUT = 120.0

SONARBOT = """<robot name='sonarbot'>
  <link name='base'>
    <inertial><mass value='1'/>
      <inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial>
    <collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision>
  </link>
  <gazebo reference='base'>
    <sensor type='ray' name='bot_sonar'>
      <pose>0 0 0.3 0 1.5707963 0</pose>
      <update_rate>10</update_rate>
      <ray>
        <scan><horizontal><samples>3</samples><min_angle>-0.05</min_angle>
          <max_angle>0.05</max_angle></horizontal></scan>
        <range><min>0.06</min><max>2.0</max></range>
      </ray>
      <plugin name='r' filename='libgazebo_ros_range.so'>
        <topicName>bot_sonar</topicName><frameName>bot_sonar_link</frameName>
      </plugin>
    </sensor>
  </gazebo>
</robot>"""


class PeerSensorsTest(unittest.TestCase):
    def test_peer_sensors(self):
        rospy.init_node('test_peer_sensors')
        clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        sonar = Stream('/sonar', Range, keep=1)
        block = Stream('/test_block_laser', PointCloud, keep=1)
        cam16 = Stream('/cam16/image_raw', Image, keep=1)
        barrel = Stream('/barrel/image_raw', Image, keep=1)
        barrel_info = Stream('/barrel/camera_info', CameraInfo, keep=1)
        trig = Stream('/trig/image_raw', Image, keep=10)
        clock.wait_count(1, WALL_TIMEOUT)

        # Range: the nearest of the 25 rays, 0.475 - 0.25 m; fov the grid's span (no <fov>).
        msg = sonar.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'sonar_link')
        self.assertEqual(msg.radiation_type, Range.INFRARED)
        self.assertAlmostEqual(msg.range, 0.225, delta=1e-3)
        self.assertAlmostEqual(msg.min_range, 0.01, places=5)
        self.assertAlmostEqual(msg.max_range, 0.75, places=5)
        self.assertAlmostEqual(msg.field_of_view, 0.5, places=5)

        # Block laser: 8 x 10 points of the floor 0.8 m below, none clipped.
        msg = block.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.header.frame_id, 'test_block_laser_frame')
        self.assertEqual(len(msg.points), 80)
        self.assertEqual(len(msg.channels), 1)
        self.assertEqual(len(msg.channels[0].values), 80)
        for p in msg.points:
            r = math.sqrt(p.x ** 2 + p.y ** 2 + p.z ** 2)
            self.assertTrue(0.4 <= r <= 1.0, r)
        # The last point carries its own ray (the others sit half a step past theirs, as
        # upstream places them): the floor 0.8 m along the sensor's x, which points down.
        self.assertAlmostEqual(msg.points[-1].x, 0.8, delta=1e-3)

        # 16-bit colour and Bayer encodings with their steps.
        msg = cam16.wait_count(1, WALL_TIMEOUT)
        self.assertEqual((msg.encoding, msg.width, msg.step, len(msg.data)),
                         ('rgb16', 64, 64 * 6, 64 * 48 * 6))
        msg = barrel.wait_count(1, WALL_TIMEOUT)
        self.assertEqual((msg.encoding, msg.step), ('bayer_rggb8', 64))
        # autoDistortion: D is the <distortion> applied to the images.
        msg = barrel_info.wait_count(1, WALL_TIMEOUT)
        self.assertEqual(msg.distortion_model, 'plumb_bob')
        self.assertEqual(list(msg.D), [-0.1, -0.1, 0.0, 0.0, -0.1])
        # The barrel's black corners (borderCrop false): nothing lands there.
        img = bytearray(barrel.latest().data)
        self.assertEqual(img[0], 0)
        self.assertGreater(img[40 * 64 + 32], 0)  # the floor, red channel

        # Triggered camera: nothing without a trigger, one image per trigger.
        def one_sim_second():
            start = clock.latest().clock.to_sec()
            wait_for(lambda: clock.latest().clock.to_sec() > start + 1.0, '1 s of sim time',
                     WALL_TIMEOUT)

        one_sim_second()
        self.assertEqual(trig.count(), 0)
        trigger = rospy.Publisher('/trig/image_trigger', Empty, queue_size=10)
        wait_for(lambda: trigger.get_num_connections() > 0, 'the trigger subscriber', WALL_TIMEOUT)
        trigger.publish(Empty())
        wait_for(lambda: trig.count() == 1 or None, 'one triggered image', WALL_TIMEOUT)
        one_sim_second()
        self.assertEqual(trig.count(), 1)
        trigger.publish(Empty())
        trigger.publish(Empty())
        wait_for(lambda: trig.count() == 3 or None, 'two more triggered images', WALL_TIMEOUT)
        one_sim_second()
        self.assertEqual(trig.count(), 3)

        # On a robot: the same plugin, its sensor looking down at its own box from 0.2 m above.
        connect_gazebo(self, {'spawn_urdf_model': SpawnModel}, WALL_TIMEOUT)
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = 0.0, 3.0, 0.06
        pose.orientation.w = 1.0
        bot = Stream('/bot_sonar', Range, keep=1)
        res = self.spawn_urdf_model(model_name='sonarbot', model_xml=SONARBOT,
                                    robot_namespace='', initial_pose=pose,
                                    reference_frame='world')
        self.assertTrue(res.success, res.status_message)
        msg = bot.wait_count(1, WALL_TIMEOUT)
        self.assertTrue(msg.header.frame_id.endswith('bot_sonar_link'), msg.header.frame_id)
        self.assertEqual(msg.radiation_type, Range.ULTRASOUND)
        self.assertAlmostEqual(msg.field_of_view, 0.1, places=5)
        self.assertAlmostEqual(msg.range, 0.25, delta=0.01)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'peer_sensors', PeerSensorsTest)
