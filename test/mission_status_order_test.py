#!/usr/bin/env python3
"""Issue 9: a user who sends a raw New_Mission on /flock/mission/new (as `rostopic pub` does)
and follows /flock/mission/status sees, for that mission id, exactly QUEUED, GATHERING,
LOADING, TRANSPORT, UNLOADING, DONE: QUEUED first, every phase once, in order. Every status
of the mission counts, whoever sent it; repeats are not collapsed. Lock-step (one process per
robot; robots and simulator in one process) and real time (one process per robot; all robots
in one process)."""

import sys
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status, New_Mission

import swarm_testing as st

EXPECTED = ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE']


class Statuses(object):
    """Every Mission_Status of one mission as it arrived, with its sender."""

    def __init__(self, mission_id):
        self.mission_id = mission_id
        self.lock = threading.Lock()
        self.items = []
        self.sub = rospy.Subscriber('/flock/mission/status', Mission_Status, self._cb,
                                    queue_size=1000, tcp_nodelay=True)

    def _cb(self, msg):
        if msg.mission_id != self.mission_id:
            return
        with self.lock:
            self.items.append((st.NAMES.get(msg.state, str(msg.state)), msg.tick,
                               msg._connection_header.get('callerid', '?')))

    def states(self):
        with self.lock:
            return [s for s, _, _ in self.items]

    def final(self):
        return any(s in ('DONE', 'ABORTED', 'REJECTED') for s in self.states())

    def describe(self):
        with self.lock:
            return ', '.join('%s (tick %d, from %s)' % item for item in self.items)

    def close(self):
        self.sub.unregister()


class MissionStatusOrder(unittest.TestCase):

    def run_raw_mission(self, lockstep, deploy):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        timeout = g('timeout_s')
        mid = g('mission_id')
        statuses = Statuses(mid)
        log = st.PositionLog()
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=lockstep,
                                max_ticks=0, deploy=deploy,
                                placement=g('placement'))
        raw = None
        try:
            self.assertTrue(log.wait_tick(g('start_ticks'), timeout), 'the swarm never ticked')
            # Exactly what `rostopic pub -1 /flock/mission/new ...` does: a new latched
            # publisher that sends at once; each subscriber (simulator, dispatcher, robots in
            # real time) gets it when its own connection is up, in no particular order.
            raw = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=1, latch=True)
            raw.publish(st.mission(mid, g('from'), g('to'), g('leaders'),
                                   (g('object_x'), g('object_y'), g('object_size_x'),
                                    g('object_size_y')), (g('target_x'), g('target_y'))))
            self.assertTrue(st.wait_for(statuses.final, timeout),
                            'mission %d did not end; statuses: %s' % (mid, statuses.describe()))
            # Anything sent late (a repeated phase, a late QUEUED) would come within a few ticks.
            end = log.latest_tick()
            self.assertTrue(log.wait_tick(end + g('after_ticks'), timeout),
                            'the swarm stopped ticking')
        finally:
            swarm.shutdown()
            log.close()
            statuses.close()
            if raw is not None:
                raw.unregister()
        rospy.loginfo('%s %s: %s', 'lock-step' if lockstep else 'real time', deploy,
                      statuses.describe())
        self.assertEqual(statuses.states(), EXPECTED,
                         '%s, deploy %s: statuses of mission %d: %s'
                         % ('lock-step' if lockstep else 'real time', deploy, mid,
                            statuses.describe()))

    def test_lockstep_process(self):
        self.run_raw_mission(True, 'process')

    def test_lockstep_host_sim(self):
        self.run_raw_mission(True, 'host_sim')

    def test_realtime_process(self):
        self.run_raw_mission(False, 'process')

    def test_realtime_host(self):
        self.run_raw_mission(False, 'host')


if __name__ == '__main__':
    rospy.init_node('mission_status_order_test')
    rostest.rosrun('swarm_transport', 'mission_status_order', MissionStatusOrder, sys.argv)
