"""Private ROS sessions for the project's scripts: a master on a free loopback port, a
roslaunch in it, and clean shutdown by pid (never by process name)."""

import os
import signal
import socket
import subprocess
import sys
import time

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..'))
WS = os.path.join(ROOT, '.catkin_ws')


def free_port():
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    port = s.getsockname()[1]
    s.close()
    return port


def workspace_env(port):
    """The environment of the built workspace (devel/setup.bash), with a private master."""
    out = subprocess.check_output(
        ['bash', '-c', 'source "%s/devel/setup.bash" && env -0' % WS])
    env = dict(kv.split('=', 1) for kv in out.decode().split('\0') if '=' in kv)
    env['PATH'] = '/usr/bin:/bin:' + env.get('PATH', '')
    env['ROS_MASTER_URI'] = 'http://127.0.0.1:%d' % port
    env['ROS_IP'] = '127.0.0.1'
    env['ROS_HOSTNAME'] = '127.0.0.1'
    env['PYTHONUNBUFFERED'] = '1'
    env.setdefault('ROS_HOME', os.path.join(WS, 'ros_home'))
    return env


class PrivateRos(object):
    """A rosmaster on a free port plus the processes started in it; stops them all by pid."""

    def __init__(self, log_dir=None, quiet=True):
        self.port = free_port()
        self.env = workspace_env(self.port)
        self.log_dir = log_dir or os.path.join(WS, 'logs', 'run-%d' % self.port)
        os.makedirs(self.log_dir, exist_ok=True)
        self.env['ROS_LOG_DIR'] = self.log_dir
        self.quiet = quiet
        self.procs = []

    def __enter__(self):
        # A SIGTERM (timeout, CI) must still stop what this session started: turn it into an
        # exception so that __exit__ runs.
        signal.signal(signal.SIGTERM, _terminate)
        self.start_master()
        os.environ.update({k: self.env[k] for k in (
            'ROS_MASTER_URI', 'ROS_IP', 'ROS_HOSTNAME', 'ROS_LOG_DIR', 'ROS_PACKAGE_PATH',
            'ROS_HOME')})
        for k in ('PYTHONPATH', 'CMAKE_PREFIX_PATH', 'LD_LIBRARY_PATH', 'ROS_ROOT',
                  'ROS_DISTRO', 'ROS_ETC_DIR', 'ROSLISP_PACKAGE_DIRECTORIES'):
            if k in self.env:
                os.environ[k] = self.env[k]
        return self

    def __exit__(self, *exc):
        self.stop()

    def start(self, args, name):
        log = open(os.path.join(self.log_dir, name + '.log'), 'w')
        # Under nohup or CI, SIGINT may arrive ignored and would stay ignored in the children:
        # then rosmaster and roslaunch ignore the stop request and every stop waits 15 s.
        p = subprocess.Popen(args, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True, preexec_fn=_default_sigint)
        self.procs.append((p, name, log))
        return p

    def start_master(self):
        self.start(['rosmaster', '--core', '-p', str(self.port)], 'rosmaster')
        deadline = time.time() + 20
        while time.time() < deadline:
            try:
                socket.create_connection(('127.0.0.1', self.port), timeout=0.5).close()
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError('rosmaster did not come up on port %d' % self.port)

    def launch(self, launch_file, launch_args, name='roslaunch'):
        # No --wait: with it this roslaunch spins forever after finding the master; the master
        # is known to be up here (start_master waited for its port).
        args = ['roslaunch', '-p', str(self.port), 'swarm_transport', launch_file]
        args += ['%s:=%s' % (k, v) for k, v in launch_args.items()]
        return self.start(args, name)

    def alive(self, name):
        return any(p.poll() is None for p, n, _ in self.procs if n == name)

    def stop(self):
        # Newest first: roslaunch before the master, each by its own process group id.
        for p, name, log in reversed(self.procs):
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGINT)
                    p.wait(timeout=15)
                except (subprocess.TimeoutExpired, ProcessLookupError):
                    try:
                        os.killpg(p.pid, signal.SIGKILL)
                    except ProcessLookupError:
                        pass
                    p.wait()
            log.close()
        self.procs = []


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _terminate(signum, _frame):
    raise SystemExit(128 + signum)


def process_alive(pid):
    """True while process `pid` runs (a zombie that exited but was not reaped yet counts as
    gone)."""
    try:
        with open('/proc/%d/status' % pid) as f:
            for line in f:
                if line.startswith('State:'):
                    return 'Z' not in line.split()[1]
    except OSError:
        return False
    return True


def log(msg):
    sys.stdout.write(msg + '\n')
    sys.stdout.flush()
