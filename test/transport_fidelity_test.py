#!/usr/bin/env python3
"""Transport as the thesis measured it (issue 9): swarm mode on three fixed seeds finishes each
transport within the tolerances of the .test file, and formation mode carries the object as one
body (slip, time). Runs the experiment runner and asserts on its per-run rows."""

import csv
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))


def param(name):
    return rospy.get_param('~' + name)


class TransportFidelity(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='st_transport_fidelity_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def runs(self, preset):
        """Runs `preset`'s setting on the .test's seeds; returns the per-run rows."""
        out = os.path.join(self.tmp, preset)
        env = dict(os.environ, ST_NO_BUILD='1')  # rostest runs on a built workspace
        proc = subprocess.run(
            [os.path.join(ROOT, 'scripts', 'experiment'), 'run', preset, '--settings',
             param('setting'), '--runs', str(param('runs')), '--seed-base',
             str(param('seed_base')), '--jobs', '2', '--deploy', 'host_sim', '--out', out],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
            timeout=param('timeout_s'))
        text = proc.stdout.decode(errors='replace')
        rospy.loginfo('%s:\n%s', preset, text)
        self.assertEqual(proc.returncode, 0, text)
        with open(os.path.join(out, 'runs.csv')) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), param('runs'), text)
        return rows

    def check(self, rows, min_ticks, max_ticks, max_slip):
        for r in rows:
            what = 'seed %s: %s' % (r['seed'], {k: r[k] for k in (
                'end', 'transport_ticks', 'slip_per_robot_m', 'object_error_m')})
            self.assertTrue(r['transport_ticks'], 'no transport finished, ' + what)
            ticks = float(r['transport_ticks'])
            self.assertGreaterEqual(ticks, min_ticks, what)
            self.assertLessEqual(ticks, max_ticks, what)
            self.assertLessEqual(float(r['slip_per_robot_m']), max_slip, what)
            self.assertLessEqual(float(r['object_error_m']), param('goal_tolerance_m') + 1e-6,
                                 what)

    def test_swarm_mode_transports_like_the_thesis_on_every_seed(self):
        self.check(self.runs(param('swarm_preset')), param('swarm_min_ticks'),
                   param('swarm_max_ticks'), param('swarm_max_slip_m'))

    def test_formation_mode_carries_the_object_as_one_body(self):
        # At least the straight distance at full speed: a formation cannot be faster.
        self.check(self.runs(param('formation_preset')), param('swarm_min_ticks'),
                   param('formation_max_ticks'), param('formation_max_slip_m'))


if __name__ == '__main__':
    rospy.init_node('transport_fidelity_test')
    rostest.rosrun('swarm_transport', 'transport_fidelity', TransportFidelity, sys.argv)
