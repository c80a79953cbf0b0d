#!/usr/bin/env python3
"""Lock-step reproducibility: the same seed twice gives identical final poses, a different
seed gives different ones."""

import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import New_Mission

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


def mission_run(seed, robots, ticks, timeout):
    """Every tick's poses and the mission's phases of the thesis's transport mission, sent
    before the first tick, in a lock-step run of `ticks` ticks."""
    status = st.StatusLog()
    pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
    swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks)
    log = None
    try:
        why = st.submit_before_first_tick(
            pub, st.mission(9, 0, 12, 3, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)), timeout)
        if why:
            raise AssertionError(why)
        log = st.PositionLog()
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('seed %d: the run stopped at tick %d' % (seed, log.latest_tick()))
        phases = [(m.state, m.tick) for m in status.of(9)]
        return {t: log.at(t) for t in range(ticks + 1)}, phases
    finally:
        swarm.shutdown()
        pub.unregister()
        status.sub.unregister()
        if log:
            log.close()


class Determinism(unittest.TestCase):

    def test_same_seed_same_transport_mission(self):
        """The lock-step barrier relays every mission message (object updates, freezes,
        statuses, the dispatcher's stamped LOADED / UNLOADED) at the same tick in every run."""
        robots = rospy.get_param('~mission_robots')
        ticks = rospy.get_param('~mission_ticks')
        timeout = rospy.get_param('~timeout_s')
        tol = rospy.get_param('~identical_tolerance_m')
        a, phases_a = mission_run(2, robots, ticks, timeout)
        b, phases_b = mission_run(2, robots, ticks, timeout)
        self.assertIn(3, [s for s, _ in phases_a], 'the mission never reached TRANSPORT: %s'
                      % phases_a)
        self.assertEqual(phases_a, phases_b)
        for t in range(ticks + 1):
            for rid in range(robots):
                self.assertLessEqual(st.moved(a[t][rid], b[t][rid]), tol,
                                     'tick %d: robot %d at %s vs %s' % (t, rid, a[t][rid],
                                                                       b[t][rid]))

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
