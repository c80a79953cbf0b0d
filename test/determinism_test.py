#!/usr/bin/env python3
"""Lock-step reproducibility: the same seed twice gives identical final poses, a different
seed gives different ones."""

import sys
import unittest

import rospy
import rostest

import swarm_testing as st


def final_poses(seed, robots, ticks, timeout):
    log = st.PositionLog()
    swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks)
    try:
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('seed %d: the run stopped at tick %d' % (seed, log.latest_tick()))
        return log.at(ticks)
    finally:
        swarm.shutdown()
        log.close()


class Determinism(unittest.TestCase):

    def test_same_seed_same_run_other_seed_other_run(self):
        robots = rospy.get_param('~robots')
        ticks = rospy.get_param('~ticks')
        timeout = rospy.get_param('~timeout_s')
        tol = rospy.get_param('~identical_tolerance_m')
        differ = rospy.get_param('~different_min_m')
        a = final_poses(11, robots, ticks, timeout)
        b = final_poses(11, robots, ticks, timeout)
        c = final_poses(12, robots, ticks, timeout)
        self.assertEqual(sorted(a), list(range(robots)))
        for rid in range(robots):
            self.assertLessEqual(st.moved(a[rid], b[rid]), tol,
                                 'seed 11 twice: robot %d ended %s vs %s' % (rid, a[rid], b[rid]))
            self.assertLessEqual(abs(a[rid][2] - b[rid][2]), 1e-3)
        self.assertGreater(max(st.moved(a[r], c[r]) for r in range(robots)), differ,
                           'seeds 11 and 12 gave the same final poses')


if __name__ == '__main__':
    rospy.init_node('determinism_test')
    rostest.rosrun('swarm_transport', 'determinism', Determinism, sys.argv)
