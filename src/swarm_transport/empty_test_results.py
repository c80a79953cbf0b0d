"""Finds rostests that ran no test case: a rosunit result file with no <testsuite>, or one with
tests="0" (e.g. a test class that broke the runner, which rostest still reports as SUCCESS).
Writes a junit file with one failure per such rostest, so that catkin_test_results counts them.
usage: empty_test_results.py RESULTS_DIR OUT_XML"""

import glob
import os
import sys
import xml.etree.ElementTree as ET


def main():
    results, out = sys.argv[1], sys.argv[2]
    empty = []
    for path in sorted(glob.glob(os.path.join(results, '**', 'rosunit-*.xml'), recursive=True)):
        try:
            root = ET.parse(path).getroot()
            tests = int(root.get('tests', '0')) if root.tag == 'testsuite' else sum(
                int(s.get('tests', '0')) for s in root.iter('testsuite'))
        except (ET.ParseError, ValueError):
            tests = 0
        if tests == 0:
            empty.append(os.path.basename(path)[len('rosunit-'):-len('.xml')])
    cases = ''.join('<testcase classname="rostest" name="%s_ran_tests"><failure message="the '
                    'rostest %s ran no test case (its runner broke)"/></testcase>' % (n, n)
                    for n in empty)
    if not empty:
        cases = '<testcase classname="rostest" name="every_rostest_ran_tests"/>'
    with open(out, 'w') as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n<testsuite name="ran_tests" '
                'tests="%d" failures="%d" errors="0">%s</testsuite>\n'
                % (max(1, len(empty)), len(empty), cases))
    for n in empty:
        print('rostest %s ran no test case' % n)
    return 0


if __name__ == '__main__':
    sys.exit(main())
