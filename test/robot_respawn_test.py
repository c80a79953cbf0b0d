#!/usr/bin/env python3
"""A robot of a transport mission killed (SIGKILL) in TRANSPORT and respawned under the same id
(/kill, /spawn, robot.launch: a fresh process), in real time, as scripts/soak does (issue 29
item 5): the mission still ends, DONE, within the test's bound - whether the robot was its first
leader or a passive member - and nobody runs it again from QUEUED (the fresh process got the
dispatcher's latched order of the running mission and led it a second time, from GATHERING:
its LOADING froze the robots in TRANSPORT, which then stood for good)."""

import os
import signal
import sys
import time
import unittest

import rospy
import rostest
from swarm_transport.srv import Kill, Spawn

import swarm_testing as st

TRANSPORT = 3


def g(key):
    return rospy.get_param('~' + key)


class RobotRespawn(unittest.TestCase):

    def respawn_in_transport(self, mission_id, robot):
        timeout = g('timeout_s')
        status = st.StatusLog()
        pub, _ = st.realtime_swarm_for(self, g('robots'), g('seed'), timeout)
        pub.publish(st.mission(mission_id, 0, g('group'), 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)))
        self.assertTrue(
            st.wait_for(lambda: status.first(mission_id, TRANSPORT) is not None, timeout),
            'no TRANSPORT; states so far %s' % status.states(mission_id))
        os.kill(st.node_pid('/robot_%d/robot' % robot), signal.SIGKILL)
        # The soak's respawn: 5 s later, removed and spawned again in the arena's middle (on the
        # object's way), then a fresh process under the same id.
        time.sleep(g('respawn_after_s'))
        rospy.wait_for_service('/spawn', timeout)
        rospy.ServiceProxy('/kill', Kill)(robot_id=robot)
        answer = rospy.ServiceProxy('/spawn', Spawn)(robot_id=robot, x=5.5, y=5.5, theta=0.0)
        self.assertEqual(answer.code, 0, answer.message)
        fresh = st.launch_file('robot.launch', id=robot)
        self.addCleanup(fresh.shutdown)
        respawned_s = time.time()
        self.assertTrue(st.wait_for(lambda: status.final(mission_id), g('end_within_s')),
                        'mission %d never ended within %d s after robot %d was respawned; '
                        'states %s, last reasons %s'
                        % (mission_id, g('end_within_s'), robot, status.states(mission_id),
                           [m.reason for m in status.of(mission_id) if m.reason][-3:]))
        ended = [m for m in status.of(mission_id) if m.state in (5, 6)]
        self.assertEqual(st.NAMES[ended[0].state], 'DONE', ended[0].reason)
        # Nobody ran it again from the start: the fresh process did not take the (latched)
        # order of a mission that runs without it (a second first leader in GATHERING and
        # LOADING, whose freeze stops the robots that carry the object).
        states = status.states(mission_id)
        after = states[states.index('TRANSPORT'):]
        self.assertFalse({'QUEUED', 'GATHERING', 'LOADING'} & set(after),
                         'a status of an earlier phase after TRANSPORT: %s' % states)
        rospy.loginfo('mission %d ended %.1f s after robot %d was respawned', mission_id,
                      time.time() - respawned_s, robot)

    def test_a_respawned_first_leader(self):
        self.respawn_in_transport(1, 0)

    def test_a_respawned_passive_robot(self):
        self.respawn_in_transport(2, 2)


if __name__ == '__main__':
    rospy.init_node('robot_respawn_test')
    rostest.rosrun('swarm_transport', 'robot_respawn', RobotRespawn, sys.argv)
