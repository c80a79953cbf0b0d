#!/usr/bin/env python3
"""/diagnostics (issue 13): every node of a running swarm publishes one status of its own on
/diagnostics, about once a wall second - the simulator (tick, robots, answering), the
dispatcher, the recorder and each robot (its ticks) - all OK in a healthy lock-step run, and
the figures move on with the run."""

import sys
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class Diagnostics(unittest.TestCase):

    def test_every_node_reports_its_status(self):
        lock = threading.Lock()
        latest = {}
        counts = {}

        def on_diag(msg):
            with lock:
                for s in msg.status:
                    latest[s.name] = s
                    counts[s.name] = counts.get(s.name, 0) + 1
        sub = rospy.Subscriber('/diagnostics', DiagnosticArray, on_diag, queue_size=1000)
        robots = g('robots')
        swarm = st.launch_swarm(robots=robots, seed=g('seed'), lockstep=True, max_ticks=0,
                                recorder=True, deploy=g('deploy'), observers=0)
        self.addCleanup(swarm.shutdown)
        self.addCleanup(sub.unregister)
        names = {'swarm_transport: simulator', 'swarm_transport: mission_dispatcher',
                 'swarm_transport: recorder'} | {'swarm_transport: robot %d' % i
                                                for i in range(robots)}
        if g('deploy') == 'host':
            names = (names - {'swarm_transport: robot %d' % i for i in range(robots)}) | {
                'swarm_transport: robot_host'}

        def all_ok_twice():
            with lock:
                return all(n in latest and latest[n].level == DiagnosticStatus.OK and
                           counts[n] >= 2 for n in names)
        self.assertTrue(st.wait_for(all_ok_twice, g('timeout_s')),
                        'missing or not OK: %s' % sorted(
                            (n, latest[n].level, latest[n].message) if n in latest else (n, None)
                            for n in names if n not in latest or latest[n].level != 0))
        with lock:
            sim = {kv.key: kv.value for kv in latest['swarm_transport: simulator'].values}
            extra = sorted(set(latest) - names)
        self.assertEqual(int(sim['robots']), robots)
        self.assertEqual(int(sim['answering']), robots)
        self.assertEqual(extra, [], 'statuses of unknown nodes')
        tick = int(sim['tick'])

        def moved_on():
            with lock:
                values = {kv.key: kv.value for kv in latest['swarm_transport: simulator'].values}
            return int(values['tick']) > tick
        self.assertTrue(st.wait_for(moved_on, g('timeout_s')), 'the simulator status stood')
        if g('deploy') == 'process':
            with lock:
                r = {kv.key: kv.value for kv in latest['swarm_transport: robot 0'].values}
            self.assertGreater(int(r['ticks']), 0)
            self.assertEqual(r['listed'], 'true')


if __name__ == '__main__':
    rospy.init_node('diagnostics_test')
    rostest.rosrun('swarm_transport', 'diagnostics', Diagnostics, sys.argv)
