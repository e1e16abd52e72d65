#!/usr/bin/env python3
"""rostest: each bad configuration makes tianracer_sim_node exit with code 1 and a message
that names the parameter, file, link, joint or controller and the value."""
import os
import subprocess
import unittest

import rosgraph
import rospkg
import rospy
import rostest

from sim_node_binary import node_binary

PKG = rospkg.RosPack().get_path('tianracer_sim')
DATA = os.path.join(PKG, 'test', 'data', 'urdf')
WORLDS = os.path.join(PKG, 'test', 'data', 'worlds')
XACRO = os.path.join(rospkg.RosPack().get_path('tianracer_description'), 'urdf',
                     'tianracer_description.xacro')


class SimBadInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_sim_bad_input', anonymous=True)
        cls.urdf = subprocess.check_output(['xacro', XACRO]).decode()

    def setUp(self):
        # Private parameters given as _name:=value stay on the server: clear them too.
        for p in ('/robot_description', '/tianracer', '/sim_under_test'):
            if rospy.has_param(p):
                rospy.delete_param(p)

    def run_node(self, *args):
        """Runs the node; returns (exit code, combined output). It must stop by itself."""
        proc = subprocess.run([node_binary(), '__name:=sim_under_test'] + list(args),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
        return proc.returncode, proc.stdout.decode(errors='replace')

    def assert_fails(self, expected, *args):
        code, out = self.run_node(*args)
        self.assertEqual(code, 1, out)
        for text in expected:
            self.assertIn(text, out)

    def assert_bad_controller(self, params, expected):
        """The car with a controller 'bad' of `params` fails, naming it and `expected`."""
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/tianracer/bad', params)
        self.assert_fails(["controller 'bad'"] + expected, '_controllers:=bad')

    def test_missing_robot_description(self):
        self.assert_fails(['/robot_description', 'is not set'])

    def test_empty_robot_description(self):
        rospy.set_param('/robot_description', '  ')
        self.assert_fails(['/robot_description', 'is empty'])

    def test_urdf_syntax_error_names_the_line(self):
        self.assert_fails(['invalid_syntax.urdf:4: XML error'],
                          '_model:=' + os.path.join(DATA, 'invalid_syntax.urdf'))

    def test_missing_mesh_names_link_and_path(self):
        self.assert_fails(['mesh', 'not found'],
                          '_model:=' + os.path.join(DATA, 'invalid_missing_mesh.urdf'))

    def test_transmission_on_unknown_joint(self):
        self.assert_fails(['transmission', 'unknown joint'],
                          '_model:=' + os.path.join(DATA, 'invalid_transmission_joint.urdf'))

    def test_non_positive_mass(self):
        self.assert_fails(['mass'], '_model:=' + os.path.join(DATA, 'invalid_mass.urdf'))

    def test_inertia_not_positive_definite(self):
        self.assert_fails(['inertia'], '_model:=' + os.path.join(DATA, 'invalid_inertia.urdf'))

    def test_controller_on_unknown_joint(self):
        self.assert_bad_controller({'type': 'velocity_controllers/JointVelocityController',
                                    'joint': 'no_such_joint'}, ['no_such_joint'])

    def test_controller_interface_mismatch(self):
        # The hinge's transmission gives EffortJointInterface, not velocity.
        self.assert_bad_controller({'type': 'velocity_controllers/JointVelocityController',
                                    'joint': 'left_steering_hinge_joint'}, ['Effort', 'Velocity'])

    def test_unknown_controller_type(self):
        self.assert_bad_controller({'type': 'foo_controllers/Bar',
                                    'joint': 'left_rear_wheel_joint'}, ['foo_controllers/Bar'])

    def test_controller_without_parameters(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(["controller 'ghost'", '/tianracer/ghost'], '_controllers:=ghost')

    # Issue 9 bad-input matrix (docs/bad_input.md): meshes that exist but hold no triangles are
    # refused when the physics loads them; world errors; the controller YAML; the spawn pose.
    def test_empty_mesh(self):
        self.assert_fails(["meshes/empty.stl': file is empty"],
                          '_model:=' + os.path.join(DATA, 'invalid_empty_mesh.urdf'))

    def test_zero_triangle_mesh(self):
        self.assert_fails(["meshes/lines.obj': no triangles"],
                          '_model:=' + os.path.join(DATA, 'invalid_no_triangles_mesh.urdf'))

    def test_world_with_an_empty_mesh_stops_with_strict_world(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(["worlds/meshes/empty.stl': file is empty"],
                          '_world:=' + os.path.join(WORLDS, 'invalid_empty_mesh.world'),
                          '_strict_world:=true')

    def test_world_with_a_missing_model_stops_with_strict_world(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(["missing_model.world:7: <include> of 'model://no_such_model': model not "
                           'found; searched:'],
                          '_world:=' + os.path.join(WORLDS, 'missing_model.world'),
                          '_strict_world:=true', '_disable_sensors:=camera depth')

    def test_world_with_a_missing_model_loads_the_rest(self):
        # As Gazebo: an error naming the URI and the folders searched, another for the empty
        # mesh, and the node runs with the rest of the world (the wall is seen by the physics).
        rospy.set_param('/robot_description', self.urdf)
        proc = subprocess.Popen([node_binary(), '__name:=sim_under_test',
                                 '_world:=' + os.path.join(WORLDS, 'missing_model.world'),
                                 '_disable_sensors:=camera depth'],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        try:
            from gazebo_msgs.srv import GetWorldProperties
            from nav_msgs.msg import Odometry
            rospy.wait_for_message('/tianracer/ground_truth/odom', Odometry, timeout=60)
            self.assertIsNone(proc.poll())
            rospy.wait_for_service('/gazebo/get_world_properties', timeout=30)
            models = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)().model_names
            for name in ('statue', 'wall'):
                self.assertIn(name, models)
            self.assertNotIn('no_such_model', models)
        finally:
            proc.terminate()
            out = proc.communicate(timeout=30)[0].decode(errors='replace')
        self.assertIn("missing_model.world:7: <include> of 'model://no_such_model': model not found; "
                      'searched:', out)
        self.assertIn('; the model is left out', out)
        self.assertIn("model 'statue' link 'base' collision 'collision': mesh '", out)
        self.assertIn("worlds/meshes/empty.stl': file is empty; the collision is left out", out)

    def test_world_syntax_error_names_the_line(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(['invalid_syntax.world:6: malformed XML'],
                          '_world:=' + os.path.join(WORLDS, 'invalid_syntax.world'))

    def test_controller_missing_joint(self):
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/tianracer/bad', {'type': 'effort_controllers/JointPositionController'})
        self.assert_fails(["controller 'bad': no joint given"], '_controllers:=bad')

    def test_controller_missing_pid(self):
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/tianracer/bad', {'type': 'effort_controllers/JointPositionController',
                                           'joint': 'left_steering_hinge_joint'})
        self.assert_fails(["controller 'bad': pid/p is missing"], '_controllers:=bad')

    def test_spawn_pose_out_of_range(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(['spawn pose', 'position x 1e+30 is out of range (|x| <= 1e+06 m)'],
                          '_x:=1e30')

    def test_spawn_pose_not_finite(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(['spawn pose', 'pose is not finite'], '_y:=nan')

    def test_bad_real_time_factor(self):
        rospy.set_param('/robot_description', self.urdf)
        self.assert_fails(['real_time_factor', '-1'], '_real_time_factor:=-1.0')

    def test_bad_lockstep_parameters(self):
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/sim_under_test/lockstep/replies', '/cmd_vel')
        rospy.set_param('/sim_under_test/lockstep/reply_period', 0.0)
        self.assert_fails(['/sim_under_test/lockstep/reply_period', 'must be a number > 0'],
                          '_disable_sensors:=ray camera depth')
        rospy.set_param('/sim_under_test/lockstep/reply_period', 0.02)
        rospy.set_param('/sim_under_test/lockstep/ticks', [1, 2])
        self.assert_fails(['/sim_under_test/lockstep/ticks', 'must be a list of topics'],
                          '_disable_sensors:=ray camera depth')

    def test_two_robots_in_one_namespace(self):
        # The same xacro twice without robot_namespace:=...: both cars would answer to
        # /tianracer/... commands.
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/sim_under_test/robots', 'car_a car_b')
        rospy.set_param('/sim_under_test/car_b/y', 1.0)
        self.assert_fails(["robot 'car_b'", 'ros_control namespace /tianracer', "robot 'car_a'",
                           'robot_namespace:=/car_b'], '_disable_sensors:=camera depth')

    def test_two_robots_on_one_sensor_topic(self):
        # robot_namespace given but not sensor_namespace: car_b's lidar would publish on /scan
        # too. It is left out with an error naming the topic and its owner; the rest runs on.
        rospy.set_param('/robot_description', self.urdf)
        rospy.set_param('/car_b/robot_description', subprocess.check_output(
            ['xacro', XACRO, 'robot_namespace:=/car_b']).decode())
        rospy.set_param('/sim_under_test/robots', 'car_a car_b')
        rospy.set_param('/sim_under_test/car_b/robot_param', '/car_b/robot_description')
        rospy.set_param('/sim_under_test/car_b/y', 1.0)
        proc = subprocess.Popen([node_binary(), '__name:=sim_under_test',
                                 '_disable_sensors:=camera depth'],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        try:
            # Up and stepping: both cars' ground truth arrive.
            from nav_msgs.msg import Odometry
            for ns in ('/tianracer', '/car_b'):
                rospy.wait_for_message(ns + '/ground_truth/odom', Odometry, timeout=60)
            self.assertIsNone(proc.poll())
        finally:
            proc.terminate()
            out = proc.communicate(timeout=30)[0].decode(errors='replace')
            rospy.delete_param('/car_b')
        self.assertIn("robot 'car_b': sensor 'hokuyo_sensor' on link 'lidar' left out: /scan is "
                      "already published by robot 'car_a' sensor 'hokuyo_sensor'", out)
        self.assertIn('sensor_namespace:=/<robot name>', out)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'sim_bad_input', SimBadInput)
