#!/usr/bin/env python3
"""One lock-step tick, two drivers: the batch engine (experiment_batch: the lock-step engine,
the robots' sessions, the dispatcher's book and the recorder's bookkeeping in one process, no
master) and a launched run (swarm.launch deploy:=host_sim: the simulator drives the same
engine over ROS) give the same run for the same presets and seeds - every robot's pose at every
tick (trace.csv) and every row of the recorder's files, byte for byte."""

import csv
import json
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


def lines(path):
    with open(path) as f:
        return f.read().splitlines()


def trace_by_tick(path):
    """trace.csv as {tick: [row, ...]} (rows in file order)."""
    out = {}
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        assert header == ['tick', 'robot_id', 'x', 'y', 'heading_deg'], header
        for row in reader:
            out.setdefault(int(row[0]), []).append(','.join(row))
    return out


class BatchEquivalence(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix='st_batch_equivalence_')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def run_preset(self, preset, settings, engine):
        out = os.path.join(self.tmp, engine, preset)
        args = ['run', preset, '--runs', str(param('runs')), '--jobs', '2', '--seed-base',
                str(param('seed_base')), '--settings', ','.join(settings), '--out', out,
                '--trace', '--engine', engine]
        if engine == 'launch':
            args += ['--deploy', 'host_sim']
        env = dict(os.environ, ST_NO_BUILD='1')  # rostest runs on a built workspace
        proc = subprocess.run([os.path.join(ROOT, 'scripts', 'experiment')] + args,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                              timeout=param('timeout_s'))
        text = proc.stdout.decode(errors='replace')
        rospy.loginfo('scripts/experiment %s:\n%s', ' '.join(args), text)
        self.assertEqual(proc.returncode, 0, 'scripts/experiment %s failed:\n%s'
                         % (' '.join(args), text))
        return out

    def compare_traces(self, launched_dir, batch_dir, where, last_tick):
        """Every tick the batch run has up to `last_tick`: the same poses of the same robots."""
        ours = trace_by_tick(os.path.join(batch_dir, 'trace.csv'))
        theirs = trace_by_tick(os.path.join(launched_dir, 'trace.csv'))
        ticks = [t for t in sorted(ours) if t <= last_tick]
        self.assertEqual(ticks, list(range(0, last_tick + 1)), '%s: batch trace ticks' % where)
        robots = 0
        for t in ticks:
            self.assertIn(t, theirs, '%s: the launched trace has no tick %d' % (where, t))
            self.assertEqual(theirs[t], ours[t], '%s: tick %d' % (where, t))
            robots += len(ours[t])
        self.assertGreater(robots, len(ticks), where)  # more than one robot per tick
        return len(ticks)

    def test_same_run_in_both_drivers(self):
        compared = ticks = arrived = 0
        for preset, settings, kind in (
                (param('flocking_preset'), param('flocking_settings').split(), 'flocking'),
                (param('leader_preset'), param('leader_settings').split(), 'leader'),
                (param('copies_preset'), param('copies_settings').split(), 'leader'),
                (param('transport_preset'), param('transport_settings').split(), 'transport')):
            launched = self.run_preset(preset, settings, 'launch')
            batch = self.run_preset(preset, settings, 'batch')
            for s in settings:
                for k in range(param('runs')):
                    a = os.path.join(launched, 'raw', s, 'run_%d' % k)
                    b = os.path.join(batch, 'raw', s, 'run_%d' % k)
                    where = '%s/%s/run_%d' % (preset, s, k)
                    with open(os.path.join(b, 'result.json')) as f:
                        rb = json.load(f)
                    with open(os.path.join(a, 'result.json')) as f:
                        ra = json.load(f)
                    if kind == 'flocking':
                        # Both run to max_ticks: every file equal.
                        for f in ('swarm_count.csv', 'run.csv', 'missions.csv'):
                            self.assertEqual(lines(os.path.join(a, f)),
                                             lines(os.path.join(b, f)), '%s %s' % (where, f))
                        ticks += self.compare_traces(a, b, where, rb['ticks'] - 1)
                        compared += 1
                        continue
                    for key in ('end', 'phases', 'last_status'):
                        self.assertEqual(ra[key], rb[key], '%s %s' % (where, key))
                    arrived += rb['end'] == 'DONE'
                    self.assertEqual(lines(os.path.join(a, 'missions.csv')),
                                     lines(os.path.join(b, 'missions.csv')), where)
                    # A launched run ticks on after the mission ended until its runner stops
                    # it: the batch run's samples and poses are its first ones.
                    ours = lines(os.path.join(b, 'swarm_count.csv'))
                    self.assertGreater(len(ours), 1, '%s swarm_count.csv' % where)
                    theirs = lines(os.path.join(a, 'swarm_count.csv'))
                    self.assertEqual(theirs[:len(ours)], ours, '%s swarm_count.csv' % where)
                    if kind == 'leader' and rb['end'] == 'DONE':
                        self.assertEqual(lines(os.path.join(a, 'leader_track.csv')),
                                         lines(os.path.join(b, 'leader_track.csv')), where)
                    ticks += self.compare_traces(a, b, where, rb['ticks'] - 1)
                    compared += 1
        expected = param('runs') * sum(len(param(p).split()) for p in (
            'flocking_settings', 'leader_settings', 'copies_settings', 'transport_settings'))
        self.assertEqual(compared, expected)
        self.assertGreater(arrived, 0, 'no mission ended DONE: the comparison was partial')
        rospy.loginfo('batch and launched runs equal: %d runs, %d ticks of poses', compared,
                      ticks)


if __name__ == '__main__':
    rospy.init_node('batch_equivalence_test')
    rostest.rosrun('swarm_transport', 'batch_equivalence', BatchEquivalence, sys.argv)
