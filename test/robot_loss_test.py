#!/usr/bin/env python3
"""Robots lost during a mission (issue 11), their processes killed (SIGKILL) in lock-step:
- a passive robot in GATHERING: its radio falls silent, the first leader drops it after
  lost_after_ticks and the rest gathers, loads and carries without it (LOADING names it);
- the first leader in TRANSPORT: the mission does not hang - the dispatcher hears nothing from
  the first leader (no phase, no progress report) for its silence limit, ends the mission
  ABORTED with a reason naming the robot, and sends Delete_Object, so the other robots of the
  mission drop it and flock on."""

import os
import signal
import sys
import unittest
import xmlrpc.client

import rosgraph
import rosnode
import rospy
import rostest
from std_srvs.srv import Trigger
from swarm_transport.msg import New_Mission

import swarm_testing as st


def node_pid(name):
    api = rosnode.get_api_uri(rosgraph.Master('/robot_loss_test'), name)
    code, _, pid = xmlrpc.client.ServerProxy(api).getPid('/robot_loss_test')
    assert code == 1, 'no pid for %s' % name
    return pid


class RobotLoss(unittest.TestCase):

    def test_a_passive_robot_lost_in_gathering_is_dropped(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        timeout = g('timeout_s')
        lost = g('lost_robot')
        status = st.StatusLog()
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=True, max_ticks=0)
        log = None
        try:
            why = st.submit_before_first_tick(
                pub, st.mission(6, 0, g('group'), 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)), timeout)
            self.assertEqual(why, '')
            log = st.PositionLog()
            self.assertTrue(st.wait_for(lambda: status.first(6, 1) is not None, timeout),
                            'no GATHERING; states so far %s' % status.states(6))
            os.kill(node_pid('/robot_%d/robot' % lost), signal.SIGKILL)
            self.assertTrue(st.wait_for(lambda: status.final(6), timeout),
                            'mission 6 never ended; states %s' % status.states(6))
            self.assertEqual(status.states(6), ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT',
                                                'UNLOADING', 'DONE'])
            loading = status.first(6, 2)
            self.assertIn('without robot(s) %d (lost' % lost, loading.reason)
        finally:
            swarm.shutdown()
            if log:
                log.close()

    def test_the_mission_of_a_lost_first_leader_ends_aborted(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        timeout = g('timeout_s')
        status = st.StatusLog()
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=True, max_ticks=0)
        log = None
        try:
            why = st.submit_before_first_tick(
                pub, st.mission(5, 0, g('group'), 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)), timeout)
            self.assertEqual(why, '')
            log = st.PositionLog()
            self.assertTrue(st.wait_for(lambda: status.first(5, 3) is not None, timeout),
                            'no TRANSPORT; states so far %s' % status.states(5))
            os.kill(node_pid('/robot_0/robot'), signal.SIGKILL)  # the first leader
            killed_at = log.latest_tick()
            self.assertTrue(st.wait_for(lambda: status.final(5), timeout),
                            'mission 5 never ended after its first leader died; states %s'
                            % status.states(5))
            end = [m for m in status.of(5) if m.state in (5, 6, 7)][0]
            self.assertEqual(st.NAMES[end.state], 'ABORTED', end.reason)
            self.assertIn('robot 0', end.reason)
            self.assertIn('silent', end.reason)
            self.assertLessEqual(end.tick - killed_at, g('max_ticks_to_abort'),
                                 'killed at tick %d, ABORTED at tick %d' % (killed_at, end.tick))
            # The other robots of the mission dropped it and go on ticking.
            self.assertTrue(log.wait_tick(end.tick + 20, timeout))
            srv = rospy.ServiceProxy('/robot_1/robot/describe', Trigger)
            srv.wait_for_service(timeout)
            self.assertTrue(st.wait_for(lambda: 'missions=[]' in srv().message, timeout),
                            srv().message)
        finally:
            swarm.shutdown()
            if log:
                log.close()


if __name__ == '__main__':
    rospy.init_node('robot_loss_test')
    rostest.rosrun('swarm_transport', 'robot_loss', RobotLoss, sys.argv)
