#!/usr/bin/env python3
"""rostest: the simulator runs a world with no robot, and a robot arrives by spawn.

- before any spawn: /clock advances, /gazebo/model_states lists the world's models and no robot,
  get_world_properties agrees, nothing is published on the car's topics;
- spawn_urdf_model adds the tianracer; the spawner waiting in its namespace starts its
  controllers: its /tianracer/joint_states appear, and wheel velocity commands on its
  controllers' topics turn its wheels and drive it forward (ground truth x).
Sim time throughout; wall time only bounds the waits.
"""
import unittest

import rospy
import rostest
from tianracer_sim.sim_time import Stream, clock_stamp, wait_for
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import GetWorldProperties, SpawnModel
from geometry_msgs.msg import Pose
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WALL_TIMEOUT = 120.0
WHEEL_RADIUS = 0.032


class WorldAloneTest(unittest.TestCase):
    def test_world_alone_then_spawn(self):
        rospy.init_node('test_world_alone')
        clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        states = Stream('/gazebo/model_states', ModelStates, stamp=lambda m: 0.0, keep=1)
        joints = Stream('/tianracer/joint_states', JointState, keep=1)
        truth = Stream('/tianracer/ground_truth/odom', Odometry, keep=1)

        # The world runs alone: sim time passes, the world's models are there, no robot.
        first = wait_for(lambda: clock.latest(), '/clock', WALL_TIMEOUT)
        wait_for(lambda: clock.latest().clock.to_sec() > first.clock.to_sec() + 0.5,
                 '/clock to advance 0.5 s', WALL_TIMEOUT)
        msg = wait_for(lambda: states.latest(), '/gazebo/model_states', WALL_TIMEOUT)
        self.assertIn('ground_plane', msg.name)
        self.assertGreater(len(msg.name), 1, 'walled_room has walls: %s' % msg.name)
        self.assertNotIn('tianracer', msg.name)
        rospy.wait_for_service('/gazebo/get_world_properties', timeout=WALL_TIMEOUT)
        props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)()
        self.assertEqual(sorted(props.model_names), sorted(msg.name))
        self.assertEqual(joints.count(), 0, 'joint_states before any robot')

        # The car arrives by spawn and drives.
        rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=WALL_TIMEOUT)
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        pose = Pose()
        pose.position.z = 0.015
        pose.orientation.w = 1.0
        res = spawn(model_name='tianracer', model_xml=rospy.get_param('/car_description'),
                    robot_namespace='/tianracer', initial_pose=pose, reference_frame='world')
        self.assertTrue(res.success, res.status_message)
        js = wait_for(lambda: joints.latest(),
                      '/tianracer/joint_states after the spawn', WALL_TIMEOUT)
        self.assertIn('left_rear_wheel_joint', js.name)
        wait_for(lambda: truth.latest(), 'ground truth', WALL_TIMEOUT)
        wheels = [rospy.Publisher('/tianracer/%s_rear_wheel_velocity_controller/command' % side,
                                  Float64, queue_size=1, latch=True) for side in ('left', 'right')]
        for pub in wheels:
            pub.publish(Float64(0.5 / WHEEL_RADIUS))

        def wheel_speed():
            js = joints.latest()
            return js.velocity[js.name.index('left_rear_wheel_joint')]
        # Once the commands are in (connections take wall time), 1 s of sim time at 0.5 m/s.
        wait_for(lambda: wheel_speed() > 0.8 * 0.5 / WHEEL_RADIUS,
                 'the wheels to turn', WALL_TIMEOUT)
        start = truth.latest().pose.pose.position.x
        t0 = clock.latest().clock.to_sec()
        wait_for(lambda: clock.latest().clock.to_sec() > t0 + 1.0,
                 '1 s of sim time driving', WALL_TIMEOUT)
        x = truth.latest().pose.pose.position.x
        self.assertGreater(x - start, 0.3, 'the spawned car drives: x %.3f -> %.3f' % (start, x))
        msg = states.latest()
        self.assertIn('tianracer', msg.name)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'world_alone', WorldAloneTest)
