"""The repo is a catkin source space whose packages catkin can all discover."""
import os
import re
import unittest

from catkin_pkg.packages import find_packages

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
EXPECTED = {'tianracer', 'tianracer_description', 'tianracer_sim', 'tianracer_control',
            'tianracer_assets', 'tianracer_bringup', 'tianracer_gym', 'tianracer_tests'}
# Stand-ins for packages the system may lack; scripts/stand_in_packages.sh leaves each out
# (CATKIN_IGNORE) where the system has the real one.
STAND_INS = {'gazebo_msgs', 'ackermann_msgs', 'xacro', 'controller_manager_msgs',
             'controller_manager', 'gazebo_ros', 'control_msgs', 'four_wheel_steering_msgs'}


class WorkspaceTest(unittest.TestCase):
    def setUp(self):
        self.packages = {pkg.name: (path, pkg) for path, pkg in find_packages(REPO).items()}

    def test_all_packages_are_discoverable(self):
        built = {p for p in STAND_INS if os.path.exists(os.path.join(REPO, p, 'package.xml'))
                 and not os.path.exists(os.path.join(REPO, p, 'CATKIN_IGNORE'))}
        self.assertEqual(set(self.packages), EXPECTED | built)

    def test_no_manifest_at_the_source_space_root(self):
        # A package.xml at the root would make catkin see one package and hide the others.
        self.assertFalse(os.path.exists(os.path.join(REPO, 'package.xml')))

    def test_manifests_are_format_3_with_valid_maintainers(self):
        for name, (_, pkg) in self.packages.items():
            self.assertEqual(pkg.package_format, 3, name)
            self.assertTrue(pkg.maintainers, name)
            for m in pkg.maintainers:
                self.assertRegex(m.email, r'^[^@\s]+@[^@\s]+\.[a-z]+$', name)
            pkg.validate()

    def test_metapackage_depends_on_the_five_packages(self):
        _, meta = self.packages['tianracer']
        self.assertTrue(any(e.tagname == 'metapackage' for e in meta.exports))
        self.assertEqual({d.name for d in meta.exec_depends},
                         {'tianracer_description', 'tianracer_sim', 'tianracer_control',
                          'tianracer_assets', 'tianracer_bringup'})

    def test_build_output_is_ignored_by_git(self):
        with open(os.path.join(REPO, '.gitignore')) as f:
            self.assertIn('/.build/', f.read().split())

    def test_ci_runs_exactly_the_readme_test_command(self):
        with open(os.path.join(REPO, '.ci', 'run')) as f:
            ci = f.read()
        with open(os.path.join(REPO, 'README.md')) as f:
            readme = f.read()
        self.assertIn('exec ./test.sh', ci)
        self.assertRegex(readme, re.compile(r'^\s*\./test\.sh\s*$', re.M))


if __name__ == '__main__':
    unittest.main()
