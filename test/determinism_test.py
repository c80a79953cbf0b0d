#!/usr/bin/env python3
"""Lock-step reproducibility: the same seed twice gives identical final poses, a different
seed gives different ones; a missions file's order enters at its tick however busy the cores
are. (The thesis mission twice with the same seed, a process per robot, identical at every
tick: test/scenarios/thesis_transport_process.yaml.)"""

import os
import subprocess
import sys
import unittest

import rospkg
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


def missions_file_run(seed, robots, ticks, timeout, path, mission_id):
    """Every tick's poses and the phases of `mission_id`, submitted by the dispatcher from the
    missions file `path`, in a lock-step run of `ticks` ticks."""
    status = st.StatusLog()
    log = st.PositionLog()
    swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks,
                            missions_file=path)
    try:
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('seed %d: the run stopped at tick %d' % (seed, log.latest_tick()))
        phases = [(m.state, m.tick) for m in status.of(mission_id)]
        return {t: log.at(t) for t in range(ticks + 1)}, phases
    finally:
        swarm.shutdown()
        log.close()
        status.sub.unregister()


class Busy(object):
    """`n` processes that spin a core each, so that the swarm's processes are scheduled
    late and in changing order; stopped by pid."""

    def __init__(self, n):
        self.procs = [subprocess.Popen([sys.executable, '-c', 'while True: pass'])
                      for _ in range(n)]

    def stop(self):
        for p in self.procs:
            p.kill()
            p.wait()


class Determinism(unittest.TestCase):

    def test_missions_file_enters_at_its_tick_under_load(self):
        """A missions file's order enters the run at the tick its start delay names, and the
        same seed and file give the same run, every tick and phase, however busy the cores
        are (the dispatcher stamps the order; lock-step holds that tick until it is in)."""
        robots = rospy.get_param('~mission_robots')
        ticks = rospy.get_param('~file_ticks')
        timeout = rospy.get_param('~timeout_s')
        tol = rospy.get_param('~identical_tolerance_m')
        start_tick = rospy.get_param('~file_start_tick')
        path = os.path.join(rospkg.RosPack().get_path('swarm_transport'), 'config', 'missions',
                            'thesis_transport.yaml')
        busy = Busy(rospy.get_param('~busy_processes'))
        try:
            runs = [missions_file_run(3, robots, ticks, timeout, path, 7)
                    for _ in range(rospy.get_param('~file_runs'))]
        finally:
            busy.stop()
        first, phases = runs[0]
        self.assertEqual(phases[:2], [(0, start_tick), (1, start_tick)],
                         'QUEUED and GATHERING should both be at tick %d: %s'
                         % (start_tick, phases))
        self.assertIn(3, [s for s, _ in phases], 'the mission never reached TRANSPORT: %s'
                      % phases)
        for i, (other, other_phases) in enumerate(runs[1:], 2):
            self.assertEqual(other_phases, phases, 'run %d' % i)
            for t in range(ticks + 1):
                for rid in range(robots):
                    self.assertLessEqual(st.moved(first[t][rid], other[t][rid]), tol,
                                         'run %d, tick %d: robot %d at %s vs %s'
                                         % (i, t, rid, other[t][rid], first[t][rid]))

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
