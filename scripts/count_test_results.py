#!/usr/bin/env python3
"""Counts test cases in catkin's JUnit result files and prints 'N passed, N failed'.

catkin_test_results counts gtest cases twice (suite and cases), so the closing line is made
here from the <testcase> elements themselves. Failing cases are listed by file and name.
Exit code: 0 when nothing failed and at least one test ran, 1 otherwise.
"""
import os
import sys
import xml.etree.ElementTree as ET


def count(results_dir):
    passed, failed, skipped, failures = 0, 0, 0, []
    for root, _, files in os.walk(results_dir):
        for name in sorted(files):
            if not name.endswith('.xml'):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, results_dir)
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
                    failures.append(label)
                elif case.find('skipped') is not None or case.get('status') == 'notrun':
                    skipped += 1
                else:
                    passed += 1
    return passed, failed, skipped, failures


def main():
    passed, failed, skipped, failures = count(sys.argv[1])
    for f in failures:
        print('FAILED ' + f)
    line = '%d passed, %d failed' % (passed, failed)
    if skipped:
        line += ', %d skipped' % skipped
    print(line)
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == '__main__':
    sys.exit(main())
