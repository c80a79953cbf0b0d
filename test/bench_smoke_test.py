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


def run_bench(args):
    """scripts/bench with these arguments: (its output, the RESULT line's dict); asserts the
    exit status and that the last line is the one RESULT line."""
    # The package folder in the workspace links to the repository: scripts/ must be
    # reached through its real path so that it finds the workspace.
    pkg = rospkg.RosPack().get_path('swarm_transport')
    bench = os.path.realpath(os.path.join(pkg, 'scripts', 'bench'))
    env = os.environ.copy()
    env.pop('ROS_MASTER_URI', None)  # the bench starts its own private master
    p = subprocess.run([bench, '--no-build'] + args, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, env=env, timeout=rospy.get_param('~timeout_s'))
    out = p.stdout.decode(errors='replace')
    case = unittest.TestCase()
    case.assertEqual(p.returncode, 0, out)
    lines = out.strip().splitlines()
    case.assertTrue(lines[-1].startswith('RESULT '), out)
    case.assertEqual(sum(1 for l in lines if l.startswith('RESULT ')), 1, out)
    return out, dict(item.split('=', 1) for item in lines[-1].split()[1:])


class BenchSmoke(unittest.TestCase):

    def test_result_line_is_complete_and_sane(self):
        robots = rospy.get_param('~robots')
        clock = rospy.get_param('~clock', 'both')
        out_csv = tempfile.NamedTemporaryFile(suffix='.csv', delete=False).name
        out, result = run_bench(
            ['--robots', str(robots), '--clock', clock,
             '--deploy', rospy.get_param('~deploy'), '--comm', 'local',
             '--seconds', str(rospy.get_param('~seconds')),
             '--warmup', str(rospy.get_param('~warmup')), '--csv', out_csv,
             '--chain-hops', str(rospy.get_param('~chain_hops'))])
        lines = out.strip().splitlines()
        for key in KEYS:
            self.assertIn(key, result, lines[-1])
        self.assertEqual(int(result['robots']), robots)
        self.assertEqual(result['clock'], clock)
        self.assertEqual(result['deploy'], rospy.get_param('~deploy'))
        # The run used the configuration asked for (the option reaches the measured child).
        self.assertEqual(result['neighbourhood'], 'chain', lines[-1])
        self.assertEqual(int(result['chain_hops']), rospy.get_param('~chain_hops'), lines[-1])
        for key in PERCENTAGES:
            value = float(result[key])
            self.assertTrue(0.0 <= value <= 100.0, '%s=%s' % (key, value))
        for key in POSITIVE:
            if key == 'lockstep_ticks_per_s' and clock == 'realtime':
                self.assertEqual(result[key], 'na', lines[-1])
                continue
            value = float(result[key])
            self.assertTrue(math.isfinite(value) and value > 0.0, '%s=%s' % (key, value))
        self.assertEqual(int(result['robots_ticking']), robots, lines[-1])
        with open(out_csv) as f:
            rows = list(csv.DictReader(f))
        os.unlink(out_csv)
        self.assertEqual(sorted(r['clock'] for r in rows),
                         ['lockstep', 'realtime'] if clock == 'both' else [clock])
        self.assertTrue(all(r['ok'] == 'True' for r in rows), rows)


BATCH_KEYS = ('robots', 'deploy', 'ticks', 'arena_m', 'lockstep_ticks_per_s',
              'cpu_us_per_robot_tick', 'cpu_s', 'ticking_s', 'startup_s', 'files_s', 'wall_s',
              'peak_rss_mb', 'final_swarm_count', 'runs_ok')


class BenchBatchSmoke(unittest.TestCase):
    """--deploy batch: one flocking job through experiment_batch (no master of its own)."""

    def test_batch_result_line_is_complete_and_sane(self):
        robots, ticks = rospy.get_param('~robots'), rospy.get_param('~ticks')
        _, result = run_bench(['--deploy', 'batch', '--robots', str(robots),
                               '--ticks', str(ticks)])
        for key in BATCH_KEYS:
            self.assertIn(key, result)
            self.assertNotEqual(result[key], 'na', key)
        self.assertEqual(int(result['robots']), robots)
        self.assertEqual(result['deploy'], 'batch')
        self.assertEqual(result['clock'], 'lockstep')
        self.assertEqual(int(result['ticks']), ticks)
        self.assertEqual(int(result['runs_ok']), 1)
        # The thesis's density: 25 robots per 11.09 m room.
        self.assertAlmostEqual(float(result['arena_m']), 11.088889 * math.sqrt(robots / 25.0),
                               places=3)
        for key in ('lockstep_ticks_per_s', 'ticking_s', 'cpu_s', 'peak_rss_mb'):
            value = float(result[key])
            self.assertTrue(math.isfinite(value) and value > 0.0, '%s=%s' % (key, value))
        for key in ('startup_s', 'files_s', 'cpu_us_per_robot_tick'):
            value = float(result[key])
            self.assertTrue(math.isfinite(value) and value >= 0.0, '%s=%s' % (key, value))
        # The phases lie inside the job's wall time; the ticks' rate is the ticks over them.
        self.assertLessEqual(float(result['startup_s']) + float(result['ticking_s']) +
                             float(result['files_s']), float(result['wall_s']) + 1e-3)
        self.assertAlmostEqual(float(result['lockstep_ticks_per_s']) * float(result['ticking_s']),
                               ticks, delta=0.01 * ticks)
        self.assertTrue(1 <= int(result['final_swarm_count']) <= robots, result)


if __name__ == '__main__':
    rospy.init_node('bench_smoke_test')
    case = BenchBatchSmoke if rospy.get_param('~deploy') == 'batch' else BenchSmoke
    rostest.rosrun('swarm_transport', 'bench_smoke', case, sys.argv)
