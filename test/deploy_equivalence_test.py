#!/usr/bin/env python3
"""deploy:=host (all robots in one robot_host process) behaves exactly like deploy:=process (a
robot process each): in lock-step with the same seed both give identical poses at tick N."""

import os
import subprocess
import sys
import unittest

import rospy
import rostest

import swarm_testing as st


def poses(deploy, seed, robots, ticks, timeout):
    log = st.PositionLog()
    swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks,
                            deploy=deploy)
    try:
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('deploy %s: the run stopped at tick %d'
                                 % (deploy, log.latest_tick()))
        return log.at(0), log.at(ticks)
    finally:
        swarm.shutdown()
        log.close()


class DeployEquivalence(unittest.TestCase):

    def test_host_and_processes_end_identical(self):
        robots = rospy.get_param('~robots')
        ticks = rospy.get_param('~ticks')
        seed = rospy.get_param('~seed')
        timeout = rospy.get_param('~timeout_s')
        tol_m = rospy.get_param('~identical_tolerance_m')
        tol_deg = rospy.get_param('~identical_tolerance_deg')
        start, by_process = poses('process', seed, robots, ticks, timeout)
        _, by_host = poses('host', seed, robots, ticks, timeout)
        self.assertEqual(sorted(by_process), list(range(robots)))
        self.assertEqual(sorted(by_host), list(range(robots)))
        for rid in range(robots):
            self.assertLessEqual(st.moved(by_process[rid], by_host[rid]), tol_m,
                                 'robot %d ended at %s as a process but %s in the host'
                                 % (rid, by_process[rid], by_host[rid]))
            turn = abs(by_process[rid][2] - by_host[rid][2]) % 360.0
            self.assertLessEqual(min(turn, 360.0 - turn), tol_deg,
                                 'robot %d heading %s vs %s' % (rid, by_process[rid],
                                                                by_host[rid]))
        self.assertGreater(max(st.moved(start[r], by_host[r]) for r in range(robots)),
                           rospy.get_param('~min_move_m'), 'nobody moved: a trivial run')

    def test_host_rejects_bad_parameters(self):
        cases = ((['_from:=5', '_to:=5'], '~to must be in'),
                 (['_to:=3', '_threads:=0'], '~threads must be in'),
                 (['_to:=3', '_comm:=shout'], '~comm must be'))
        for i, (args, expect) in enumerate(cases):
            # A node name per case: private parameters from the command line stay set.
            p = subprocess.run(['rosrun', 'swarm_transport', 'robot_host',
                                '__name:=robot_host_bad%d' % i] + args, env=os.environ.copy(),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
            out = p.stdout.decode(errors='replace')
            self.assertNotEqual(p.returncode, 0, '%s exited 0:\n%s' % (args, out))
            self.assertIn(expect, out)
            self.assertEqual(len([l for l in out.splitlines() if 'FATAL' in l]), 1, out)


if __name__ == '__main__':
    rospy.init_node('deploy_equivalence_test')
    rostest.rosrun('swarm_transport', 'deploy_equivalence', DeployEquivalence, sys.argv)
