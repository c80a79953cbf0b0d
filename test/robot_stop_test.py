#!/usr/bin/env python3
"""A mission's first leader stopped (SIGSTOP) for 2 s and continued, in real time, as
scripts/soak does (issue 29 item 5): its mission ends DONE, and every status of it comes from
that robot. In a real-time simulation the simulator relays a stopped robot's pose from its world,
so the other robots never lost it and promoted nobody; the robot itself, finding its ticks jumped
by more than lost_after_s, used to count itself lost and stop leading - the mission stood
without a first leader until the dispatcher aborted it as silent (missions 7 and 13 of a
2-minute soak slice beside a busy loop)."""

import os
import signal
import sys
import threading
import time
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status

import swarm_testing as st

GATHERING, TRANSPORT = 1, 3


def g(key):
    return rospy.get_param('~' + key)


class Senders(object):
    """Who published each status of /flock/mission/status (its caller id), per mission."""

    def __init__(self):
        self.lock = threading.Lock()
        self.by_mission = {}
        self.sub = rospy.Subscriber('/flock/mission/status', Mission_Status, self._cb,
                                    queue_size=1000)

    def _cb(self, msg):
        with self.lock:
            self.by_mission.setdefault(msg.mission_id, set()).add(
                msg._connection_header.get('callerid', '?'))

    def of(self, mission_id):
        with self.lock:
            return set(self.by_mission.get(mission_id, set()))


class RobotStop(unittest.TestCase):

    def test_a_first_leader_stopped_for_2_s_leads_its_mission_to_the_end(self):
        timeout = g('timeout_s')
        status = st.StatusLog()
        senders = Senders()
        last_progress = {}
        progress_sub = rospy.Subscriber(
            '/flock/mission/progress', Mission_Status,
            lambda m: last_progress.__setitem__(m.mission_id, m), queue_size=100)
        self.addCleanup(progress_sub.unregister)

        def progress_of(mission_id):
            m = last_progress.get(mission_id)
            if m is None:
                return 'none heard'
            return ('%s, tick %d, %d of %d robots inside, lost %s, object at (%.2f, %.2f)'
                    % (st.NAMES.get(m.state, m.state), m.tick, m.robots_inside,
                       m.robots_assigned, list(m.lost), m.object_position_x,
                       m.object_position_y))
        pub, _ = st.realtime_swarm_for(self, g('robots'), g('seed'), timeout)
        leader = 0
        for mission_id, phase, obj, target in ((1, GATHERING, (7.0, 7.0), (3.0, 3.0)),
                                                (2, TRANSPORT, (3.0, 3.0), (7.0, 7.0))):
            pub.publish(st.mission(mission_id, 0, g('group'), 1, obj + (2.0, 2.0), target))
            self.assertTrue(
                st.wait_for(lambda: status.first(mission_id, phase) is not None, timeout),
                'mission %d: no %s; states so far %s'
                % (mission_id, st.NAMES[phase], status.states(mission_id)))
            pid = st.node_pid('/robot_%d/robot' % leader)
            os.kill(pid, signal.SIGSTOP)
            try:
                time.sleep(g('stop_s'))
            finally:
                os.kill(pid, signal.SIGCONT)
            continued_s = time.time()
            if not st.wait_for(lambda: status.final(mission_id), g('end_within_s')):
                self.fail('mission %d (first leader stopped %.0f s in %s) never ended within %d '
                          's; states %s; its last progress: %s; its robots:\n%s'
                          % (mission_id, g('stop_s'), st.NAMES[phase], g('end_within_s'),
                             status.states(mission_id), progress_of(mission_id),
                             st.describe_robots(range(g('group')))))
            ended = [m for m in status.of(mission_id) if m.state in (5, 6)]
            self.assertEqual(st.NAMES[ended[0].state], 'DONE',
                             'mission %d: %s' % (mission_id, ended[0].reason))
            # Nobody else led it: the others heard the stopped robot all along.
            self.assertEqual(senders.of(mission_id), {'/robot_%d/robot' % leader},
                             'mission %d: statuses from %s' % (mission_id,
                                                                sorted(senders.of(mission_id))))
            rospy.loginfo('mission %d ended DONE %.1f s after its first leader was continued',
                          mission_id, time.time() - continued_s)


if __name__ == '__main__':
    rospy.init_node('robot_stop_test')
    rostest.rosrun('swarm_transport', 'robot_stop', RobotStop, sys.argv)
