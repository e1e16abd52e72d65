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


class FakeManager:
    """controller_manager_interface's calls, recorded; `unknown` cannot be loaded (a type the
    manager does not have), and what was not loaded cannot be started."""
    def __init__(self, unknown):
        self.unknown, self.loaded, self.running, self.calls = set(unknown), set(), set(), []

    def load_controller(self, name):
        self.calls.append(('load', name))
        if name in self.unknown:
            return False
        self.loaded.add(name)
        return True

    def start_controller(self, name):
        self.calls.append(('start', name))
        if name not in self.loaded:
            return False
        self.running.add(name)
        return True

    def stop_controller(self, name):
        self.calls.append(('stop', name))
        ok = name in self.running
        self.running.discard(name)
        return ok

    def unload_controller(self, name):
        self.calls.append(('unload', name))
        ok = name in self.loaded
        self.loaded.discard(name)
        return ok


class ControllerManagerCommands(unittest.TestCase):
    def run_with(self, fake, args):
        real = cli.cm
        cli.cm = fake
        try:
            return cli.run(args)
        finally:
            cli.cm = real

    def test_spawn_starts_every_controller_it_could_load(self):
        fake = FakeManager(unknown=['arm_controller'])
        status = self.run_with(fake, ['spawn', 'joint_state_controller', 'arm_controller', 'gripper'])
        self.assertEqual(fake.running, {'joint_state_controller', 'gripper'})
        self.assertEqual(status, 1)  # one failed: the exit status says so
        self.assertEqual(fake.calls[:3], [('load', 'joint_state_controller'),
                                          ('load', 'arm_controller'), ('load', 'gripper')])
        fake = FakeManager(unknown=[])
        self.assertEqual(self.run_with(fake, ['sp', 'a', 'b']), 0)
        self.assertEqual(fake.running, {'a', 'b'})

    def test_kill_unloads_every_controller_it_can(self):
        fake = FakeManager(unknown=[])
        self.run_with(fake, ['spawn', 'a', 'b'])
        fake.running.discard('a')  # stopped already: its stop fails, its unload still runs
        self.assertEqual(self.run_with(fake, ['kill', 'a', 'b']), 1)
        self.assertEqual(fake.loaded, set())
