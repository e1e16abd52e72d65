#!/usr/bin/env python3
"""Counts test cases in catkin's JUnit result files and prints 'N passed, N failed'.

catkin_test_results counts gtest cases twice (suite and cases), so the closing line is made
here from the <testcase> elements themselves. Failing cases are listed by file and name, each
with the first lines of its failure message (a CI log may be all a reader has of a failure).
Before them, where the time goes: the slowest test files (a rostest's file holds its whole
run, launch included) and the slowest test cases.

  count_test_results.py RESULTS_DIR [--slowest N]   (N = 10 by default, 0: no tables)

Exit code: 0 when nothing failed and at least one test ran, 1 otherwise.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

RUNNER = 'rostest.runner.RosTest'  # rostest's own case: the whole rostest, not a test case


def result_files(results_dir):
    for root, _, files in os.walk(results_dir):
        for name in sorted(files):
            if name.endswith('.xml'):
                path = os.path.join(root, name)
                yield path, os.path.relpath(path, results_dir)


MESSAGE_LINES = 6


def failure_text(case):
    """The first lines of a failed case's message: the failure's or error's text (a Python
    traceback, gtest's expectation) or, without one, its message attribute."""
    for tag in ('failure', 'error'):
        element = case.find(tag)
        if element is None:
            continue
        text = (element.text or '').strip() or (element.get('message') or '').strip()
        lines = [l.rstrip() for l in text.splitlines() if l.strip()]
        if len(lines) > MESSAGE_LINES:  # the end of a traceback says most
            lines = lines[:2] + ['...'] + lines[-(MESSAGE_LINES - 3):]
        return lines
    return []


def count(results_dir):
    passed, failed, skipped, failures = 0, 0, 0, []
    for path, rel in result_files(results_dir):
        try:
            tree = ET.parse(path)
        except ET.ParseError as e:
            failed += 1
            failures.append('%s: unreadable result file (%s)' % (rel, e))
            continue
        cases = list(tree.getroot().iter('testcase'))
        if not cases:  # a result file without cases is a failure to run
            failed += 1
            failures.append('%s: no test cases' % rel)
            continue
        for case in cases:
            label = '%s: %s.%s' % (rel, case.get('classname', ''), case.get('name', ''))
            if case.find('failure') is not None or case.find('error') is not None:
                failed += 1
                failures.append('\n'.join([label] + ['    ' + l for l in failure_text(case)]))
            elif case.find('skipped') is not None or case.get('status') == 'notrun':
                skipped += 1
            else:
                passed += 1
    return passed, failed, skipped, failures


def _seconds(element):
    try:
        return float(element.get('time', '0') or 0)
    except ValueError:
        return 0.0


def timings(results_dir):
    """([(seconds, test file)], [(seconds, test case)]). A test file is a rostest (its
    rostest-*.xml: the test node's run, from its start to its end, the launch's own start-up
    and shutdown not included), a gtest binary or a nosetests file; the rosunit-*.xml of a
    rostest's test node holds its cases, not another file."""
    files, cases = [], []
    for path, rel in result_files(results_dir):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError:
            continue
        name = os.path.basename(rel)
        if not name.startswith('rosunit-'):
            # nosetests' suites have no time: their cases' add up.
            seconds = _seconds(root) if root.get('time') else sum(
                _seconds(c) for c in root.iter('testcase'))
            files.append((seconds, rel))
        for case in root.iter('testcase'):
            if case.get('classname') == RUNNER:
                continue
            cases.append((_seconds(case), '%s: %s.%s' % (rel, case.get('classname', ''),
                                                         case.get('name', ''))))
    return sorted(files, reverse=True), sorted(cases, reverse=True)


def table(title, rows, n):
    lines = [title]
    for seconds, label in rows[:n]:
        lines.append('  %7.1f s  %s' % (seconds, label))
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('results_dir')
    parser.add_argument('--slowest', type=int, default=10, metavar='N',
                        help='list the N slowest test files and cases (0: none)')
    args = parser.parse_args()
    passed, failed, skipped, failures = count(args.results_dir)
    if args.slowest > 0:
        files, cases = timings(args.results_dir)
        total = sum(s for s, _ in files)
        print('\n'.join(table('slowest %d of %d test files (%.0f s in all; catkin runs as many at '
                              'once as make has jobs):' % (min(args.slowest, len(files)),
                                                            len(files), total),
                              files, args.slowest)))
        print('\n'.join(table('slowest %d of %d test cases:' % (min(args.slowest, len(cases)),
                                                                len(cases)),
                              cases, args.slowest)))
    for f in failures:
        print('FAILED ' + f)
    line = '%d passed, %d failed' % (passed, failed)
    if skipped:
        line += ', %d skipped' % skipped
    print(line)
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == '__main__':
    sys.exit(main())
