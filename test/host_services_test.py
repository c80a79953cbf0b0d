#!/usr/bin/env python3
"""Robots and simulator in one robot_host in real time (swarm.launch deploy:=host_sim) with
robot_services:=false (issue 10, item 8: the per-robot services' registration is O(N^2) at
start-up):
- none of the per-robot services is offered (robot_<id>/robot/describe and state,
  robot_<id>/teleport_absolute and teleport_relative), the global ones are (/spawn, /kill);
- the robots fly, and the swarm-wide topics the host subscribes once for all its robots reach
  each of them: a Robot_Freeze of every id stops every robot, a Robot_Continue starts them
  again."""

import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import Robot_Continue, Robot_Freeze

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class HostServices(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.timeout = g('timeout_s')
        cls.robots = g('robots')
        cls.log = st.PositionLog()
        cls.swarm = st.launch_swarm(robots=cls.robots, seed=g('seed'), lockstep=False,
                                    deploy='host_sim', robot_services=False, dispatcher=False)
        assert cls.log.wait_tick(3, cls.timeout), 'the swarm never ticked'

    @classmethod
    def tearDownClass(cls):
        cls.swarm.shutdown()

    def moved(self, ticks):
        """The largest distance a robot moved over the next `ticks` radio rounds (m)."""
        start = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(start + ticks, self.timeout))
        a, b = self.log.at(start), self.log.at(start + ticks)
        self.assertEqual(sorted(a), list(range(self.robots)))
        return max(((b[i][0] - a[i][0]) ** 2 + (b[i][1] - a[i][1]) ** 2) ** 0.5 for i in a)

    def test_1_no_per_robot_services(self):
        names = st.service_names()
        for rid in range(self.robots):
            for name in ('/robot_%d/robot/describe' % rid, '/robot_%d/robot/state' % rid,
                         '/robot_%d/teleport_absolute' % rid,
                         '/robot_%d/teleport_relative' % rid):
                self.assertNotIn(name, names)
        self.assertIn('/spawn', names)
        self.assertIn('/kill', names)

    def test_2_shared_topics_reach_every_robot(self):
        ticks = g('window_ticks')
        self.assertGreater(self.moved(ticks), g('moving_m'), 'the robots do not fly')
        freeze = rospy.Publisher('/flock/freeze', Robot_Freeze, queue_size=10)
        resume = rospy.Publisher('/flock/continue', Robot_Continue, queue_size=10)
        self.assertTrue(st.wait_for(lambda: freeze.get_num_connections() > 0, self.timeout))
        self.assertTrue(st.wait_for(lambda: resume.get_num_connections() > 0, self.timeout))
        freeze.publish(Robot_Freeze(robot_index_from=0, robot_index_to=self.robots))
        # The freeze takes effect within a few rounds; from then on nobody moves.
        self.assertTrue(self.log.wait_tick(self.log.latest_tick() + 5, self.timeout))
        self.assertLess(self.moved(ticks), g('standing_m'), 'a robot did not hear the freeze')
        resume.publish(Robot_Continue(robot_index_from=0, robot_index_to=self.robots))
        self.assertTrue(self.log.wait_tick(self.log.latest_tick() + 5, self.timeout))
        self.assertGreater(self.moved(ticks), g('moving_m'), 'the robots did not continue')


if __name__ == '__main__':
    rospy.init_node('host_services_test')
    rostest.rosrun('swarm_transport', 'host_services', HostServices, sys.argv)
