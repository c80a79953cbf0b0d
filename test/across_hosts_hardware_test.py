#!/usr/bin/env python3
"""The hardware deployment across hosts (issue 28, item 4): the core (master, core.launch's
positions node and dispatcher, the stand-in's bases) in one network namespace, the robot
processes (robots.launch hardware:=true) split over two others, so that poses, positions and
missions cross the veth links. Two cases, each a swarm of its own:
  - a rate-limited link: what each robot host sends the other host at most `rate` (tbf); the
    thesis mission ends DONE. Probes in both robot namespaces time every robot's announcements
    on both sides (the namespaces share one clock): the delay between the hosts, and the robots'
    own ~diagnostics say which share of the positions in their rounds arrived within a tick.
  - a partition: host b's link down for `down_s` during TRANSPORT; its mission members are named
    lost, the mission goes on (or ABORTS naming them), every robot still ticks, and once the link
    is back the core hears every robot again and host b's robots take a second transport to DONE.
Needs root (CAP_NET_ADMIN) for `ip netns`; without it the test is skipped and says why."""

import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import rospkg
import rospy
import rostest

from netns_hosts import NetHosts, Unavailable

THESIS = '7,0,12,3,7:7:2:2,3,3'  # config/missions/thesis_transport.yaml
NAMES = ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE']


def g(key):
    return rospy.get_param('~' + key)


def quantile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(q * len(s)))] if s else float('nan')


def read_probe(path):
    """{(id, x, y, angle): first arrival wall} of the announcements seen once there."""
    seen, twice = {}, set()
    with open(path, errors='replace') as f:
        for line in f:
            if len(line.split()) != 5:
                continue  # the last line, cut by the probe's stop
            t, rid, x, y, a = line.split()
            key = (int(rid), x, y, a)
            if key in seen:
                twice.add(key)
            else:
                seen[key] = float(t)
    return seen, twice


class Swarm(unittest.TestCase):
    """A hardware swarm across three namespaces: the core's nodes, robots [0, split) on host a
    and the rest on host b."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='across_hosts_hw_')
        self.addCleanup(shutil.rmtree, self.tmp, True)
        try:
            self.net = NetHosts('sh%d' % (os.getpid() % 100000), self.tmp, g('port'))
        except Unavailable as e:
            self.skipTest(str(e))
        self.addCleanup(self.net.close)
        self.pkg = rospkg.RosPack().get_path('swarm_transport')

    def swarm(self, split):
        robots = g('robots')
        self.net.start('core', 'roslaunch', '-p', str(g('port')), 'swarm_transport',
                       'core.launch', 'recorder:=false', 'seed:=%d' % g('seed'))
        self.net.start('core', 'roslaunch', '--wait', 'swarm_transport', 'bases.launch',
                       'robots:=%d' % robots, 'positions:=false')
        for host, lo, hi in (('a', 0, split), ('b', split, robots)):
            self.net.start(host, 'roslaunch', '--wait', 'swarm_transport', 'robots.launch',
                           'from:=%d' % lo, 'to:=%d' % hi, 'hardware:=true', 'diagnostics:=true')

    def watch(self, *args):
        cmd = self.net.command('core', sys.executable,
                               os.path.join(self.pkg, 'test', 'across_hosts_hw_watch.py'),
                               '--robots', str(g('robots')), '--timeout', str(g('timeout_s')),
                               *args)
        w = subprocess.run(cmd, env=self.net.env('core'), capture_output=True, text=True,
                           timeout=g('timeout_s') + 60)
        sys.stdout.write(w.stdout)
        if w.returncode != 0:
            # What decides the case first (a summary scripts/test prints whole): the missions'
            # states and the partition, then each robot's pose watch (a robot without poses
            # stands and is not heard), then the output and the logs' tails.
            lines = w.stdout.splitlines()
            summary = [l for l in lines if l.startswith(('STATUS ', 'DOWN ', 'UP ', 'READY ',
                                                          'SUBMIT '))][-40:]
            summary += [l for l in lines if l.startswith('HEARD ')][-5:]
            poses = self.net.grep(r'no pose for|poses are back|lost \(not heard', 40)
            self.fail('a mission did not end:\n%s\n--- pose watch and losses\n%s\n--- output\n'
                      '%s\n%s\n%s' % ('\n'.join(summary), '\n'.join(poses), w.stdout[-4000:],
                                      w.stderr[-2000:], self.net.logs()))
        return w.stdout.splitlines()

    def states(self, lines, mission):
        return [l.split()[2] for l in lines if l.startswith('STATUS %d ' % mission)]

    def stats(self, lines):
        """{robot id: fields of its last ~diagnostics line}."""
        out = {}
        for l in lines:
            if l.startswith('STATS '):
                f = dict(kv.partition('=')[::2] for kv in l.split()[1:])
                out[int(f['id'])] = f
        return out



class RateLimited(Swarm):

    def test_rate_limited_link(self):
        split, rate = g('split'), g('rate')
        self.net.limit('a', 'b', rate)
        self.net.limit('b', 'a', rate)
        self.swarm(split)
        probes = {h: os.path.join(self.tmp, 'probe_%s.txt' % h) for h in ('a', 'b')}
        for h, path in probes.items():
            self.net.start(h, sys.executable, os.path.join(self.pkg, 'test',
                                                           'across_hosts_probe.py'), path)
        sent0 = {h: self.net.sent_bytes(h) for h in ('a', 'b')}
        t0 = time.time()
        lines = self.watch('--mission', THESIS)
        span = time.time() - t0
        sent = {h: 8e-3 * (self.net.sent_bytes(h) - sent0[h]) / span for h in ('a', 'b')}
        # The robots' own figures: of the positions in their rounds, those that arrived within
        # a tick (by arrival: a position that waited in a queue counts as fresh).
        stats = self.stats(lines)
        self.assertEqual(sorted(stats), list(range(g('robots'))), stats.keys())
        updates = sum(int(f['updates']) for f in stats.values())
        share = sum(int(f['delivered']) for f in stats.values()) / max(1, updates)
        late = sum(int(f['late']) for f in stats.values()) / max(
            1, sum(int(f['ticks']) for f in stats.values()))
        # The probes: each announcement's arrival on its own host and on the other.
        for proc, _ in self.net.procs[-2:]:
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(timeout=15)
        seen = {h: read_probe(p) for h, p in probes.items()}
        ready = float(next(l.split()[1] for l in lines if l.startswith('READY ')))
        delays, sent_n = [], 0
        for here, there, ids in (('a', 'b', range(split)), ('b', 'a', range(split, 99999))):
            local, twice = seen[here]
            remote, _ = seen[there]
            for key, t in local.items():
                if key[0] not in ids or key in twice or t < ready:
                    continue
                sent_n += 1
                if key in remote:
                    delays.append(remote[key] - t)
        within = sum(1 for d in delays if d <= 0.11) / max(1, sent_n)
        states = self.states(lines, 7)
        print('FIGURES rate=%s mission=%s robots_delivered_pct=%.1f robots_late_pct=%.2f '
              'probe_announcements=%d probe_arrived_pct=%.1f probe_within_tick_pct=%.1f '
              'delay_median_ms=%.0f delay_p95_ms=%.0f delay_max_ms=%.0f sent_kbit_s_a=%.0f '
              'sent_kbit_s_b=%.0f' % (rate, states[-1:], 100 * share, 100 * late, sent_n,
                                      100.0 * len(delays) / max(1, sent_n), 100 * within,
                                      1e3 * quantile(delays, 0.5), 1e3 * quantile(delays, 0.95),
                                      1e3 * max(delays or [float('nan')]), sent['a'], sent['b']))
        self.assertEqual(states, NAMES, '\n'.join(lines))
        self.assertGreater(sent_n, 1000, 'the probes saw too few announcements')
        self.assertGreaterEqual(100.0 * len(delays) / max(1, sent_n), g('min_arrived_pct'))
        # The median, not the tail: under CPU load the tail is TCP's retransmission timing on
        # a bucket that drops most packets (docs/hardware.md), while a queue of our own that
        # held announcements would move the median.
        self.assertLessEqual(1e3 * quantile(delays, 0.5), g('max_delay_median_ms'))


class Partition(Swarm):

    def test_partition(self):
        split, robots = g('split'), g('robots')
        self.swarm(split)
        second = '8,%d,%d,%d,%s,%s' % (split, robots, g('second_leaders'), g('second_object'),
                                       g('second_target'))
        lines = self.watch('--mission', THESIS, '--mission', second,
                           '--partition', self.net.link['b'][0], '--down-s', str(g('down_s')))
        text = '\n'.join(lines)
        down = float(next(l.split()[1] for l in lines if l.startswith('DOWN ')))
        up = float(next(l.split()[1] for l in lines if l.startswith('UP ')))
        self.assertAlmostEqual(up - down, g('down_s'), delta=0.5)
        members_b = set(range(split, 12))
        # The mission's side names host b's members lost within the bound of the link going down.
        named = set()
        for l in lines:
            if re.match(r'(STATUS|PROGRESS) 7 ', l) and 'lost' in l:
                wall = float(l.split()[4 if l.startswith('STATUS') else 3])
                if down < wall <= down + g('lost_within_s'):
                    named |= set(int(i) for i in re.findall(r'\d+', l.split('lost')[0].split(
                        'robot(s)')[-1]))
        self.assertTrue(members_b <= named, 'robots %s not named lost within %.1f s of DOWN:\n%s'
                        % (sorted(members_b - named), g('lost_within_s'), text))
        states7 = self.states(lines, 7)
        self.assertIn(states7[-1] if states7 else None, ('DONE', 'ABORTED'), text)
        # The core heard no robot of host b while the link was down, and every robot again
        # after it came back; host b's robots take mission 8.
        heard = [(float(l.split()[1]), set(int(i) for i in (l.split() + [''])[2].split(',')
                                           if i)) for l in lines if l.startswith('HEARD ')]
        self.assertTrue(any(down < t < up + 1.0 and ids == set(range(split))
                            for t, ids in heard), 'host b still heard while down:\n' + text)
        after = [l for l in lines if l.startswith('READY ') and float(l.split()[1]) > up]
        self.assertTrue(after, 'not every robot heard again after the link came back:\n' + text)
        self.assertIn('SUBMIT 8 0 ', text)
        self.assertEqual(self.states(lines, 8)[-1:], ['DONE'], text)
        # No node hangs: every robot's figures are recent at the end.
        stats = self.stats(lines)
        self.assertEqual(sorted(stats), list(range(robots)), stats.keys())
        newest = max(float(f['wall']) for f in stats.values())
        stale = [i for i, f in stats.items() if float(f['wall']) < newest - 3.0]
        self.assertFalse(stale, 'robots %s stopped reporting' % stale)


if __name__ == '__main__':
    rospy.init_node('across_hosts_hardware_test')
    case = {'rate': RateLimited, 'partition': Partition}[rospy.get_param('~case')]
    rostest.rosrun('swarm_transport', 'across_hosts_hardware', case, sys.argv)
