#!/usr/bin/env python3
"""rostest: a Gazebo user's launch file runs unchanged (test/launch/tianracer_gazebo.launch).

- gzserver from gazebo_ros's empty_world.launch is tianracer_sim's node as /gazebo on the world
  given (its models listed by get_world_properties), and spawn_model put the car in it;
- the spawner in /tianracer loaded and started the YAML's controllers: list_controllers shows them
  running with their types; robot_state_publisher turns their joint states into TF;
- the car drives from its velocity controllers;
- switch_controller stops one, and its joint no longer follows its commands;
- bad input on that path (a spawner given an unknown name and a type the simulator does not run,
  a switch of a controller that is not loaded) gets controller_manager's errors, and the sim goes
  on with the good controllers running;
- shutting the spawner down unloads them.

Everything is timed in sim time; wall time only bounds the waits.
"""
import math
import sys

import rosnode
import rospy
import rostest
import tf2_ros
from gazebo_msgs.srv import GetWorldProperties
from rosgraph_msgs.msg import Log

from controller_test_support import (CONTROLLERS, LEFT, NS, RIGHT, STRICT, ControllerTestCase,
                                     run_spawner, sim_sleep, wall_wait)

STEERING = {CONTROLLERS[3]: 0.0, CONTROLLERS[4]: 0.0}


class GazeboUserTest(ControllerTestCase):
    @classmethod
    def setUpClass(cls):
        cls.start('test_gazebo_user')
        cls.tf = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf)

    def test_a_gzserver_runs_the_world_and_spawn_model_the_car(self):
        self.assertIn('/gazebo', rosnode.get_node_names())
        rospy.wait_for_service('/gazebo/get_world_properties', timeout=60.0)
        models = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)().model_names
        for name in ('ground_plane', 'walls', 'box_front', 'tianracer'):
            self.assertIn(name, models)
        t0 = rospy.get_time()
        sim_sleep(0.2)
        self.assertGreater(rospy.get_time(), t0)

    def test_b_the_spawner_started_the_controllers(self):
        self.assertTrue(wall_wait(lambda: self.states() == {n: 'running' for n in CONTROLLERS},
                                  120.0), self.states())
        types = {c.name: c.type for c in self.list().controller}
        self.assertEqual(types[LEFT], 'velocity_controllers/JointVelocityController')
        self.assertEqual(types['joint_state_controller'],
                         'joint_state_controller/JointStateController')
        self.assertTrue(wall_wait(lambda: all(p.get_num_connections() > 0
                                              for p in self.pubs.values()), 60.0))

    def test_c_robot_state_publisher_gives_tf(self):
        self.assertTrue(wall_wait(lambda: self.tf.can_transform(
            'base_link', 'left_rear_wheel', rospy.Time(0)), 60.0),
            'no TF base_link -> left_rear_wheel from robot_state_publisher')
        self.assertTrue(self.tf.can_transform('base_link', 'left_steering_hinge', rospy.Time(0)))

    def test_d_the_car_drives_from_its_velocity_controllers(self):
        self.assertTrue(wall_wait(lambda: self.truth.msg is not None, 60.0))
        self.command(dict(STEERING, **{LEFT: 0.0, RIGHT: 0.0}), 0.5)
        p0 = self.truth.msg.pose.pose.position
        self.command(dict(STEERING, **{LEFT: 15.0, RIGHT: 15.0}), 2.0)
        p1 = self.truth.msg.pose.pose.position
        moved = math.hypot(p1.x - p0.x, p1.y - p0.y)
        rospy.loginfo('drove %.3f m in 2 s at 15 rad/s', moved)
        self.assertGreater(moved, 0.6)  # 0.96 m at 15 rad/s * 0.032 m, less the start
        self.assertGreater(p1.x - p0.x, 0.6)  # forward, straight
        self.assertAlmostEqual(self.wheel_velocity('left_rear_wheel_joint'), 15.0, delta=1.0)

    def test_e_a_stopped_controller_lets_its_joint_go(self):
        self.assertTrue(self.switch([], [LEFT], STRICT, False, 0.0).ok)
        self.assertEqual(self.states()[LEFT], 'stopped')
        self.assertEqual(self.states()[RIGHT], 'running')
        self.assert_stopped_left_wheel_goes_then_follows_again()

    def test_f_bad_input_gets_controller_managers_errors_and_the_sim_goes_on(self):
        # The bad spawner starts once this test hears the sim node's log (run_spawner).
        self.assertTrue(wall_wait(lambda: self.hears('/gazebo'), 60.0),
                        'not connected to /gazebo on /rosout')
        manager_errors = [
            "Could not load controller 'no_such_controller' because the type was not specified. "
            "Did you load the controller configuration on the parameter server (namespace: "
            "'%s/no_such_controller')?" % NS,
            "Could not load controller 'no_such_type_controller' because controller type "
            "'no_such_controllers/NoSuchController' does not exist.",
        ]
        spawner_errors = ['Failed to load no_such_controller',
                          'Failed to load no_such_type_controller']
        with run_spawner(['no_such_controller', 'no_such_type_controller'], NS,
                         'bad_spawner') as out:
            for text in manager_errors:
                self.assertTrue(wall_wait(lambda: text in [t for _, t in self.said(Log.ERROR)],
                                          60.0), '%r not in %r' % (text, self.said(Log.ERROR)))
            for text in spawner_errors:
                self.assertTrue(wall_wait(lambda: text in out.text(), 60.0),
                                '%r not in the spawner\'s output %r' % (text, out.text()))
        self.assertFalse(self.switch(['not_loaded'], [], STRICT, False, 0.0).ok)
        text = ("Could not start controller with name 'not_loaded' because no controller with "
                "this name exists")
        self.assertTrue(wall_wait(lambda: text in [t for _, t in self.said(Log.ERROR)], 10.0))
        # The good ones still run, and sim time goes on.
        self.assertEqual(self.states(), {n: 'running' for n in CONTROLLERS})
        t0 = rospy.get_time()
        sim_sleep(0.5)
        self.assertGreater(rospy.get_time(), t0)

    def test_g_shutting_the_spawner_down_unloads_them(self):
        spawners = [n for n in rosnode.get_node_names() if n == NS + '/controller_spawner']
        self.assertEqual(len(spawners), 1, rosnode.get_node_names())
        rosnode.kill_nodes(spawners)
        self.assertTrue(wall_wait(lambda: self.states() == {}, 60.0), self.states())
        # No joint_state_controller: no joint states any more; the sim runs on.
        t0 = rospy.get_time()
        sim_sleep(0.5)
        self.assertGreater(rospy.get_time(), t0)


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'gazebo_user', GazeboUserTest, sys.argv)
