#!/usr/bin/env python3
"""rostest: a robot spawned through gazebo_ros's entry points, its controllers started by
controller_manager's spawner and managed through <ns>/controller_manager/*, as in Gazebo.

- before the spawner runs, the robot runs no controller (nothing listens to its command topics);
- the spawner loads and starts them: list_controllers shows them running, the car drives from its
  velocity controllers;
- switch_controller stops one: its joint no longer follows its commands;
- bad input: each gets controller_manager's error text, ok = false, and the sim goes on;
- the controller_manager command line lists them;
- shutting the spawner down unloads them;
- a spawner for a robot that does not exist gives up after its timeout and exits;
- a spawner interrupted (SIGINT, as roslaunch ending) while it logs exits at once, wherever the
  signal lands (it once hung for a minute when the signal came during a log line's call to the
  master).

Everything is timed in sim time; wall time only bounds the waits.
"""
import math
import os
import random
import signal
import subprocess
import sys

import rosnode
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from std_msgs.msg import Bool

from controller_test_support import (BEST_EFFORT, CONTROLLERS, LEFT, NS, RIGHT, STRICT,
                                     ControllerTestCase, run_spawner, sim_sleep, wall_wait)


class ControllerManagerTest(ControllerTestCase):
    @classmethod
    def setUpClass(cls):
        cls.start('test_controller_manager')

    def test_a_no_controller_before_the_spawner(self):
        self.assertEqual(self.states(), {})
        topic = '%s/%s/command' % (NS, LEFT)
        subscribers = [nodes for t, nodes in rospy.get_master().getSystemState()[2][1]
                       if t == topic]
        self.assertEqual(subscribers, [])
        # Our own launch files start every controller of their YAML.
        if rospy.has_param('~own_robot_namespace'):
            own = rospy.get_param('~own_robot_namespace')
            rospy.wait_for_service(own + '/controller_manager/list_controllers', 60.0)
            listed = rospy.ServiceProxy(own + '/controller_manager/list_controllers',
                                        ListControllers)().controller
            self.assertEqual(sorted(c.name for c in listed), sorted(CONTROLLERS))
            self.assertEqual({c.state for c in listed}, {'running'})

    def test_b_the_spawner_starts_them(self):
        rospy.Publisher('/start_spawner', Bool, queue_size=1, latch=True).publish(Bool(True))
        self.assertTrue(wall_wait(lambda: self.states() == {n: 'running' for n in CONTROLLERS},
                                  120.0), self.states())
        by_name = {c.name: c for c in self.list().controller}
        self.assertEqual(by_name[LEFT].type, 'velocity_controllers/JointVelocityController')
        self.assertEqual([(r.hardware_interface, r.resources)
                          for r in by_name[LEFT].claimed_resources],
                         [('hardware_interface::VelocityJointInterface', ['left_rear_wheel_joint'])])
        self.assertTrue(wall_wait(lambda: all(self.pubs[n].get_num_connections() > 0
                                              for n in self.pubs), 30.0))

    def test_c_the_car_drives_from_its_velocity_controllers(self):
        self.assertTrue(wall_wait(lambda: self.truth.msg is not None, 60.0))
        p0 = self.truth.msg.pose.pose.position
        straight = {CONTROLLERS[3]: 0.0, CONTROLLERS[4]: 0.0}
        self.command(dict(straight, **{LEFT: 15.0, RIGHT: 15.0}), 2.0)
        p1 = self.truth.msg.pose.pose.position
        moved = math.hypot(p1.x - p0.x, p1.y - p0.y)
        rospy.loginfo('drove %.3f m in 2 s at 15 rad/s', moved)
        self.assertGreater(moved, 0.6)  # 0.96 m at 15 rad/s * 0.032 m, less the start
        self.assertAlmostEqual(self.wheel_velocity('left_rear_wheel_joint'), 15.0, delta=1.0)

    def test_d_a_stopped_controller_lets_its_joint_go(self):
        res = self.switch([], [LEFT], STRICT, False, 0.0)
        self.assertTrue(res.ok)
        self.assertEqual(self.states()[LEFT], 'stopped')
        self.assert_stopped_left_wheel_goes_then_follows_again()

    def test_e_bad_input_gets_controller_managers_errors(self):
        rospy.set_param(NS + '/no_such_type', {'type': 'no_such_controllers/NoSuchController'})
        cases = [
            (lambda: self.load('no_such_controller'),
             "Could not load controller 'no_such_controller' because the type was not specified. "
             "Did you load the controller configuration on the parameter server (namespace: "
             "'%s/no_such_controller')?" % NS),
            (lambda: self.load('no_such_type'),
             "Could not load controller 'no_such_type' because controller type "
             "'no_such_controllers/NoSuchController' does not exist."),
            (lambda: self.load(LEFT),
             "A controller named '%s' was already loaded inside the controller manager" % LEFT),
            (lambda: self.switch(['not_loaded'], [], STRICT, False, 0.0),
             "Could not start controller with name 'not_loaded' because no controller with this "
             "name exists"),
            (lambda: self.unload(RIGHT),
             "Could not unload controller with name '%s' because it is still running" % RIGHT),
        ]
        for call, text in cases:
            n = self.log_count()
            self.assertFalse(call().ok, text)
            self.assertTrue(wall_wait(lambda: text in self.errors_since(n), 10.0),
                            '%r not in %r' % (text, self.errors_since(n)))
        # BEST_EFFORT skips what it cannot do.
        self.assertTrue(self.switch(['not_loaded'], [], BEST_EFFORT, False, 0.0).ok)
        # Nothing changed, and the simulation goes on.
        self.assertEqual(self.states(), {n: 'running' for n in CONTROLLERS})
        t0 = rospy.get_time()
        sim_sleep(0.5)
        self.assertGreater(rospy.get_time(), t0)

    def test_f_controller_manager_command_line(self):
        env = dict(os.environ, ROS_NAMESPACE=NS)
        out = subprocess.run(['rosrun', 'controller_manager', 'controller_manager', 'list'],
                             env=env, stdout=subprocess.PIPE, universal_newlines=True,
                             timeout=60).stdout
        self.assertIn("'%s' - 'hardware_interface::VelocityJointInterface' ( running )" % LEFT,
                      out)
        self.assertIn("'joint_state_controller' - 'hardware_interface::JointStateInterface' "
                      "( running )", out)
        types = subprocess.run(['rosrun', 'controller_manager', 'controller_manager',
                                'list-types'], env=env, stdout=subprocess.PIPE,
                               universal_newlines=True, timeout=60).stdout
        self.assertIn('effort_controllers/JointPositionController', types.split())

    def test_g_shutting_the_spawner_down_unloads_them(self):
        spawners = [n for n in rosnode.get_node_names() if n.startswith(NS + '/controller_spawner')]
        self.assertEqual(len(spawners), 1, rosnode.get_node_names())
        rosnode.kill_nodes(spawners)
        self.assertTrue(wall_wait(lambda: self.states() == {}, 60.0), self.states())

    def test_h_a_spawner_for_a_robot_that_does_not_exist_gives_up(self):
        # Started here, not by the launch file, so that its last words cannot go out before
        # this test listens: they are read from its output.
        with run_spawner(['--timeout', '3', 'joint_state_controller'], '/ghost',
                         'controller_spawner') as out:
            text = ("Controller Spawner couldn't find the expected controller_manager ROS "
                    "interface.")
            self.assertTrue(wall_wait(lambda: text in out.text(), 120.0), out.text())
            self.assertTrue(wall_wait(lambda: not any(n.startswith('/ghost/')
                                                      for n in rosnode.get_node_names()), 120.0),
                            rosnode.get_node_names())
        t0 = rospy.get_time()
        sim_sleep(0.5)
        self.assertGreater(rospy.get_time(), t0)

    def test_i_an_interrupted_spawner_exits_at_once(self):
        # The signal lands 0-12 ms after the spawner's error line, while it logs its next lines
        # (each reads /rosout_disable_topics_generation from the master). Ten places, the same
        # every run.
        place = random.Random(0)
        env = dict(os.environ, ROS_NAMESPACE=NS, PYTHONUNBUFFERED='1')
        for k in range(10):
            spawner = subprocess.Popen(['rosrun', 'controller_manager', 'spawner',
                                        'no_such_controller', '__name:=interrupted_spawner'],
                                       env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                       universal_newlines=True)
            said = []
            for line in spawner.stdout:
                said.append(line)
                if 'Failed to load no_such_controller' in line:
                    break
            delay = place.uniform(0.0, 0.012)
            rospy.rostime.wallsleep(delay)
            spawner.send_signal(signal.SIGINT)
            try:
                spawner.wait(10.0)
            except subprocess.TimeoutExpired:
                spawner.kill()
                self.fail('spawner %d, interrupted %.1f ms after its error, still runs 10 s later:'
                          ' %s' % (k, 1e3 * delay, ''.join(said)))
            spawner.stdout.close()


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'controller_manager', ControllerManagerTest, sys.argv)
