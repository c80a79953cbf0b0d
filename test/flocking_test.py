#!/usr/bin/env python3
"""Lock-step flocking scenario: N robots for K ticks; every robot moves, no two overlap beyond
a tolerance, none leaves the arena. Parameters (and tolerances) come from the .test file."""

import itertools
import math
import sys
import unittest

import rospy
import rostest

import swarm_testing as st


class FlockingLockstep(unittest.TestCase):

    def test_swarm_moves_without_collisions_inside_the_arena(self):
        robots = rospy.get_param('~robots')
        ticks = rospy.get_param('~ticks')
        seed = rospy.get_param('~seed')
        overlap_tol = rospy.get_param('~overlap_tolerance_m')
        border_tol = rospy.get_param('~border_tolerance_m')
        min_move = rospy.get_param('~min_move_m')
        log = st.PositionLog()
        swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks)
        try:
            self.assertTrue(log.wait_tick(ticks - 1, rospy.get_param('~timeout_s')),
                            'the simulator did not reach tick %d (last %d)'
                            % (ticks - 1, log.latest_tick()))
        finally:
            swarm.shutdown()
            log.close()
        size = rospy.get_param('/swarm/world_size_m')
        radius = rospy.get_param('/swarm/robot_radius_m')
        seen = log.ticks()
        self.assertGreaterEqual(len(seen), ticks * 0.95, 'too few ticks observed')
        first, last = log.at(seen[0]), log.at(seen[-1])
        self.assertEqual(len(first), robots)
        for rid in range(robots):
            self.assertGreater(st.moved(first[rid], last[rid]), min_move,
                               'robot %d did not move' % rid)
        worst = float('inf')
        for t in seen:
            pos = log.at(t)
            for rid, p in pos.items():
                self.assertTrue(radius - border_tol <= p[0] <= size - radius + border_tol and
                                radius - border_tol <= p[1] <= size - radius + border_tol,
                                'robot %d left the arena at tick %d: %s' % (rid, t, p))
            for (a, pa), (b, pb) in itertools.combinations(pos.items(), 2):
                d = math.hypot(pa[0] - pb[0], pa[1] - pb[1])
                worst = min(worst, d)
                self.assertGreaterEqual(d, 2 * radius - overlap_tol,
                                        'robots %d and %d overlap at tick %d (%.4f m apart)'
                                        % (a, b, t, d))
        rospy.loginfo('closest approach over the run: %.4f m (2r = %.3f)', worst, 2 * radius)


if __name__ == '__main__':
    rospy.init_node('flocking_test')
    rostest.rosrun('swarm_transport', 'flocking_lockstep', FlockingLockstep, sys.argv)
