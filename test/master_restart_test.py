#!/usr/bin/env python3
"""A ROS master restart (issue 11): ROS 1 nodes do not register again with a new master. A
swarm runs on a master of the test's own (simulator, dispatcher and robots, a process each, in
lock-step); the master is killed and started again on the same port. Every node must notice
within the bound stated in the .test file, say so in one line, and exit (non-zero), and the
launch with it - instead of running on, unreachable, as before."""

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
import xmlrpc.client

import rospy
import rostest

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class MasterRestart(unittest.TestCase):

    def setUp(self):
        self.port = int(os.environ.get('ST_MASTER_RESTART_PORT', '0')) or self.free_port()
        self.uri = 'http://127.0.0.1:%d' % self.port
        self.env = dict(os.environ, ROS_MASTER_URI=self.uri)
        self.env['ROS_HOME'] = tempfile.mkdtemp(prefix='master_restart_')
        self.addCleanup(shutil.rmtree, self.env['ROS_HOME'], True)
        self.procs = []
        self.core_pids = []  # rosmaster and rosout of each roscore (sessions of their own)
        self.addCleanup(self.stop_all)

    @staticmethod
    def free_port():
        import socket
        with socket.socket() as s:
            s.bind(('127.0.0.1', 0))
            return s.getsockname()[1]

    def start(self, *cmd):
        log = tempfile.NamedTemporaryFile('w+', prefix='master_restart_', suffix='.log',
                                          delete=False)
        proc = subprocess.Popen(cmd, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                start_new_session=True)
        self.procs.append((proc, log))
        return proc, log

    def stop_all(self):
        st.stop_process_groups([proc for proc, _ in self.procs])
        for _, log in self.procs:
            os.unlink(log.name)
        for pid in self.core_pids:
            if st.process_alive(pid):
                os.kill(pid, signal.SIGKILL)

    def core_up(self):
        """Waits for the roscore just started; remembers its master's and rosout's pids."""
        self.assertTrue(st.wait_for(lambda: '/rosout' in self.nodes(), 30), 'no roscore')
        self.core_pids += [self.master().getPid('/test')[2], self.pid_of('/rosout')]

    def master(self):
        return xmlrpc.client.ServerProxy(self.uri)

    def nodes(self):
        try:
            _, _, state = self.master().getSystemState('/test')
        except OSError:  # no master (yet)
            return set()
        names = set()
        for kind in state:
            for _, members in kind:
                names.update(members)
        return names

    def ticked(self):
        """True when the swarm published a tick (rostopic on the test's own master)."""
        try:
            out = subprocess.run(['rostopic', 'echo', '-n', '1', '/flock/world_poses/tick'],
                                 env=self.env, capture_output=True, text=True, timeout=10)
        except subprocess.TimeoutExpired:
            return False
        return out.returncode == 0 and out.stdout.split()[:1] != [] and \
            out.stdout.split()[0].isdigit()

    def master_up(self):
        try:
            return self.master().getPid('/test')[0] == 1
        except OSError:
            return False

    def pid_of(self, name):
        _, _, api = self.master().lookupNode('/test', name)
        return xmlrpc.client.ServerProxy(api).getPid('/test')[2]

    def test_every_node_stops_after_a_master_restart(self):
        master, _ = self.start('roscore', '-p', str(self.port))
        self.core_up()
        robots = g('robots')
        wanted = {'/simulator', '/mission_dispatcher'} | {'/robot_%d/robot' % i
                                                           for i in range(robots)}
        launch, launch_log = self.start(
            'roslaunch', '--wait', 'swarm_transport', 'swarm.launch', 'robots:=%d' % robots,
            'lockstep:=true', 'seed:=%d' % g('seed'))
        self.assertTrue(st.wait_for(lambda: wanted <= self.nodes(), g('timeout_s')),
                        'the swarm did not come up')
        # Listed is not yet up: a node still registering when the master goes blocks in
        # roscpp's retry loop and registers with the new master, which then knows it (the
        # simulator ran on once, 2026-11-28). A tick needs every node's answer: all are up.
        self.assertTrue(st.wait_for(self.ticked, g('timeout_s'), period=0.5),
                        'the swarm never ticked')
        pids = {name: self.pid_of(name) for name in wanted}
        # The master goes (SIGKILL: no goodbye; roscore starts rosmaster and rosout in sessions
        # of their own, so each by its pid) and comes back on the same port.
        os.killpg(master.pid, signal.SIGKILL)
        for pid in self.core_pids:
            os.kill(pid, signal.SIGKILL)
        master.wait()
        self.assertTrue(st.wait_for(lambda: not self.master_up(), 10), 'the master still runs')
        time.sleep(g('down_s'))
        self.start('roscore', '-p', str(self.port))
        self.core_up()
        restarted = time.monotonic()
        stopped = st.wait_for(lambda: not any(st.process_alive(p) for p in pids.values()),
                              g('max_s_to_stop'))
        launch_log.flush()
        with open(launch_log.name) as f:
            text = f.read()
        self.assertTrue(
            stopped, 'still running %.0f s after the restart: %s; the launch said:\n%s'
            % (g('max_s_to_stop'), [n for n, p in pids.items() if st.process_alive(p)],
               text[-4000:]))
        took = time.monotonic() - restarted
        self.assertTrue(st.wait_for(lambda: launch.poll() is not None, 30),
                        'roslaunch ran on without its simulator')
        launch_log.flush()
        with open(launch_log.name) as f:
            text = f.read()
        self.assertIn('restarted and does not know this node', text, text[-3000:])
        # None came back on the new master by itself (nothing runs on unregistered).
        self.assertFalse(wanted & self.nodes())
        rospy.loginfo('every node stopped %.1f s after the master came back', took)


if __name__ == '__main__':
    rospy.init_node('master_restart_test')
    rostest.rosrun('swarm_transport', 'master_restart', MasterRestart, sys.argv)
