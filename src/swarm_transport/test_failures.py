#!/usr/bin/env python3
"""Prints, for every failed or erroneous test case in a catkin test_results folder, the test
name and its failure message (not the launched nodes' output), so that a CI log says why."""

import os
import sys
import xml.etree.ElementTree as ET


def main(root):
    for folder, _, files in sorted(os.walk(root)):
        for name in sorted(files):
            if not name.endswith('.xml'):
                continue
            path = os.path.join(folder, name)
            try:
                tree = ET.parse(path)
            except ET.ParseError as e:
                print('%s: unreadable result file (%s)' % (path, e))
                continue
            for case in tree.iter('testcase'):
                for kind in ('failure', 'error'):
                    for f in case.findall(kind):
                        text = (f.get('message') or '') + '\n' + (f.text or '')
                        lines = [ln for ln in text.strip().splitlines() if ln.strip()]
                        print('--- %s %s: %s.%s' % (name, kind.upper(), case.get('classname'),
                                                     case.get('name')))
                        for ln in lines[-40:]:
                            print('    ' + ln)


if __name__ == '__main__':
    main(sys.argv[1])
