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
                             start_new_session=True, preexec_fn=default_sigint)
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
        # Newest first: roslaunch before the master, each by its own process group id; the
        # nodes a roslaunch started too (stop_process_trees).
        stop_process_trees([p for p, _, _ in self.procs])
        for _, _, log in self.procs:
            log.close()
        self.procs = []


# Longer than roslaunch's own escalation (SIGINT, 15 s, SIGTERM, 2 s, then SIGKILL: roslaunch
# nodeprocess.py), so that a roslaunch still stops its slow nodes itself.
STOP_TIMEOUT_S = 20.0


def _stat(pid):
    """(ppid, start time) of process `pid` from /proc/<pid>/stat, or None when it is gone."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
    except (OSError, IndexError):
        return None
    return int(fields[1]), int(fields[19])


def descendants(pid):
    """{pid: start time} of every process below `pid` now (children, their children, ...)."""
    children = {}
    for name in os.listdir('/proc'):
        if name.isdigit():
            st = _stat(int(name))
            if st:
                children.setdefault(st[0], []).append((int(name), st[1]))
    out, todo = {}, [pid]
    while todo:
        for child, start in children.get(todo.pop(), []):
            if child not in out:
                out[child] = start
                todo.append(child)
    return out


def _still_running(pid, start):
    st = _stat(pid)
    return bool(st) and st[1] == start and process_alive(pid)


def stop_process_trees(procs, timeout=STOP_TIMEOUT_S):
    """Stops subprocess.Popen processes started with start_new_session=True, one after the
    other, last first: SIGINT to its process group, SIGKILL to the group after `timeout` s.
    Then SIGKILL to every process that was below one of them when the stop began and still
    runs (same pid and start time). roslaunch starts each node in a session of its own
    (os.setsid), out of the group's reach: without the last step a node that outlives its
    killed roslaunch runs on as an orphan. Returns the pids killed that way."""
    below = {}
    for proc in procs:
        if proc.poll() is None:
            below.update(descendants(proc.pid))
    for proc in reversed(procs):
        if proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait()
    # What a SIGKILL to its group just hit may take a moment to go: wait up to 1 s for that.
    deadline = time.time() + 1.0
    while any(_still_running(p, s) for p, s in below.items()) and time.time() < deadline:
        time.sleep(0.05)
    orphans = []
    for pid, start in sorted(below.items()):
        if _still_running(pid, start):
            try:
                os.kill(pid, signal.SIGKILL)
                orphans.append(pid)
            except ProcessLookupError:
                pass
    if orphans:
        log('[swarm_transport] killed %d process(es) left behind by a stopped parent: %s'
            % (len(orphans), ' '.join(map(str, orphans))))
    return orphans


def default_sigint():
    """SIGINT as by default (a preexec_fn): under nohup or CI it may arrive ignored and would
    stay ignored in a child, which then ignores the stop request."""
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
