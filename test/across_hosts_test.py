#!/usr/bin/env python3
"""A swarm across hosts (issue 11): three network namespaces on this machine stand in for three
machines on one network (a bridge, veth pairs, one IP each). The core runs the master, the
simulator and the dispatcher (swarm.launch deploy:=none, ROS_IP of the core); two robot hosts
run half of the robots each (robot_host.launch, ROS_IP of their own). The thesis mission
(config/missions/thesis_transport.yaml) must end DONE with every phase in order, and every
node must be registered under the address of its own namespace.
Needs root (CAP_NET_ADMIN) for `ip netns`; without it the test is skipped and says why."""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rospy
import rostest

from netns_hosts import NetHosts, Unavailable

NAMES = ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE']


def g(key):
    return rospy.get_param('~' + key)


class AcrossHosts(unittest.TestCase):

    def setUp(self):
        tmp = tempfile.mkdtemp(prefix='across_hosts_')
        self.addCleanup(shutil.rmtree, tmp, True)
        try:
            self.net = NetHosts('st%d' % (os.getpid() % 100000), tmp, g('port'))
        except Unavailable as e:
            self.skipTest(str(e))
        self.addCleanup(self.net.close)
        self.addr, self.start, self.logs = self.net.addr, self.net.start, self.net.logs

    def test_the_thesis_mission_across_three_hosts(self):
        pkg = rospkg.RosPack().get_path('swarm_transport')
        robots, split = g('robots'), g('split')
        self.start('core', 'roslaunch', '-p', str(g('port')), 'swarm_transport', 'swarm.launch',
                   'deploy:=none', 'lockstep:=true', 'robots:=%d' % robots,
                   'seed:=%d' % g('seed'),
                   'missions_file:=%s/config/missions/thesis_transport.yaml' % pkg)
        self.start('a', 'roslaunch', '--wait', 'swarm_transport', 'robot_host.launch',
                   'from:=0', 'to:=%d' % split, 'clock:=lockstep', 'name:=a')
        self.start('b', 'roslaunch', '--wait', 'swarm_transport', 'robot_host.launch',
                   'from:=%d' % split, 'to:=%d' % robots, 'clock:=lockstep', 'name:=b')
        watch = subprocess.run(
            self.net.command('core', sys.executable,
                             os.path.join(pkg, 'test', 'across_hosts_watch.py'),
                             str(g('mission_id')), str(g('timeout_s'))),
            env=self.net.env('core'), capture_output=True, text=True, timeout=g('timeout_s') + 60)
        lines = watch.stdout.splitlines()
        states = [l.split()[1] for l in lines if l.startswith('STATUS ')]
        self.assertEqual(watch.returncode, 0, 'mission not DONE: %s\n%s\n%s'
                         % (states, watch.stderr[-2000:], self.logs()))
        self.assertEqual(states, NAMES, states)
        nodes = dict(l.split()[1:3] for l in lines if l.startswith('NODE '))
        for node, host in (('/simulator', 'core'), ('/mission_dispatcher', 'core'),
                           ('/robot_host_a', 'a'), ('/robot_host_b', 'b')):
            self.assertIn(node, nodes, nodes)
            self.assertIn('//%s:' % self.addr[host], nodes[node],
                          '%s is registered as %s, not on %s' % (node, nodes[node], host))


if __name__ == '__main__':
    rospy.init_node('across_hosts_test')
    rostest.rosrun('swarm_transport', 'across_hosts', AcrossHosts, sys.argv)
