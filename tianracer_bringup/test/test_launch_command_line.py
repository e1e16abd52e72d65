"""The first launch a new user types, run as typed: `roslaunch tianracer_bringup tianracer.launch
ARG:=VALUE ...` on a command line of its own (a private master), not through an including launch
file (roslaunch parses command-line values differently: it refuses ':=' inside one).

- model_args in the form roslaunch accepts (name=value) reaches xacro;
- control_config without control_key: the controllers are read from the robot's namespace;
- a YAML without the robot's key: a start-up WARNING naming the namespace searched and the
  YAML's top-level keys.
"""
import os
import re
import tempfile
import time
import unittest
import xmlrpc.client

from tianracer_bringup.ros_session import CALLER, RosSession

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'data')
QUIET = ['world:=empty', 'lidar:=false', 'camera:=false', 'depth:=false', 'rviz:=false']


def launch(args, name):
    log_dir = tempfile.mkdtemp(prefix='tianracer_cmdline_')
    return RosSession(['tianracer_bringup', 'tianracer.launch'] + args,
                      os.path.join(log_dir, name + '_roslaunch.log'), os.path.join(log_dir, 'log'))


def log_text(session):
    with open(session.log_path, errors='replace') as f:
        return f.read()


def wait_for_log(session, pattern, timeout):
    deadline = time.time() + timeout
    while time.time() < deadline:
        session.check_running()
        match = re.search(pattern, log_text(session))
        if match:
            return match
        time.sleep(0.2)
    raise AssertionError('no line matching %r within %.0f s; see %s' %
                         (pattern, timeout, session.log_path))


def publishers(session, topic):
    pubs, _, _ = session.system_state()
    return [nodes for t, nodes in pubs if t == topic]


def subscribed(session, topic):
    _, subs, _ = session.system_state()
    return any(t == topic for t, _ in subs)


class ModelArgsAndControllersFromTheRobotsNamespace(unittest.TestCase):
    """roslaunch tianracer_bringup tianracer.launch robot_name:=racecar
         control_config:=racecar_control.yaml model_args:="robot_namespace=/racecar sensor_namespace=/racecar"
    """

    @classmethod
    def setUpClass(cls):
        cls.session = launch(['robot_name:=racecar',
                              'control_config:=' + os.path.join(DATA, 'racecar_control.yaml'),
                              'model_args:=robot_namespace=/racecar sensor_namespace=/racecar'] +
                             QUIET, 'racecar').start()
        # The robot line: the controllers the simulator started.
        cls.robot_line = wait_for_log(cls.session, r"robot 'racecar' \(.*", 240).group(0)

    @classmethod
    def tearDownClass(cls):
        cls.session.close()

    def test_model_args_reach_xacro(self):
        code, _, urdf = self.session.master().getParam(CALLER, '/robot_description')
        self.assertEqual(code, 1)
        # sensor_namespace moved the lidar's topic; robot_namespace the ros_control plugin.
        self.assertIn('<topicName>/racecar/scan</topicName>', urdf)
        self.assertIn('<robotNamespace>/racecar</robotNamespace>', urdf)
        self.assertNotIn('Invalid remapping argument', log_text(self.session))

    def test_controllers_come_from_the_robots_namespace(self):
        for name in ('joint_state_controller', 'left_rear_wheel_velocity_controller',
                     'left_steering_hinge_position_controller'):
            self.assertIn(name, self.robot_line)
        self.assertIn(' in /racecar', self.robot_line)
        self.session.wait_for(lambda: publishers(self.session, '/racecar/joint_states'), 60,
                              '/racecar/joint_states')
        self.session.wait_for(
            lambda: subscribed(self.session, '/racecar/left_rear_wheel_velocity_controller/command'),
            60, 'the wheel controller command topic')
        self.assertNotIn('but no controller', log_text(self.session))


class NoControllerForTheRobotIsAWarning(unittest.TestCase):
    """roslaunch tianracer_bringup tianracer.launch robot_name:=racecar
         control_config:=two_robots_control.yaml   (keys car_a and car_b)
    """

    @classmethod
    def setUpClass(cls):
        cls.session = launch(['robot_name:=racecar',
                              'control_config:=' + os.path.join(DATA, 'two_robots_control.yaml')] +
                             QUIET, 'no_controllers').start()

    @classmethod
    def tearDownClass(cls):
        cls.session.close()

    def test_warning_names_the_namespace_and_the_keys(self):
        line = wait_for_log(self.session, r"\[ WARN\].*robot 'racecar' has gazebo_ros_control but "
                                          r"no controller.*", 240).group(0)
        self.assertIn('under /racecar', line)
        self.assertIn('two_robots_control.yaml has the top-level keys [car_a, car_b]', line)
        self.assertIn('control_key:=car_a', line)
        # The simulator goes on without controllers.
        self.session.wait_for(lambda: publishers(self.session, '/clock'), 60, '/clock')
        self.session.check_running()


if __name__ == '__main__':
    unittest.main()
