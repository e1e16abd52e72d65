"""The workspace's env hook (tianracer_sim/env-hooks/50.tianracer_python_startup.sh): sourcing
the workspace sets SETUPTOOLS_USE_DISTUTILS=stdlib unless the user set it, and with it
roslaunch starts without loading setuptools (docs/performance.md, Start-up)."""
import os
import subprocess
import sys
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
HOOK = os.path.join(REPO, 'tianracer_sim', 'env-hooks', '50.tianracer_python_startup.sh')
ROS_PYTHON = '/usr/bin/python3'


def sourced(script, env, shell='sh'):
    return subprocess.run([shell, '-c', script], env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=60)


@unittest.skipIf(sys.version_info >= (3, 12), 'Python 3.12 has no distutils of its own')
class PythonStartupHookTest(unittest.TestCase):
    def env(self, **extra):
        env = dict(os.environ)
        env.pop('SETUPTOOLS_USE_DISTUTILS', None)
        env.update(extra)
        return env

    def test_hook_sets_stdlib_when_unset(self):
        proc = sourced('. "%s"; echo "[$SETUPTOOLS_USE_DISTUTILS]"' % HOOK, self.env())
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(proc.stdout.strip(), '[stdlib]')

    def test_hook_keeps_the_users_value(self):
        proc = sourced('. "%s"; echo "[$SETUPTOOLS_USE_DISTUTILS]"' % HOOK,
                       self.env(SETUPTOOLS_USE_DISTUTILS='local'))
        self.assertEqual(proc.stdout.strip(), '[local]')

    def test_hook_under_set_u(self):
        proc = sourced('set -u; . "%s"; echo "[$SETUPTOOLS_USE_DISTUTILS]"' % HOOK, self.env())
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(proc.stdout.strip(), '[stdlib]')

    def test_devel_space_sources_it(self):
        setup = os.path.join(REPO, '.build', 'devel', 'setup.bash')
        if not os.path.isfile(setup):
            self.skipTest('no devel space at %s (scripts/setup.sh builds it)' % setup)
        proc = sourced('source "%s"; echo "[$SETUPTOOLS_USE_DISTUTILS]"' % setup, self.env(),
                       shell='bash')
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(proc.stdout.strip().splitlines()[-1], '[stdlib]')

    def test_roslaunch_starts_without_setuptools(self):
        if not os.path.exists(ROS_PYTHON):
            self.skipTest('no %s' % ROS_PYTHON)
        probe = 'import sys, roslaunch; print("setuptools" in sys.modules)'

        def loads_setuptools(env):
            proc = subprocess.run([ROS_PYTHON, '-c', probe], env=env, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, universal_newlines=True, timeout=60)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            return proc.stdout.strip() == 'True'

        self.assertFalse(loads_setuptools(self.env(SETUPTOOLS_USE_DISTUTILS='stdlib')))
        # Without it the shim loads setuptools (the cost the hook removes), where the shim is installed.
        if not loads_setuptools(self.env()):
            self.skipTest("this system's setuptools has no distutils shim: nothing to remove")


if __name__ == '__main__':
    unittest.main()
