#!/usr/bin/env python3
"""The README's five-minute tour runs as written (issue 26): every command of its code blocks,
read from README.md itself, in order, as a user types them into one terminal - `source` and
`export` change the environment of the commands after them, a command ending in `&` runs in the
background and the next one starts once it is up (the swarm: its simulator publishes
/flock/world_poses and the dispatcher offers its submit service; rviz: it subscribes
/flock/markers and is still running `rviz_up_s` later), every other command must exit 0 within
`command_s`, and the mission `watch` must end at DONE. The tour must hold every step: a
swarm, rviz, a mission and its watch, a scenario and an experiment.

What differs from a user's terminal, and why: the master port of the tour (11411) becomes a
free port and `/tmp/` a directory of this test (two runs at once cannot collide); ST_NO_BUILD=1
(scripts/test has built; a nested catkin_make would race it); rviz draws on a virtual display
(Xvfb, software GL) unless DISPLAY is set. Background commands are stopped at the end as
`kill %2 %1` would, by their process groups."""

import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import rosgraph
import rospy
import rostest

import swarm_testing as st

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
TOUR_HEADING = '## A five-minute tour'
TOUR_PORT = '11411'


def tour_commands(readme):
    """The command lines of the tour's shell code blocks, in order."""
    text = open(readme).read()
    start = text.index(TOUR_HEADING)
    end = text.find('\n## ', start + len(TOUR_HEADING))
    section = text[start:end if end >= 0 else len(text)]
    commands = []
    for block in re.findall(r'```(?:bash|sh)?\n(.*?)```', section, flags=re.S):
        commands += [line.strip() for line in block.splitlines()
                     if line.strip() and not line.strip().startswith('#')]
    return commands


def _free_port():
    import socket
    sock = socket.socket()
    sock.bind(('127.0.0.1', 0))
    port = sock.getsockname()[1]
    sock.close()
    return port


class ReadmeTour(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.command_s = rospy.get_param('~command_s')
        cls.ready_s = rospy.get_param('~ready_s')
        cls.rviz_up_s = rospy.get_param('~rviz_up_s')
        cls.tmp = tempfile.mkdtemp(prefix='readme_tour_')
        cls.port = str(_free_port())
        cls.background = []
        cls.xvfb = None

    @classmethod
    def tearDownClass(cls):
        st.stop_process_groups(cls.background)
        if cls.xvfb is not None:
            st.stop_process_groups([cls.xvfb])
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def env(self):
        env = dict(os.environ, ST_NO_BUILD='1', ROS_HOME=os.path.join(self.tmp, 'ros_home'),
                   PATH='/usr/bin:' + os.environ.get('PATH', ''))
        env.pop('ROS_HOSTNAME', None)
        if not env.get('DISPLAY'):
            env.update(DISPLAY=self.virtual_display(), LIBGL_ALWAYS_SOFTWARE='1')
        return env

    def virtual_display(self):
        number = next(n for n in range(91, 200)
                      if not os.path.exists('/tmp/.X11-unix/X%d' % n)
                      and not os.path.exists('/tmp/.X%d-lock' % n))
        self.__class__.xvfb = subprocess.Popen(
            ['Xvfb', ':%d' % number, '-screen', '0', '1280x1024x24', '-nolisten', 'tcp'],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        self.assertTrue(st.wait_for(lambda: os.path.exists('/tmp/.X11-unix/X%d' % number), 20,
                                    0.1), 'Xvfb did not start')
        return ':%d' % number

    def localise(self, command):
        return command.replace(TOUR_PORT, self.port).replace('/tmp/', self.tmp + '/')

    def master(self, env):
        return rosgraph.Master('/readme_tour', master_uri=env['ROS_MASTER_URI'])

    def state(self, env):
        try:
            return self.master(env).getSystemState()
        except Exception:  # not up yet
            return [], [], []

    def wait_ready(self, command, proc, env):
        """Waits until a background command is up (what a user waits for before the next)."""
        if ' swarm.launch' in command:
            def up():
                pubs, _, services = self.state(env)
                return (any(t == '/flock/world_poses' and '/simulator' in n for t, n in pubs)
                        and any(s == '/mission_dispatcher/submit' for s, _ in services))
            what, limit = 'the swarm (simulator and dispatcher)', self.ready_s
        elif 'rviz' in command:
            def up():
                _, subs, _ = self.state(env)
                return any(t == '/flock/markers' and any('rviz' in n for n in nodes)
                           for t, nodes in subs)
            what, limit = 'rviz (a subscriber of /flock/markers)', self.ready_s
        else:
            self.fail('the tour backgrounds a command this test does not know: %s' % command)
        ok = st.wait_for(lambda: up() or proc.poll() is not None, limit, 0.2)
        self.assertIsNone(proc.poll(), '%s exited (%s): %s' % (what, proc.poll(),
                                                                self.tail(proc)))
        self.assertTrue(ok and up(), '%s not up after %g s: %s' % (what, limit, self.tail(proc)))
        if 'rviz' in command:
            time.sleep(self.rviz_up_s)  # it must stay up drawing, not crash on its first frame
            self.assertIsNone(proc.poll(), 'rviz exited after it started: %s' % self.tail(proc))

    def tail(self, proc):
        with open(proc.log_path) as log:
            return log.read()[-1500:]

    def test_every_tour_command_runs(self):
        commands = tour_commands(os.path.join(ROOT, 'README.md'))
        joined = '\n'.join(commands)
        for step in ('swarm.launch', 'rviz', 'mission transport', 'mission watch',
                     'scripts/scenario run', 'scripts/experiment run'):
            self.assertIn(step, joined, 'the tour lost its step %r' % step)
        env = self.env()
        for number, written in enumerate(commands):
            command = self.localise(written)
            rospy.loginfo('tour %d: %s', number + 1, command)
            if command.startswith('source '):
                out = subprocess.run(['bash', '-c', command + ' && env -0'], cwd=ROOT, env=env,
                                     stdout=subprocess.PIPE, check=True).stdout
                env = dict(item.split('=', 1) for item in out.decode().split('\0') if '=' in item)
            elif command.startswith('export '):
                env.update(word.split('=', 1) for word in shlex.split(command)[1:])
            elif command.endswith('&'):
                log_path = os.path.join(self.tmp, 'background_%d.log' % number)
                proc = subprocess.Popen(['bash', '-c', 'exec ' + command[:-1]], cwd=ROOT,
                                        env=env, stdout=open(log_path, 'w'),
                                        stderr=subprocess.STDOUT, start_new_session=True)
                proc.log_path = log_path
                self.background.append(proc)
                self.wait_ready(command, proc, env)
            else:
                proc = subprocess.run(['bash', '-c', command], cwd=ROOT, env=env,
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                      universal_newlines=True, timeout=self.command_s)
                self.assertEqual(proc.returncode, 0, 'tour command %r exited %d:\n%s'
                                 % (written, proc.returncode, proc.stdout[-3000:]))
                if 'mission watch' in command:
                    self.assertIn('DONE', proc.stdout)
                words = shlex.split(command)
                if 'scripts/experiment' in words[0] and '--out' in words:
                    out = words[words.index('--out') + 1]
                    self.assertTrue(os.path.isfile(os.path.join(out, 'summary.csv')), out)
        # `kill %2 %1`: the background commands end (roslaunch takes its master along).
        st.stop_process_groups(self.background)
        for proc in self.background:
            self.assertIsNotNone(proc.poll())


if __name__ == '__main__':
    rospy.init_node('readme_tour_test')
    rostest.rosrun('swarm_transport', 'readme_tour', ReadmeTour, sys.argv)
