#!/usr/bin/env python3
"""rostest (gazebo_properties.test): gazebo_ros's property services on the simulator started by
gazebo_ros's empty_world.launch, paused, on test/worlds/properties.world, plus 'arm' spawned by
spawn_model with -J shoulder 0.4. Each service with good input (the value read back is the one
set) and bad input (success false, the message naming what is wrong, nothing changed); and the
exact /gazebo topic and service list (test_gazebo_ros_network.py's)."""
import time
import unittest

import rospy
import rostest
from dynamic_reconfigure.msg import Config, DoubleParameter
from dynamic_reconfigure.srv import Reconfigure
from gazebo_msgs.msg import ODEJointProperties, ODEPhysics
from gazebo_msgs.srv import (ApplyJointEffort, DeleteLight, GetJointProperties,
                             GetLightProperties, GetLinkProperties, GetPhysicsProperties,
                             JointRequest, SetJointProperties, SetLightProperties,
                             SetLinkProperties, SetModelConfiguration, SetPhysicsProperties)
from geometry_msgs.msg import Vector3
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty
from tianracer_sim.sim_time import connect_gazebo

import test_gazebo_ros_network as network

NAN = float('nan')


# The services this test calls, as attributes of the test case named as the services are.
SERVICES = {
    'get_joint_properties': GetJointProperties, 'set_joint_properties': SetJointProperties,
    'get_physics_properties': GetPhysicsProperties, 'set_physics_properties': SetPhysicsProperties,
    'get_light_properties': GetLightProperties, 'set_light_properties': SetLightProperties,
    'delete_light': DeleteLight, 'get_link_properties': GetLinkProperties,
    'set_link_properties': SetLinkProperties, 'set_model_configuration': SetModelConfiguration,
    'apply_joint_effort': ApplyJointEffort, 'clear_joint_forces': JointRequest,
    'set_parameters': Reconfigure, 'pause_physics': Empty, 'unpause_physics': Empty}


class GazeboPropertiesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_gazebo_properties')
        connect_gazebo(cls, SERVICES, 120.0)

    def test_a_exact_gazebo_ros_lists(self):
        # spawn_model has done its work (the arm is in the world) before the lists are read.
        deadline = time.time() + 60.0
        while not self.get_joint_properties('arm::shoulder').success and time.time() < deadline:
            time.sleep(0.5)
        network.check_lists(self, disabled=False)

    def test_b_spawn_model_J_sets_the_joint(self):
        j = self.get_joint_properties('arm::shoulder')
        self.assertTrue(j.success, j.status_message)
        self.assertAlmostEqual(j.position[0], 0.4, places=9)

    def test_c_joint_properties(self):
        j = self.get_joint_properties('pivot')
        self.assertTrue(j.success, j.status_message)
        self.assertEqual(j.type, GetJointProperties._response_class.REVOLUTE)
        self.assertEqual(j.damping, (0.0,))
        res = self.set_model_configuration('pendulum', '', ['pivot'], [0.3])
        self.assertTrue(res.success, res.status_message)
        j = self.get_joint_properties('pendulum::pivot')
        self.assertAlmostEqual(j.position[0], 0.3, places=9)
        self.assertEqual(j.rate, (0.0,))
        res = self.set_joint_properties('pivot', ODEJointProperties(damping=[0.7], loStop=[-0.5],
                                                                    hiStop=[0.5]))
        self.assertTrue(res.success, res.status_message)
        self.assertEqual(self.get_joint_properties('pivot').damping, (0.7,))
        # Bad input: named, nothing changed.
        bad = self.get_joint_properties('nope')
        self.assertFalse(bad.success)
        self.assertIn("joint 'nope' not found", bad.status_message)
        bad = self.set_joint_properties('pivot', ODEJointProperties(damping=[NAN], hiStop=[0.1]))
        self.assertFalse(bad.success)
        self.assertIn('damping must be finite', bad.status_message)
        bad = self.set_joint_properties('pivot', ODEJointProperties(damping=[-1.0]))
        self.assertFalse(bad.success)
        self.assertIn('got -1', bad.status_message)
        bad = self.set_joint_properties('pivot', ODEJointProperties(cfm=[0.1]))
        self.assertFalse(bad.success)
        self.assertIn('cfm', bad.status_message)
        self.assertEqual(self.get_joint_properties('pivot').damping, (0.7,))
        for args, text in ((('ghost', '', ['pivot'], [0.1]), "no model named 'ghost'"),
                           (('pendulum', '', ['elbow'], [0.1]), "no movable joint 'elbow'"),
                           (('pendulum', '', ['pivot'], [NAN]), 'position nan is not finite'),
                           (('pendulum', '', ['pivot'], []), '1 joint names but 0 positions')):
            bad = self.set_model_configuration(*args)
            self.assertFalse(bad.success, args)
            self.assertIn(text, bad.status_message)
        self.assertAlmostEqual(self.get_joint_properties('pivot').position[0], 0.3, places=9)

    def test_d_physics_properties(self):
        p = self.get_physics_properties()
        self.assertTrue(p.success)
        self.assertTrue(p.pause)
        self.assertAlmostEqual(p.time_step, 0.001)
        self.assertAlmostEqual(p.gravity.z, -9.8)
        self.assertEqual(p.ode_config.sor_pgs_iters, 20)
        ode = p.ode_config
        ode.sor_pgs_iters = 40
        res = self.set_physics_properties(0.002, 500.0, Vector3(0, 0, -1.62), ode)
        self.assertTrue(res.success, res.status_message)
        q = self.get_physics_properties()
        self.assertAlmostEqual(q.time_step, 0.002)
        self.assertAlmostEqual(q.max_update_rate, 500.0)
        self.assertAlmostEqual(q.gravity.z, -1.62)
        self.assertEqual(q.ode_config.sor_pgs_iters, 40)
        # The dynamic_reconfigure face: the same settings.
        update = rospy.wait_for_message('/gazebo/parameter_updates', Config, timeout=30.0)
        self.assertIn(('gravity_z', -1.62), [(d.name, d.value) for d in update.doubles])
        r = self.set_parameters(Config(doubles=[DoubleParameter('gravity_z', -9.8)]))
        self.assertIn(('gravity_z', -9.8), [(d.name, d.value) for d in r.config.doubles])
        self.assertAlmostEqual(self.get_physics_properties().gravity.z, -9.8)
        # Bad input: refused, nothing changed.
        for args, text in (((-0.001, 500.0, Vector3(0, 0, -9.8), ODEPhysics()), 'time_step must be in'),
                           ((0.001, 500.0, Vector3(NAN, 0, -9.8), ODEPhysics()), 'gravity (nan'),
                           ((0.001, -5.0, Vector3(0, 0, -9.8), ODEPhysics()), 'max_update_rate'),
                           ((0.001, 500.0, Vector3(0, 0, -9.8), ODEPhysics(cfm=0.5, sor_pgs_iters=20)),
                            'ode_config.sor_pgs_w')):
            bad = self.set_physics_properties(*args)
            self.assertFalse(bad.success, args)
            self.assertIn(text, bad.status_message)
        q = self.get_physics_properties()
        self.assertAlmostEqual(q.time_step, 0.002)
        self.assertAlmostEqual(q.max_update_rate, 500.0)

    def test_e_lights(self):
        sun = self.get_light_properties('sun')
        self.assertTrue(sun.success)
        self.assertAlmostEqual(sun.attenuation_constant, 0.9)
        lamp = self.get_light_properties('lamp')
        self.assertAlmostEqual(lamp.diffuse.g, 0.5)
        self.assertAlmostEqual(lamp.attenuation_linear, 0.5)
        res = self.set_light_properties(light_name='lamp', diffuse=ColorRGBA(0.1, 0.2, 0.3, 1.0),
                             specular=ColorRGBA(0.1, 0.1, 0.1, 1.0), attenuation_constant=1.0)
        self.assertTrue(res.success, res.status_message)
        lamp = self.get_light_properties('lamp')
        self.assertAlmostEqual(lamp.diffuse.b, 0.3, places=6)
        self.assertAlmostEqual(lamp.attenuation_linear, 0.0)
        bad = self.set_light_properties(light_name='lamp', diffuse=ColorRGBA(NAN, 0, 0, 1),
                             attenuation_constant=1.0)
        self.assertFalse(bad.success)
        self.assertIn("light 'lamp': diffuse", bad.status_message)
        bad = self.set_light_properties(light_name='nope', diffuse=ColorRGBA(1, 1, 1, 1))
        self.assertFalse(bad.success)
        self.assertIn("light 'nope' not found", bad.status_message)
        self.assertAlmostEqual(self.get_light_properties('lamp').diffuse.b, 0.3, places=6)
        self.assertFalse(self.get_light_properties('nope').success)
        self.assertTrue(self.delete_light('lamp').success)
        self.assertFalse(self.get_light_properties('lamp').success)
        self.assertFalse(self.delete_light('lamp').success)

    def test_f_links(self):
        l = self.get_link_properties('pendulum::bob')
        self.assertTrue(l.success, l.status_message)
        self.assertAlmostEqual(l.mass, 1.5)
        self.assertAlmostEqual(l.com.position.z, 0.01)
        self.assertAlmostEqual(l.iyy, 0.003)
        bad = self.get_link_properties('pendulum::arm')
        self.assertFalse(bad.success)
        self.assertIn("has no link 'arm'", bad.status_message)
        bad = self.set_link_properties(link_name='pendulum::bob', mass=2.0)
        self.assertFalse(bad.success)
        self.assertIn('nothing changed', bad.status_message)
        self.assertAlmostEqual(self.get_link_properties('pendulum::bob').mass, 1.5)

    def test_g_apply_joint_effort(self):
        self.assertTrue(self.set_model_configuration('pendulum', '', ['pivot'], [0.0]).success)
        res = self.apply_joint_effort('pivot', 0.2, rospy.Time(0), rospy.Duration(-1))
        self.assertTrue(res.success, res.status_message)
        bad = self.apply_joint_effort('nope', 0.2, rospy.Time(0), rospy.Duration(-1))
        self.assertFalse(bad.success)
        self.assertIn("joint 'nope' not found", bad.status_message)
        bad = self.apply_joint_effort('pivot', NAN, rospy.Time(0), rospy.Duration(-1))
        self.assertFalse(bad.success)
        # Half a second of sim time pushes the pendulum forward; cleared, it stops being pushed.
        self.unpause_physics()
        start = rospy.get_time()
        while rospy.get_time() < start + 0.3 and not rospy.is_shutdown():
            rospy.sleep(0.05)
        self.pause_physics()
        self.assertGreater(self.get_joint_properties('pivot').position[0], 0.0)
        self.clear_joint_forces('pivot')


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'gazebo_properties', GazeboPropertiesTest)
