#!/usr/bin/env python3
"""A hung robot in lock-step (issue 11): a robot process stopped with SIGSTOP costs the
simulator's lockstep_timeout_s once, not every tick - the others go on at full speed while it
stands - and once it is continued (SIGCONT) it answers again and moves with the swarm."""

import os
import signal
import sys
import time
import unittest

import rospy
import rostest

import swarm_testing as st


class HungRobot(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.robots = rospy.get_param('~robots')
        cls.timeout = rospy.get_param('~timeout_s')
        cls.log = st.PositionLog()
        cls.swarm = st.launch_swarm(robots=cls.robots, seed=rospy.get_param('~seed'),
                                    lockstep=True, max_ticks=0)
        assert cls.log.wait_tick(5, cls.timeout), 'the swarm never ticked'

    @classmethod
    def tearDownClass(cls):
        cls.swarm.shutdown()
        cls.log.close()

    def test_a_hung_robot_is_waited_for_once_and_rejoins(self):
        hung = rospy.get_param('~hung_robot')
        window = rospy.get_param('~window_s')
        pid = st.node_pid('/robot_%d/robot' % hung)
        os.kill(pid, signal.SIGSTOP)
        try:
            start_tick = self.log.latest_tick()
            time.sleep(window)
            stopped_ticks = self.log.latest_tick() - start_tick
            # Waiting lockstep_timeout_s (2 s) every tick would give window / 2 ticks.
            self.assertGreaterEqual(stopped_ticks, rospy.get_param('~min_ticks_while_hung'),
                                    '%d ticks in %.0f s with robot %d stopped'
                                    % (stopped_ticks, window, hung))
            # It stands while stopped (the last ticks of the window): it drives nothing, so its
            # heading stays exactly as it was (a neighbour's push-apart moves a robot but never
            # turns it), and it moves at most as far as pushes take it.
            end = self.log.latest_tick()
            a, b = self.log.at(end - 20), self.log.at(end)
            turned = abs((b[hung][2] - a[hung][2] + 180.0) % 360.0 - 180.0)
            self.assertLessEqual(turned, rospy.get_param('~still_deg'),
                                 'the stopped robot turned %.4f deg' % turned)
            self.assertLessEqual(st.moved(a[hung], b[hung]), rospy.get_param('~still_m'),
                                 'the stopped robot moved')
        finally:
            os.kill(pid, signal.SIGCONT)
        # Continued, it answers again and drives with the others (however long the resumed
        # process takes to get going on a loaded machine: ticks go on meanwhile).
        resumed = self.log.latest_tick()
        before = self.log.at(resumed)[hung]

        def moves_again():
            now = self.log.at(self.log.latest_tick())
            return hung in now and st.moved(before, now[hung]) > rospy.get_param('~moves_m')

        self.assertTrue(st.wait_for(moves_again, self.timeout),
                        'robot %d did not move again after SIGCONT' % hung)

if __name__ == '__main__':
    rospy.init_node('hung_robot_test')
    rostest.rosrun('swarm_transport', 'hung_robot', HungRobot, sys.argv)
