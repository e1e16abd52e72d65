#!/usr/bin/env python3
"""rostest: the node and the Python environment set a robot up by the same rules.

- test model (a), whose controllers are keyed `mycar` in its YAML (its namespace is /car_a):
  the node (sim.launch) and tianracer_sim.simulator.Simulation read them from /mycar and load
  the same controllers, in the same order, with the same types; the node subscribes exactly the
  command topics the environment's controllers have, under the robot's namespace /car_a;
- a YAML naming a controller type that does not exist: spawning a robot whose controllers are
  read there fails with the message the environment raises.
"""
import os
import subprocess
import unittest

import rosgraph
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose

from tianracer_sim import simulator
from tianracer_sim.sim_time import connect_gazebo

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, '..', 'data')
MODEL = os.path.join(DATA, 'urdf', 'car_a', 'car_a.xacro')
REKEYED = os.path.join(DATA, 'robot_setup', 'car_a_rekeyed.yaml')
BAD = os.path.join(DATA, 'robot_setup', 'bad_type.yaml')
WAIT = 240.0


def environment(control_config, control_namespace=''):
    return simulator.Simulation(model=MODEL, robot_name='car_a', control_config=control_config,
                                control_namespace=control_namespace, world='empty',
                                disable_sensors=['ray', 'camera', 'multicamera', 'imu'],
                                observe=[])


class RobotSetupTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_robot_setup')
        rospy.wait_for_service('/car_a/controller_manager/list_controllers', timeout=WAIT)
        cls.list = rospy.ServiceProxy('/car_a/controller_manager/list_controllers', ListControllers)

    def test_same_controllers_topics_and_namespaces(self):
        env = environment(REKEYED)
        self.assertEqual(env.robot_name, 'car_a')
        self.assertEqual(env.robot_namespace, '/car_a')
        self.assertEqual(env.control_namespace, '/mycar')
        node = [(c.name, c.type) for c in self.list().controller]
        self.assertEqual(sorted(node), sorted(env.controllers))
        self.assertEqual(len(node), 5)
        # The node's command topics: what it subscribes, under the robot's namespace.
        master = rosgraph.Master('/test_robot_setup')
        _, subscribers, _ = master.getSystemState()
        subscribed = sorted(t for t, nodes in subscribers
                            if '/tianracer_sim' in nodes and t.endswith('/command'))
        expected = sorted('/car_a/%s/command' % c['controller'] for c in env.commands)
        self.assertEqual(subscribed, expected)
        self.assertEqual(len(expected), 4)

    def test_same_error_for_an_unknown_type(self):
        with self.assertRaises(Exception) as raised:
            environment(BAD, control_namespace='/bad_ctrl')
        env_error = str(raised.exception)
        self.assertIn("unknown type 'no_such_controllers/NoSuchController'", env_error)
        # The same model in its own namespace (car_a's plugins name /car_a themselves).
        urdf = subprocess.check_output(['xacro', MODEL]).decode().replace(
            '<robotNamespace>/car_a</robotNamespace>', '<robotNamespace>/bad</robotNamespace>')
        spawn = connect_gazebo(self, {'spawn_urdf_model': SpawnModel}, WAIT).spawn_urdf_model
        pose = Pose()
        pose.position.x = 3.0
        pose.orientation.w = 1.0
        answer = spawn(model_name='bad', model_xml=urdf, robot_namespace='/bad',
                       initial_pose=pose, reference_frame='world')
        self.assertFalse(answer.success)
        # The same message, from "controller 'wheel_controller': unknown type ..." on (the
        # environment places it in the YAML file too).
        core = env_error[env_error.index("controller 'wheel_controller'"):]
        self.assertIn(core.split(' (known types')[0], answer.status_message)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'robot_setup', RobotSetupTest)
