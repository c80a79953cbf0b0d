#!/usr/bin/env python3
"""scripts/bench runs end to end at a small scale: its last line is one RESULT line with every
key, the rates are positive and the percentages lie in [0, 100]; the CSV has a row per run."""

import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rospy
import rostest

KEYS = ('robots', 'clock', 'deploy', 'comm', 'tick_hz', 'late_pct', 'delivered_pct', 'cpu_pct',
        'rss_mb_per_robot', 'lockstep_ticks_per_s', 'startup_s')
PERCENTAGES = ('late_pct', 'delivered_pct', 'cpu_pct')
POSITIVE = ('tick_hz', 'rss_mb_per_robot', 'lockstep_ticks_per_s', 'startup_s')


class BenchSmoke(unittest.TestCase):

    def test_result_line_is_complete_and_sane(self):
        robots = rospy.get_param('~robots')
        # The package folder in the workspace links to the repository: scripts/ must be
        # reached through its real path so that it finds the workspace.
        pkg = rospkg.RosPack().get_path('swarm_transport')
        bench = os.path.realpath(os.path.join(pkg, 'scripts', 'bench'))
        out_csv = tempfile.NamedTemporaryFile(suffix='.csv', delete=False).name
        env = os.environ.copy()
        env.pop('ROS_MASTER_URI', None)  # the bench starts its own private master
        p = subprocess.run(
            [bench, '--no-build', '--robots', str(robots), '--clock', 'both',
             '--deploy', rospy.get_param('~deploy'), '--comm', 'local',
             '--seconds', str(rospy.get_param('~seconds')),
             '--warmup', str(rospy.get_param('~warmup')), '--csv', out_csv,
             '--chain-hops', str(rospy.get_param('~chain_hops'))],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
            timeout=rospy.get_param('~timeout_s'))
        out = p.stdout.decode(errors='replace')
        self.assertEqual(p.returncode, 0, out)
        lines = out.strip().splitlines()
        self.assertTrue(lines[-1].startswith('RESULT '), out)
        self.assertEqual(sum(1 for l in lines if l.startswith('RESULT ')), 1, out)
        result = dict(item.split('=', 1) for item in lines[-1].split()[1:])
        for key in KEYS:
            self.assertIn(key, result, lines[-1])
        self.assertEqual(int(result['robots']), robots)
        self.assertEqual(result['clock'], 'both')
        # The run used the configuration asked for (the option reaches the measured child).
        self.assertEqual(result['neighbourhood'], 'chain', lines[-1])
        self.assertEqual(int(result['chain_hops']), rospy.get_param('~chain_hops'), lines[-1])
        for key in PERCENTAGES:
            value = float(result[key])
            self.assertTrue(0.0 <= value <= 100.0, '%s=%s' % (key, value))
        for key in POSITIVE:
            value = float(result[key])
            self.assertTrue(math.isfinite(value) and value > 0.0, '%s=%s' % (key, value))
        self.assertEqual(int(result['robots_ticking']), robots, lines[-1])
        with open(out_csv) as f:
            rows = list(csv.DictReader(f))
        os.unlink(out_csv)
        self.assertEqual(sorted(r['clock'] for r in rows), ['lockstep', 'realtime'])
        self.assertTrue(all(r['ok'] == 'True' for r in rows), rows)


if __name__ == '__main__':
    rospy.init_node('bench_smoke_test')
    rostest.rosrun('swarm_transport', 'bench_smoke', BenchSmoke, sys.argv)
