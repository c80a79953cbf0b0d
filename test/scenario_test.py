#!/usr/bin/env python3
"""A scenario written as data (test/scenarios/*.yaml, docs/scenarios.md) under rostest: the same
runner as `scripts/scenario run`, in rostest's master; one assertion per expectation, each
failure naming the expectation and the measured value."""

import os
import sys
import tempfile
import unittest

import rospy
import rostest

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
from swarm_transport import scenario
from swarm_transport import scenario_format as fmt


def scenario_path(name):
    """An absolute path, or a name (with or without .yaml) under test/scenarios/."""
    if os.path.isabs(name):
        return name
    if not name.endswith('.yaml'):
        name += '.yaml'
    return os.path.join(ROOT, 'test', 'scenarios', name)


class Scenario(unittest.TestCase):

    def test_expectations_hold(self):
        s = fmt.load(scenario_path(rospy.get_param('~file')))
        recorder = scenario.Recorder()
        directory = tempfile.mkdtemp(prefix='st_scenario_test_')
        first = scenario.run_once(s, recorder, os.path.join(directory, 'run1'))
        second = scenario.run_once(s, recorder, os.path.join(directory, 'run2')) \
            if scenario.needs_second_run(s) else None
        results = scenario.evaluate(s, first, second)
        for ok, what, measured in results:
            rospy.loginfo('%s  %s: %s', 'PASS' if ok else 'FAIL', what, measured)
        failed = ['%s: %s' % (what, measured) for ok, what, measured in results if not ok]
        self.assertEqual(failed, [], '%s: %d of %d expectations failed'
                         % (s['name'], len(failed), len(results)))


if __name__ == '__main__':
    rospy.init_node('scenario_test')
    rostest.rosrun('swarm_transport', 'scenario', Scenario, sys.argv)
