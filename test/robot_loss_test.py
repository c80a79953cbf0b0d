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

import rospy
import rostest
from swarm_transport.msg import New_Mission

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RobotLoss(unittest.TestCase):

    def kill_in_phase(self, mission_id, phase, robot):
        """Launches the swarm, submits a transport mission of robots [0, group) led by robot 0
        before tick 0, and kills `robot`'s process once the mission reported `phase`. Returns
        (status log, position log, the tick of the kill); the swarm is shut down at cleanup."""
        timeout = g('timeout_s')
        status = st.StatusLog()
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=True, max_ticks=0)
        self.addCleanup(swarm.shutdown)
        why = st.submit_before_first_tick(
            pub, st.mission(mission_id, 0, g('group'), 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)),
            timeout)
        self.assertEqual(why, '')
        log = st.PositionLog()
        self.addCleanup(log.close)
        self.assertTrue(st.wait_for(lambda: status.first(mission_id, phase) is not None, timeout),
                        'no %s; states so far %s' % (st.NAMES[phase], status.states(mission_id)))
        os.kill(st.node_pid('/robot_%d/robot' % robot), signal.SIGKILL)
        killed_at = log.latest_tick()
        self.assertTrue(st.wait_for(lambda: status.final(mission_id), timeout),
                        'mission %d never ended after robot %d died; states %s'
                        % (mission_id, robot, status.states(mission_id)))
        return status, log, killed_at

    def test_a_passive_robot_lost_in_gathering_is_dropped(self):
        lost = g('lost_robot')
        status, _, _ = self.kill_in_phase(6, 1, lost)
        self.assertEqual(status.states(6), ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT',
                                            'UNLOADING', 'DONE'])
        self.assertIn('without robot(s) %d (lost' % lost, status.first(6, 2).reason)

    def test_the_mission_of_a_lost_first_leader_ends_aborted(self):
        status, log, killed_at = self.kill_in_phase(5, 3, 0)  # the first leader in TRANSPORT
        end = [m for m in status.of(5) if m.state in (5, 6, 7)][0]
        self.assertEqual(st.NAMES[end.state], 'ABORTED', end.reason)
        self.assertIn('robot 0', end.reason)
        self.assertIn('silent', end.reason)
        self.assertLessEqual(end.tick - killed_at, g('max_ticks_to_abort'),
                             'killed at tick %d, ABORTED at tick %d' % (killed_at, end.tick))
        # The other robots of the mission dropped it and go on ticking.
        self.assertTrue(log.wait_tick(end.tick + 20, g('timeout_s')))
        self.assertTrue(
            st.wait_for(lambda: not st.robot_state(1, g('timeout_s')).mission_ids, g('timeout_s')),
            st.robot_state(1, g('timeout_s')))


if __name__ == '__main__':
    rospy.init_node('robot_loss_test')
    rostest.rosrun('swarm_transport', 'robot_loss', RobotLoss, sys.argv)
