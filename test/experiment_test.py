#!/usr/bin/env python3
"""The experiment runner (scripts/experiment) end to end: two invocations of the smoke preset
(each run in its own private master, started by the runner) give summary.csv with the
documented columns, finite values in range, the raw per-run files and the PNG plots, and the
same numbers twice; `report` writes a results page. The aggregation itself (trimmed mean,
series on the 10 s grid, aborted missions) on hand-made CSVs and the presets' validation are
plain unit tests in test/python/ (no ROS master)."""

import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospy
import rostest

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
from swarm_transport import experiment_presets as presets

SUMMARY_HEADER = ['setting', 'metric', 'mean', 'median', 'trimmed_mean', 'runs']
COUNT_METRICS = ('final_swarm_count', 'mean_swarm_count', 'initial_swarm_count',
                 'final_largest_swarm')


def param(name):
    return rospy.get_param('~' + name)


def read_summary(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


class ExperimentRunner(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='st_experiment_test_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def run_experiment(self, *args):
        env = dict(os.environ, ST_NO_BUILD='1')  # rostest runs on a built workspace
        proc = subprocess.run([os.path.join(ROOT, 'scripts', 'experiment')] + list(args),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                              timeout=param('timeout_s'))
        out = proc.stdout.decode(errors='replace')
        rospy.loginfo('scripts/experiment %s:\n%s', ' '.join(args), out)
        self.assertEqual(proc.returncode, 0, 'scripts/experiment %s failed:\n%s'
                         % (' '.join(args), out))
        return out

    def smoke(self, name, *extra):
        out_dir = os.path.join(self.tmp, name, param('preset'))
        text = self.run_experiment('run', param('preset'), '--runs', str(param('runs')),
                                   '--jobs', str(param('jobs')), '--seed-base',
                                   str(param('seed_base')), '--out', out_dir, *extra)
        return out_dir, text

    def check_trace(self, run_dir):
        """--trace: every robot's pose at every tick from tick 0 on, inside the arena."""
        path = os.path.join(run_dir, 'trace.csv')
        self.assertTrue(os.path.isfile(path), path)
        with open(path) as f:
            reader = csv.DictReader(f)
            self.assertEqual(reader.fieldnames, ['tick', 'robot_id', 'x', 'y', 'heading_deg'])
            rows = list(reader)
        per_tick = {}
        for r in rows:
            per_tick.setdefault(int(r['tick']), set()).add(int(r['robot_id']))
            x, y, h = float(r['x']), float(r['y']), float(r['heading_deg'])
            self.assertTrue(0.0 <= x <= param('world_size_m') and
                            0.0 <= y <= param('world_size_m'), r)
            self.assertTrue(0.0 <= h < 360.0, r)
        ticks = sorted(per_tick)
        self.assertEqual(ticks[0], 0, path)
        self.assertEqual(ticks, list(range(ticks[0], ticks[-1] + 1)), 'a tick is missing')
        self.assertGreaterEqual(ticks[-1], param('max_ticks') - 1, path)
        for tick, ids in per_tick.items():
            self.assertEqual(ids, set(range(param('robots'))), 'tick %d' % tick)

    def test_smoke_preset_end_to_end_and_reproducible(self):
        first, text = self.smoke('a')
        settings = param('settings').split()
        # The default engine: every run in an experiment_batch process, no ROS master.
        self.assertIn('RESULT preset=%s deploy=batch runs=%d ' % (param('preset'),
                                                     param('runs') * len(settings)), text)
        header, rows = read_summary(os.path.join(first, 'summary.csv'))
        self.assertEqual(header, SUMMARY_HEADER)
        robots = param('robots')
        self.assertEqual(sorted({r['setting'] for r in rows}), sorted(settings))
        for r in rows:
            where = '%s/%s' % (r['setting'], r['metric'])
            self.assertEqual(int(r['runs']), param('runs'), where)
            vals = [float(r[c]) for c in ('mean', 'median', 'trimmed_mean')]
            for v in vals:
                self.assertTrue(math.isfinite(v), where)
            if r['metric'] in COUNT_METRICS or r['metric'].startswith('swarm_count_t'):
                for v in vals:
                    self.assertTrue(1.0 <= v <= robots, '%s = %s outside [1, %d]'
                                    % (where, v, robots))
            if r['metric'] == 'swarm_count_slope_per_h':
                for v in vals:
                    self.assertLessEqual(abs(v), param('max_abs_slope_per_h'), where)
        for s in settings:
            metrics = {r['metric'] for r in rows if r['setting'] == s}
            for m in presets.METRICS['flocking']:
                self.assertIn(m, metrics)
            self.assertIn('swarm_count_t0', metrics)
            self.assertIn('swarm_count_t100', metrics)
            seeds = set()
            for k in range(param('runs')):
                run_dir = os.path.join(first, 'raw', s, 'run_%d' % k)
                for f in ('swarm_count.csv', 'run.csv', 'config.yaml', 'job.json',
                          'result.json'):
                    self.assertTrue(os.path.isfile(os.path.join(run_dir, f)),
                                    '%s missing in %s' % (f, run_dir))
                with open(os.path.join(run_dir, 'result.json')) as f:
                    seeds.add(json.load(f)['seed'])
            self.assertEqual(seeds, {param('seed_base') + k for k in range(param('runs'))})
        for png in ('swarm_count.png', 'metrics.png'):
            path = os.path.join(first, png)
            self.assertTrue(os.path.isfile(path), path)
            with open(path, 'rb') as f:
                self.assertEqual(f.read(8), b'\x89PNG\r\n\x1a\n', path)
            self.assertGreater(os.path.getsize(path), 2000, path)

        # Traced: the same numbers (the tracer only listens) and a trace of every tick.
        second, _ = self.smoke('b', '--trace')
        for s in settings:
            for k in range(param('runs')):
                self.check_trace(os.path.join(second, 'raw', s, 'run_%d' % k))
        _, again = read_summary(os.path.join(second, 'summary.csv'))
        self.assertEqual([(r['setting'], r['metric']) for r in rows],
                         [(r['setting'], r['metric']) for r in again])
        tol = param('identical_tolerance')
        for a, b in zip(rows, again):
            for c in ('mean', 'median', 'trimmed_mean'):
                self.assertLessEqual(abs(float(a[c]) - float(b[c])), tol,
                                     '%s/%s %s: %s then %s' % (a['setting'], a['metric'], c,
                                                               a[c], b[c]))

        page = os.path.join(self.tmp, 'results.md')
        self.run_experiment('report', os.path.join(self.tmp, 'a'), '--out', page)
        with open(page) as f:
            text = f.read()
        self.assertIn('`%s`' % param('preset'), text)
        self.assertIn('swarm_count.png', text)
        self.assertTrue(os.path.isfile(os.path.join(self.tmp, 'results', param('preset'),
                                                    'swarm_count.png')))

    def test_transport_repeats_in_every_deployment(self):
        """A transport preset launched in one process per robot and in one process for all
        (host_sim), and in the batch engine: the same seeds give the same missions.csv rows,
        byte for byte. Under load a mission used to start at a scheduling-dependent tick (a
        first leader waited tick by tick for its subscribers); two runs at a time (--jobs 2)
        keep both cores busy."""
        preset = param('transport_preset')
        rows = {}
        for deploy in ('process', 'host_sim', 'batch'):
            out = os.path.join(self.tmp, 'deploy_' + deploy, preset)
            engine = ['--engine', 'batch'] if deploy == 'batch' else [
                '--engine', 'launch', '--deploy', deploy]
            text = self.run_experiment('run', preset, '--runs', '1', '--jobs', '2',
                                       '--out', out, *engine)
            self.assertIn('RESULT preset=%s deploy=%s ' % (preset, deploy), text)
            for setting in param('transport_settings').split():
                run_dir = os.path.join(out, 'raw', setting, 'run_0')
                with open(os.path.join(run_dir, 'result.json')) as f:
                    self.assertEqual(json.load(f)['end'], 'DONE', run_dir)
                with open(os.path.join(run_dir, 'missions.csv')) as f:
                    lines = f.read().splitlines()
                self.assertEqual(len(lines), 2, run_dir)  # header + the mission
                row = dict(zip(lines[0].split(','), lines[1].split(',')))
                self.assertEqual(row['final_state'], 'DONE', run_dir)
                self.assertEqual(row['queued_tick'], '0', run_dir)  # submitted before tick 0
                self.assertEqual(row['gathering_tick'], '0', run_dir)
                self.assertGreater(int(row['transport_ticks']), 0, run_dir)
                self.assertTrue(0.0 <= float(row['leader_contact']) <= 1.0, run_dir)
                rows.setdefault(setting, []).append(lines[1])
        for setting, (process, host_sim, batch) in rows.items():
            self.assertEqual(process, host_sim, '%s: process and host_sim differ' % setting)
            self.assertEqual(batch, host_sim, '%s: batch and host_sim differ' % setting)


if __name__ == '__main__':
    rospy.init_node('experiment_test')
    rostest.rosrun('swarm_transport', 'experiment_runner', ExperimentRunner, sys.argv)
