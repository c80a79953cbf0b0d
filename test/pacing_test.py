#!/usr/bin/env python3
"""Lock-step pacing (issue 13): with real_time_factor 1.0 a lock-step run keeps to the wall
clock - 100 ticks of 0.1 s take 10 s - while every tick stays a lock-step tick."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from swarm_transport.msg import Robot_Positions

import swarm_testing as st


class Pacing(unittest.TestCase):

    def test_real_time_factor_one_keeps_to_the_wall_clock(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        arrivals = {}
        lock = threading.Lock()

        def on_positions(msg):
            with lock:
                arrivals.setdefault(msg.tick, time.time())

        sub = rospy.Subscriber('/flock/world_poses', Robot_Positions, on_positions,
                               queue_size=1000, tcp_nodelay=True)
        swarm = st.launch_swarm(robots=g('robots'), seed=1, lockstep=True, max_ticks=0,
                                real_time_factor=g('real_time_factor'))
        try:
            first, last = g('first_tick'), g('first_tick') + g('ticks')
            ok = st.wait_for(lambda: last in arrivals, g('timeout_s'))
            self.assertTrue(ok, 'tick %d never came' % last)
            with lock:
                wall = arrivals[last] - arrivals[first]
                ticks = sorted(t for t in arrivals if first <= t <= last)
            self.assertEqual(ticks, list(range(first, last + 1)), 'a tick is missing')
            expected = g('ticks') * g('tick_period_s') / g('real_time_factor')
            self.assertLessEqual(abs(wall - expected), g('tolerance') * expected,
                                 '%d ticks took %.2f s of wall time, expected %.2f'
                                 % (g('ticks'), wall, expected))
        finally:
            sub.unregister()
            swarm.shutdown()


if __name__ == '__main__':
    rospy.init_node('pacing_test')
    rostest.rosrun('swarm_transport', 'pacing', Pacing, sys.argv)
