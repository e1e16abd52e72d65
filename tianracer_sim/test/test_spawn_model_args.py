#!/usr/bin/env python3
"""spawn_model's arguments: gazebo_ros spawn_model's, parsed the same way; what we cannot
honour (-J, -database) and bad values are refused with a message."""
import contextlib
import io
import math
import os
import tempfile
import unittest

from tianracer_sim.script_module import load_script

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'scripts', 'spawn_model')


sm = load_script(SCRIPT, 'spawn_model_script')


class ParseTest(unittest.TestCase):
    def refused(self, argv):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as ctx:
            sm.parse_args(argv)
        self.assertEqual(ctx.exception.code, sm.USAGE_ERROR)
        return err.getvalue()

    def test_gazebo_launch_line(self):
        a = sm.parse_args('-urdf -param robot_description -model car2 -x 1.5 -y -2 -z 0.1 '
                          '-R 0.1 -P 0.2 -Y 1.57 -robot_namespace /car2 -unpause'.split())
        self.assertTrue(a.urdf)
        self.assertFalse(a.sdf)
        self.assertEqual(a.param_name, 'robot_description')
        self.assertEqual(a.model_name, 'car2')
        self.assertEqual((a.x, a.y, a.z, a.R, a.P, a.Y), (1.5, -2.0, 0.1, 0.1, 0.2, 1.57))
        self.assertEqual(a.robot_namespace, '/car2')
        self.assertTrue(a.unpause)
        self.assertEqual(sm.service_names(a)[0], '/gazebo/spawn_urdf_model')

    def test_defaults(self):
        a = sm.parse_args('-sdf -file box.sdf -model box'.split())
        self.assertEqual((a.x, a.y, a.z, a.R, a.P, a.Y), (0.0,) * 6)
        self.assertEqual(a.reference_frame, '')
        self.assertIsNone(a.robot_namespace)  # the node's namespace, as gazebo_ros
        self.assertEqual(a.wait_model, '')
        self.assertFalse(a.bond)
        self.assertEqual(sm.service_names(a),
                         ('/gazebo/spawn_sdf_model', '/gazebo/delete_model',
                          '/gazebo/unpause_physics', '/gazebo/model_states'))

    def test_gazebo_namespace_and_wait(self):
        a = sm.parse_args('-sdf -file b.sdf -model b -gazebo_namespace sim/ -wait car1 '
                          '-reference_frame car1::base_link -b -package_to_model'.split())
        self.assertEqual(sm.service_names(a)[0], '/sim/spawn_sdf_model')
        self.assertEqual(a.wait_model, 'car1')
        self.assertEqual(a.reference_frame, 'car1::base_link')
        self.assertTrue(a.bond)

    def test_kind_source_and_model_are_required(self):
        self.refused('-file b.sdf -model b'.split())              # -urdf or -sdf
        self.refused('-urdf -sdf -file b.sdf -model b'.split())   # not both
        self.refused('-urdf -model b'.split())                    # a source
        self.refused('-urdf -file a -param b -model b'.split())   # one source
        self.refused('-urdf -file a'.split())                     # -model

    def test_joint_positions(self):
        a = sm.parse_args('-urdf -param d -model c -J pivot 0.5 -J elbow -0.1'.split())
        self.assertEqual(a.joints, [['pivot', 0.5], ['elbow', -0.1]])
        self.assertEqual(sm.configuration_service(a), '/gazebo/set_model_configuration')
        self.assertIn('-J pivot nan', self.refused('-urdf -param d -model c -J pivot nan'.split()))
        self.assertIn('-J pivot one', self.refused('-urdf -param d -model c -J pivot one'.split()))

    def test_unsupported_and_bad_values_are_named(self):
        self.assertIn('model database', self.refused('-sdf -database cone -model c'.split()))
        self.assertIn('-x nan', self.refused('-urdf -param d -model c -x nan'.split()))
        self.assertIn('-Y inf', self.refused('-urdf -param d -model c -Y inf'.split()))
        self.refused('-urdf -param d -model c -x one'.split())

    def test_quaternion_is_rz_ry_rx(self):
        x, y, z, w = sm.quaternion_from_rpy(0.0, 0.0, math.pi / 2)
        self.assertAlmostEqual(z, math.sqrt(0.5))
        self.assertAlmostEqual(w, math.sqrt(0.5))
        # roll then pitch (extrinsic x then y): q = qy * qx
        x, y, z, w = sm.quaternion_from_rpy(0.3, 0.2, 0.0)
        cx, sx, cy, sy = math.cos(0.15), math.sin(0.15), math.cos(0.1), math.sin(0.1)
        self.assertAlmostEqual(x, cy * sx)
        self.assertAlmostEqual(y, sy * cx)
        self.assertAlmostEqual(z, -sy * sx)
        self.assertAlmostEqual(w, cy * cx)

    def test_load_xml(self):
        with tempfile.NamedTemporaryFile('w', suffix='.sdf', delete=False) as f:
            f.write('<sdf/>')
        try:
            self.assertEqual(sm.load_xml(sm.parse_args(['-sdf', '-file', f.name, '-model', 'b'])),
                             '<sdf/>')
        finally:
            os.unlink(f.name)
        with self.assertRaisesRegex(ValueError, '-file /no/such.sdf'):
            sm.load_xml(sm.parse_args('-sdf -file /no/such.sdf -model b'.split()))
        a = sm.parse_args('-urdf -param robot_description -model c'.split())
        self.assertEqual(sm.load_xml(a, lambda name: '<robot/>'), '<robot/>')
        with self.assertRaisesRegex(ValueError, 'parameter is not set'):
            sm.load_xml(a, lambda name: None)
        with self.assertRaisesRegex(ValueError, 'empty'):
            sm.load_xml(a, lambda name: '  \n')
        a = sm.parse_args('-urdf -stdin -model c'.split())
        self.assertEqual(sm.load_xml(a, stdin=io.StringIO('<robot/>')), '<robot/>')


if __name__ == '__main__':
    unittest.main()
