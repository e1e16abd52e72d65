"""The xacro stand-in's cache of expansions (xacro/xacro_cache.py): a second run of the same
command answers from the cache; a changed include, input, arg, environment variable or
package path expands again; a bad cache file is reported and replaced; other options are not
cached; a failing expansion is not cached."""
import glob
import json
import os
import shutil
import subprocess
import tempfile
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
XACRO = os.path.join(REPO, 'xacro', 'xacro')
MARK = '<!-- from the cache -->'


@unittest.skipIf(os.path.exists(os.path.join(REPO, 'xacro', 'CATKIN_IGNORE')),
                 'the system has a real xacro package')
class XacroCacheTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='xacro_cache_test_')
        self.addCleanup(shutil.rmtree, self.tmp)
        self.cache = os.path.join(self.tmp, 'cache')
        self.pkg = os.path.join(self.tmp, 'pkgs', 'cache_test_pkg')
        os.makedirs(os.path.join(self.pkg, 'urdf'))
        self.write('package.xml', '<package format="2"><name>cache_test_pkg</name><version>1.0.0'
                   '</version><description>d</description><maintainer email="a@b.org">a</maintainer>'
                   '<license>BSD</license><buildtool_depend>catkin</buildtool_depend></package>')
        self.write('urdf/robot.xacro',
                   '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '  <xacro:arg name="colour" default="red"/>\n'
                   '  <xacro:include filename="$(find cache_test_pkg)/urdf/part.xacro"/>\n'
                   '  <link name="base_$(arg colour)"/>\n'
                   '  <link name="env_$(optenv CACHE_TEST_SUFFIX none)"/>\n'
                   '  <xacro:part/>\n'
                   '</robot>\n')
        self.write('urdf/part.xacro', self.part('wheel'))
        self.model = os.path.join(self.pkg, 'urdf', 'robot.xacro')
        self.env = dict(os.environ, TIANRACER_XACRO_CACHE=self.cache,
                        ROS_PACKAGE_PATH=os.path.join(self.tmp, 'pkgs'))
        self.env.pop('CACHE_TEST_SUFFIX', None)

    @staticmethod
    def part(link):
        return ('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                '  <xacro:macro name="part"><link name="%s"/></xacro:macro>\n</robot>\n' % link)

    def write(self, rel, text):
        with open(os.path.join(self.pkg, rel), 'w') as f:
            f.write(text)

    def xacro(self, *args, env=None, ok=True):
        proc = subprocess.run([XACRO] + list(args), env=env or self.env, cwd=self.tmp,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              universal_newlines=True, timeout=120)
        if ok:
            self.assertEqual(proc.returncode, 0, proc.stderr)
        return proc

    def entries(self):
        return sorted(glob.glob(os.path.join(self.cache, '*.json')))

    def mark_entries(self):
        """Puts a mark into every cached output: a run that prints it was answered from the cache."""
        for path in self.entries():
            with open(path) as f:
                entry = json.load(f)
            entry['stdout'] = MARK + entry['stdout']
            with open(path, 'w') as f:
                json.dump(entry, f)

    def test_second_run_is_a_hit_with_the_same_output(self):
        first = self.xacro(self.model)
        self.assertIn('<link name="base_red"/>', first.stdout)
        self.assertIn('<link name="wheel"/>', first.stdout)
        self.assertEqual(len(self.entries()), 1)
        uncached = self.xacro(self.model, env=dict(self.env, TIANRACER_XACRO_CACHE='off'))
        self.assertEqual(first.stdout, uncached.stdout)
        second = self.xacro(self.model)
        self.assertEqual(first.stdout, second.stdout)
        self.mark_entries()
        self.assertTrue(self.xacro(self.model).stdout.startswith(MARK))

    def test_stderr_is_replayed_on_a_hit(self):
        first = self.xacro('--inorder', self.model)
        self.assertIn('in-order processing became default', first.stderr)
        self.mark_entries()
        second = self.xacro('--inorder', self.model)
        self.assertTrue(second.stdout.startswith(MARK))
        self.assertEqual(first.stderr, second.stderr)

    def test_changed_include_expands_again(self):
        self.xacro(self.model)
        self.mark_entries()
        self.write('urdf/part.xacro', self.part('tyre'))
        out = self.xacro(self.model).stdout
        self.assertFalse(out.startswith(MARK))
        self.assertIn('<link name="tyre"/>', out)
        self.assertNotIn('<link name="wheel"/>', out)
        # and the new expansion replaced the entry
        self.assertEqual(len(self.entries()), 1)
        self.mark_entries()
        self.assertTrue(self.xacro(self.model).stdout.startswith(MARK))

    def test_changed_input_expands_again(self):
        self.xacro(self.model)
        self.mark_entries()
        with open(self.model) as f:
            text = f.read()
        self.write('urdf/robot.xacro', text.replace('base_', 'chassis_'))
        out = self.xacro(self.model).stdout
        self.assertFalse(out.startswith(MARK))
        self.assertIn('<link name="chassis_red"/>', out)

    def test_changed_arg_expands_again(self):
        self.xacro(self.model)
        self.mark_entries()
        out = self.xacro(self.model, 'colour:=blue').stdout
        self.assertFalse(out.startswith(MARK))
        self.assertIn('<link name="base_blue"/>', out)
        self.assertEqual(len(self.entries()), 2)

    def test_changed_environment_variable_expands_again(self):
        self.assertIn('<link name="env_none"/>', self.xacro(self.model).stdout)
        self.mark_entries()
        out = self.xacro(self.model, env=dict(self.env, CACHE_TEST_SUFFIX='set')).stdout
        self.assertFalse(out.startswith(MARK))
        self.assertIn('<link name="env_set"/>', out)
        # an unrelated variable does not matter
        self.mark_entries()
        out = self.xacro(self.model, env=dict(self.env, CACHE_TEST_SUFFIX='set', UNRELATED='1')).stdout
        self.assertTrue(out.startswith(MARK))

    def test_moved_package_expands_again(self):
        self.xacro(self.model)
        self.mark_entries()
        moved = os.path.join(self.tmp, 'other', 'cache_test_pkg')
        shutil.copytree(self.pkg, moved)
        out = self.xacro(os.path.join(moved, 'urdf', 'robot.xacro'),
                         env=dict(self.env, ROS_PACKAGE_PATH=os.path.dirname(moved))).stdout
        self.assertFalse(out.startswith(MARK))
        self.assertIn(moved, out)  # the banner names the file expanded

    def test_bad_cache_file_is_reported_and_replaced(self):
        good = self.xacro(self.model).stdout
        for garbage in ('{not json', '[1, 2]', json.dumps({'format': 1, 'files': {}}),
                        '\xff\xfe'):
            (path,) = self.entries()
            with open(path, 'w', encoding='latin-1') as f:
                f.write(garbage)
            proc = self.xacro(self.model)
            self.assertEqual(proc.stdout, good)
            self.assertIn('is not a valid cache entry', proc.stderr)
            self.assertIn(path, proc.stderr)
            # replaced by a good entry: the next run is a quiet hit
            again = self.xacro(self.model)
            self.assertEqual(again.stdout, good)
            self.assertEqual(again.stderr, '')

    def test_other_options_and_off_are_not_cached(self):
        out_file = os.path.join(self.tmp, 'out.urdf')
        self.xacro('-o', out_file, self.model)
        self.xacro('--deps', self.model)
        self.xacro(self.model, env=dict(self.env, TIANRACER_XACRO_CACHE='off'))
        self.assertEqual(self.entries(), [])
        with open(out_file) as f:
            self.assertIn('<link name="base_red"/>', f.read())

    def test_failed_expansion_is_not_cached(self):
        self.write('urdf/part.xacro', '<robot><unclosed></robot>')
        proc = self.xacro(self.model, ok=False)
        self.assertNotEqual(proc.returncode, 0)
        self.assertEqual(self.entries(), [])
        self.write('urdf/part.xacro', self.part('wheel'))
        self.assertIn('<link name="wheel"/>', self.xacro(self.model).stdout)


if __name__ == '__main__':
    unittest.main()
