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

import swarm_testing as st

NAMES = ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE']


def g(key):
    return rospy.get_param('~' + key)


def ip(*args):
    subprocess.run(('ip',) + args, check=True, capture_output=True, text=True)


class AcrossHosts(unittest.TestCase):

    def setUp(self):
        tag = 'st%d' % (os.getpid() % 100000)
        self.ns = {'core': tag + 'c', 'a': tag + 'a', 'b': tag + 'b'}
        self.addr = {'core': '10.77.0.1', 'a': '10.77.0.2', 'b': '10.77.0.3'}
        self.procs = []
        self.tmp = tempfile.mkdtemp(prefix='across_hosts_')
        self.addCleanup(shutil.rmtree, self.tmp, True)
        try:
            ip('netns', 'add', self.ns['core'])
        except (OSError, subprocess.CalledProcessError) as e:
            self.skipTest('network namespaces are not available here (%s)'
                          % getattr(e, 'stderr', e))
        self.addCleanup(self.teardown_net)
        core = self.ns['core']
        ip('-n', core, 'link', 'set', 'lo', 'up')
        ip('-n', core, 'link', 'add', 'br0', 'type', 'bridge')
        ip('-n', core, 'addr', 'add', self.addr['core'] + '/24', 'dev', 'br0')
        ip('-n', core, 'link', 'set', 'br0', 'up')
        for host in ('a', 'b'):
            ns = self.ns[host]
            ip('netns', 'add', ns)
            ip('-n', ns, 'link', 'set', 'lo', 'up')
            outer, inner = tag + 'v' + host, tag + 'p' + host
            ip('link', 'add', outer, 'type', 'veth', 'peer', 'name', inner)
            ip('link', 'set', outer, 'netns', core)
            ip('link', 'set', inner, 'netns', ns)
            ip('-n', core, 'link', 'set', outer, 'master', 'br0')
            ip('-n', core, 'link', 'set', outer, 'up')
            ip('-n', ns, 'addr', 'add', self.addr[host] + '/24', 'dev', inner)
            ip('-n', ns, 'link', 'set', inner, 'up')

    def teardown_net(self):
        st.stop_process_groups([proc for proc, _ in self.procs])
        for ns in self.ns.values():
            subprocess.run(['ip', 'netns', 'del', ns], capture_output=True)

    def env(self, host):
        env = dict(os.environ)
        env.pop('ROS_HOSTNAME', None)  # it would win over ROS_IP
        env['ROS_IP'] = self.addr[host]
        env['ROS_MASTER_URI'] = 'http://%s:%d' % (self.addr['core'], g('port'))
        env['ROS_HOME'] = os.path.join(self.tmp, host)
        return env

    def start(self, host, *cmd):
        log = open(os.path.join(self.tmp, '%s-%d.log' % (host, len(self.procs))), 'w')
        proc = subprocess.Popen(('ip', 'netns', 'exec', self.ns[host]) + cmd, env=self.env(host),
                                stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.procs.append((proc, log.name))
        return proc

    def logs(self):
        out = []
        for _, name in self.procs:
            with open(name) as f:
                out.append('--- %s\n%s' % (name, f.read()[-3000:]))
        return '\n'.join(out)

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
            ['ip', 'netns', 'exec', self.ns['core'], sys.executable,
             os.path.join(pkg, 'test', 'across_hosts_watch.py'), str(g('mission_id')),
             str(g('timeout_s'))],
            env=self.env('core'), capture_output=True, text=True, timeout=g('timeout_s') + 60)
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
