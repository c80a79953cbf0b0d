#!/usr/bin/env python3
"""Invalid parameters make a node exit non-zero with one clear message."""

import os
import subprocess
import sys
import unittest

import rospy
import rostest


def run_node(node, args, swarm_params):
    for k, v in swarm_params.items():
        rospy.set_param('/swarm/' + k, v)
    try:
        p = subprocess.run(['rosrun', 'swarm_transport', node] + args, env=os.environ.copy(),
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
    finally:
        for k in swarm_params:
            rospy.delete_param('/swarm/' + k)
    return p.returncode, p.stdout.decode(errors='replace')


class BadParams(unittest.TestCase):

    def check(self, node, args, params, expect):
        code, out = run_node(node, args, params)
        self.assertNotEqual(code, 0, '%s %s with %s exited 0:\n%s' % (node, args, params, out))
        self.assertIn(expect, out, 'no clear message:\n' + out)
        fatal = [l for l in out.splitlines() if 'FATAL' in l]
        self.assertEqual(len(fatal), 1, 'expected exactly one FATAL line:\n' + out)

    def test_robot_without_id(self):
        self.check('robot', ['__name:=robot_bad1'], {}, '~id must be set')

    def test_robot_negative_range(self):
        self.check('robot', ['_id:=3', '__name:=robot_bad2'], {'local_range_m': -1.0},
                   'local_range_m')

    def test_robot_nan_speed(self):
        self.check('robot', ['_id:=3', '__name:=robot_bad3'], {'speed_m_per_tick': float('nan')},
                   'speed_m_per_tick')

    def test_simulator_bad_clock(self):
        self.check('simulator', ['_clock:=sometimes', '__name:=sim_bad'], {}, 'clock')

    def test_simulator_bad_placement(self):
        self.check('simulator', ['_placement:=grid', '__name:=sim_bad_placement'], {},
                   "placement must be 'random', 'corner' or 'file'")

    def test_simulator_negative_real_time_factor(self):
        self.check('simulator', ['_real_time_factor:=-1.0', '__name:=sim_bad_pacing'], {},
                   'real_time_factor must be a finite number >= 0')

    def test_dispatcher_missing_events_file(self):
        self.check('mission_dispatcher', ['_events_file:=/no/such/events.yaml',
                                          '__name:=dispatcher_bad_events'], {},
                   '~events_file /no/such/events.yaml')

    def test_robot_host_bad_deploy(self):
        # A robot_host runs deploy host or host_sim; a typo or another deployment is refused.
        self.check('robot_host', ['_to:=2', '_deploy:=host-sim', '__name:=host_bad_deploy'], {},
                   "~deploy must be 'process', 'host', 'host_sim' or 'none' but is 'host-sim'")
        self.check('robot_host', ['_to:=2', '_deploy:=process', '__name:=host_bad_deploy2'], {},
                   "~deploy of a robot_host must be 'host' or 'host_sim' but is 'process'")


if __name__ == '__main__':
    rospy.init_node('bad_params_test')
    rostest.rosrun('swarm_transport', 'bad_params', BadParams, sys.argv)
