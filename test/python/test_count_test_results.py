#!/usr/bin/env python3
"""scripts/count_test_results.py, the closing line of `.ci/run`: it counts <testcase> elements
(a gtest case once, not twice as catkin_test_results does), treats a result file without cases
as a failure to run, and lists each failed case with the first lines of its message, so that a
CI log that shows only the summary still says what failed."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
SCRIPT = os.path.join(REPO, 'scripts', 'count_test_results.py')

GTEST = '''<?xml version="1.0" encoding="UTF-8"?>
<testsuites tests="2" failures="1" name="AllTests" time="0.1">
  <testsuite name="Suite" tests="2" failures="1" time="0.1">
    <testcase name="Good" status="run" time="0.01" classname="Suite" />
    <testcase name="Bad" status="run" time="0.02" classname="Suite">
      <failure message="test_x.cpp:12&#x0A;Expected equality of these values:&#x0A;  1&#x0A;  2" type=""><![CDATA[test_x.cpp:12
Expected equality of these values:
  1
  2]]></failure>
    </testcase>
  </testsuite>
</testsuites>
'''

ROSUNIT = '''<?xml version="1.0" encoding="utf-8"?>
<testsuite name="rosunit" tests="2" errors="0" failures="1" time="3.0">
  <testcase classname="__main__.StepTest" name="test_1" time="1.0"></testcase>
  <testcase classname="__main__.StepTest" name="test_4" time="2.0">
    <failure type="AssertionError"><![CDATA[Traceback (most recent call last):
  File "test_step.py", line 120, in test_4
    self.helper()
  File "test_step.py", line 60, in helper
    self.check()
  File "test_step.py", line 70, in check
    self.assertTrue(feedback)
AssertionError: [] is not true
]]></failure>
  </testcase>
</testsuite>
'''


class CountTestResults(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.dir)

    def write(self, name, text):
        with open(os.path.join(self.dir, name), 'w') as f:
            f.write(text)

    def run_script(self):
        p = subprocess.run([sys.executable, SCRIPT, self.dir, '--slowest', '0'],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
        return p.returncode, p.stdout

    def test_counts_cases_and_names_failures_with_their_messages(self):
        self.write('gtest-x.xml', GTEST)
        self.write('rosunit-step.xml', ROSUNIT)
        rc, out = self.run_script()
        self.assertEqual(rc, 1)
        lines = out.splitlines()
        self.assertEqual(lines[-1], '2 passed, 2 failed')
        self.assertIn('FAILED gtest-x.xml: Suite.Bad', lines)
        self.assertIn('    Expected equality of these values:', lines)
        self.assertIn('FAILED rosunit-step.xml: __main__.StepTest.test_4', lines)
        # A long traceback keeps its start and, above all, its end: the assertion.
        self.assertIn('    AssertionError: [] is not true', lines)
        self.assertIn('    Traceback (most recent call last):', lines)
        self.assertIn('    ...', lines)
        self.assertLessEqual(len([l for l in lines if l.startswith('    ')]), 4 + 6)

    def test_all_passing_exits_0(self):
        self.write('rosunit-ok.xml', ROSUNIT.replace(
            ROSUNIT[ROSUNIT.index('<failure'):ROSUNIT.index('</failure>') + 10], ''))
        rc, out = self.run_script()
        self.assertEqual(rc, 0, out)
        self.assertEqual(out.splitlines()[-1], '2 passed, 0 failed')

    def test_a_file_without_cases_is_a_failure(self):
        self.write('rostest-empty.xml', '<testsuite name="x" tests="0"></testsuite>')
        rc, out = self.run_script()
        self.assertEqual(rc, 1)
        self.assertIn('FAILED rostest-empty.xml: no test cases', out)
        self.assertEqual(out.splitlines()[-1], '0 passed, 1 failed')


if __name__ == '__main__':
    unittest.main()
