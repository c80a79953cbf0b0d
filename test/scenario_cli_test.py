#!/usr/bin/env python3
"""scripts/scenario's verdicts (issue 14): a deliberately broken scenario (an impossible
deadline) runs and exits 1 naming the failed expectation and its measured value, while the one
that holds is PASS; a malformed file exits 2 naming its line and key before anything starts."""

import os
import subprocess
import sys
import unittest

import rospy
import rostest

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))


def scenario(*args):
    env = dict(os.environ, ST_NO_BUILD='1')
    proc = subprocess.run([os.path.join(ROOT, 'scripts', 'scenario')] + list(args), env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=rospy.get_param('~timeout_s'))
    return proc.returncode, proc.stdout


class ScenarioCli(unittest.TestCase):

    def test_an_impossible_deadline_fails_by_name(self):
        code, out = scenario('run', os.path.join(ROOT, 'test', 'scenarios', 'broken',
                                                 'impossible_deadline.yaml'))
        self.assertEqual(code, 1, out)
        self.assertIn('FAIL  expect[1] mission_state by_tick=20 mission=7 state=DONE', out)
        self.assertIn('PASS  expect[0] in_arena', out)
        self.assertIn('1 of 2 expectations hold', out)

    def test_a_malformed_file_names_line_and_key_before_starting(self):
        path = os.path.join(ROOT, 'test', 'scenarios', 'broken', 'malformed.yaml')
        for cmd in ('check', 'run'):
            code, out = scenario(cmd, path)
            self.assertEqual(code, 2, out)
            self.assertIn('malformed.yaml:9: events[0].freeze: must be [from, to)', out)
            self.assertNotIn('[scenario]', out)  # nothing was started


if __name__ == '__main__':
    rospy.init_node('scenario_cli_test')
    rostest.rosrun('swarm_transport', 'scenario_cli', ScenarioCli, sys.argv)
