"""scripts/catkin_generator.sh: a new workspace is built with Ninja when it is installed, one
already configured keeps its generator (CMake refuses to switch), and every catkin_make of
scripts/setup.sh and test.sh passes what it says, so ./test.sh after ./run.sh builds the same
workspace with the same generator."""
import os
import re
import shutil
import subprocess
import tempfile
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
HELPER = os.path.join(REPO, 'scripts', 'catkin_generator.sh')


def generator(workspace, path=None):
    env = dict(os.environ)
    if path is not None:
        env['PATH'] = path
    out = subprocess.run(['/bin/bash', '-c', 'source "$0"; catkin_generator "$1"', HELPER, workspace],
                         env=env, capture_output=True, text=True, check=True)
    return out.stdout.strip()


class CatkinGeneratorTest(unittest.TestCase):
    def setUp(self):
        self.ws = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.ws)

    def cache(self, generator_name):
        os.makedirs(os.path.join(self.ws, 'build'), exist_ok=True)
        with open(os.path.join(self.ws, 'build', 'CMakeCache.txt'), 'w') as f:
            f.write('CMAKE_BUILD_TYPE:STRING=Release\n'
                    'CMAKE_GENERATOR:INTERNAL=%s\n' % generator_name)

    def test_new_workspace_uses_ninja_when_installed(self):
        self.assertEqual(generator(self.ws), '--use-ninja' if shutil.which('ninja') else '')

    def test_new_workspace_without_ninja_uses_make(self):
        empty = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, empty)
        self.assertEqual(generator(self.ws, path=empty), '')

    def test_a_ninja_workspace_stays_ninja(self):
        self.cache('Ninja')
        self.assertEqual(generator(self.ws), '--use-ninja')

    def test_a_make_workspace_stays_make(self):
        self.cache('Unix Makefiles')
        self.assertEqual(generator(self.ws), '')
        self.cache('Ninja Multi-Config')  # not the single-config Ninja catkin_make makes
        self.assertEqual(generator(self.ws), '')

    def test_every_catkin_make_of_setup_and_test_passes_the_generator(self):
        for script in ('scripts/setup.sh', 'test.sh'):
            with open(os.path.join(REPO, script)) as f:
                text = f.read()
            calls = re.findall(r'^[^#\n]*\bcatkin_make\b(?! \()[^\n]*', text, re.M)
            calls = [c for c in calls if not re.match(r'\s*(say|echo)\b', c)]
            self.assertTrue(calls, script)
            for call in calls:
                self.assertIn('catkin_make "${generator[@]}"', call, '%s: %s' % (script, call))


if __name__ == '__main__':
    unittest.main()
