"""The spawner's and controller_manager's arguments, without ROS: options as ros_control's,
the service names in a namespace, controller names from a YAML file."""
import os
import tempfile
import unittest

from controller_manager import cli, spawner


class SpawnerArguments(unittest.TestCase):
    def test_options_and_defaults(self):
        a = spawner.parse_args(['joint_state_controller', 'wheel_controller'])
        self.assertEqual(a.controllers, ['joint_state_controller', 'wheel_controller'])
        self.assertFalse(a.stopped)
        self.assertEqual(a.timeout, 30)
        self.assertIsNone(a.namespace)
        a = spawner.parse_args(['--stopped', '--timeout', '2.5', '--namespace', '/car',
                                '--wait-for', '/ready', 'c'])
        self.assertTrue(a.stopped)
        self.assertEqual((a.timeout, a.namespace, a.wait_for), (2.5, '/car', '/ready'))
        self.assertTrue(spawner.parse_args(['--no-timeout', 'c']).no_timeout)

    def test_at_least_one_controller(self):
        with self.assertRaises(SystemExit):
            spawner.parse_args(['--stopped'])

    def test_timeout_zero_or_no_timeout_waits_forever(self):
        self.assertIsNone(spawner.Spawner(spawner.parse_args(['--timeout', '0', 'c'])).timeout)
        self.assertIsNone(spawner.Spawner(spawner.parse_args(['--no-timeout', 'c'])).timeout)
        self.assertEqual(spawner.Spawner(spawner.parse_args(['c'])).timeout, 30)

    def test_service_names(self):
        self.assertEqual(spawner.service_names(''),
                         ('controller_manager/load_controller',
                          'controller_manager/switch_controller',
                          'controller_manager/unload_controller'))
        self.assertEqual(spawner.service_names('/car/')[0], '/car/controller_manager/load_controller')
        self.assertEqual(spawner.service_names('car')[2], 'car/controller_manager/unload_controller')

    def test_yaml_file_names_its_controllers(self):
        path = os.path.join(tempfile.mkdtemp(), 'ctrl.yaml')
        with open(path, 'w') as f:
            f.write('jsc:\n  type: joint_state_controller/JointStateController\n'
                    'wheel:\n  type: velocity_controllers/JointVelocityController\n  joint: w\n')
        uploaded = []
        names = spawner.controller_names(['first', path, 'last'], uploaded.append)
        self.assertEqual(names, ['first', 'jsc', 'wheel', 'last'])
        self.assertEqual(uploaded[0]['wheel']['joint'], 'w')


class ControllerManagerCommand(unittest.TestCase):
    def test_unknown_command_prints_the_usage_and_fails(self):
        self.assertEqual(cli.run(['frobnicate', 'x']), 1)
        self.assertEqual(cli.run([]), 0)


if __name__ == '__main__':
    unittest.main()
