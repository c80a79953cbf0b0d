"""What scripts/soak does to a running swarm (issue 29): the node processes it watches (pids,
memory, file descriptors), the fault schedule drawn from the seed, and each fault's injection.

Every process is found through its node's own XML-RPC API (getPid) and stopped by pid; nothing
is stopped by name."""

import os
import random
import signal
import time

from swarm_transport.bench_proc import status_kb
from swarm_transport.st_ros import process_alive

KINDS = ('robot_kill', 'robot_stop', 'dispatcher_restart', 'recorder_restart', 'radio_loss',
         'flood')
# Asked for by name only (--faults), not in the default mix: SIGKILL (and respawn) of the first
# leader of a mission while it gathers - the moment of the one robot crash of a soak hour
# (docs/reliability.md), hit by a robot_kill only by chance.
EXTRA_KINDS = ('leader_kill',)
ALL_KINDS = KINDS + EXTRA_KINDS
DISPATCHER = '/mission_dispatcher'
RECORDER = '/recorder'
SIMULATOR = '/simulator'


def robot_node(rid, deploy):
    return '/robot_host' if deploy == 'host' else '/robot_%d/robot' % rid


def node_pid(name, timeout_s=3.0):
    """The pid of node `name` (its XML-RPC getPid), or None when it is not registered or does
    not answer within `timeout_s` (a stopped process accepts the connection and never answers:
    without the timeout the soak would wait for the robot it stopped itself)."""
    import xmlrpc.client
    import rosgraph
    import rosnode

    class Transport(xmlrpc.client.Transport):
        def make_connection(self, host):
            conn = super().make_connection(host)
            conn.timeout = timeout_s
            return conn
    try:
        api = rosnode.get_api_uri(rosgraph.Master('/soak'), name, skip_cache=True)
        if not api:
            return None
        proxy = xmlrpc.client.ServerProxy(api, transport=Transport())
        code, _, pid = proxy.getPid('/soak')
        return pid if code == 1 else None
    except Exception:  # noqa: BLE001 - a node that is gone answers in many ways
        return None


def fd_count(pid):
    try:
        return len(os.listdir('/proc/%d/fd' % pid))
    except OSError:
        return None


class Schedule(object):
    """Faults drawn from the seed: the kinds (all of KINDS, or those asked for) in shuffled
    rounds (so a short soak still sees each kind), gaps uniform in [gap_min_s, gap_max_s], the robots and loss levels drawn alongside."""

    def __init__(self, seed, robots, gap_min_s, gap_max_s, first_s, kinds=KINDS):
        self.rng = random.Random(seed)
        self.kinds = tuple(kinds)
        self.robots = robots
        self.gap = (gap_min_s, gap_max_s)
        self.next_s = first_s
        self.queue = []

    def draw(self):
        """(at_s, kind, robot, loss) of the next fault."""
        if not self.queue:
            self.queue = list(self.kinds)
            self.rng.shuffle(self.queue)
        kind = self.queue.pop(0)
        at = self.next_s
        self.next_s += self.rng.uniform(*self.gap)
        return at, kind, self.rng.randrange(self.robots), round(self.rng.uniform(0.3, 0.8), 2)


class Watch(object):
    """The long-lived nodes: each incarnation (pid) with its memory and descriptors sampled.
    A pid that disappears without the soak having killed it is a crash."""

    def __init__(self, warmup_s):
        self.warmup_s = warmup_s
        self.incarnations = {}  # pid -> dict(name, start, samples [(t, rss_kb, fds)], end)
        self.current = {}       # node name -> pid
        self.killed = set()     # pids the soak killed on purpose
        self.stopped = set()    # pids the soak stopped (SIGSTOP) and not yet continued
        self.crashes = []       # (t, name, pid)

    def track(self, name, now):
        if self.current.get(name) in self.stopped:
            return self.current[name]  # a stopped node does not answer: nothing to ask
        pid = node_pid(name)
        if pid is None or pid in self.incarnations:
            if pid is not None:
                self.current[name] = pid
            return pid
        self.current[name] = pid
        self.incarnations[pid] = {'name': name, 'start': now, 'samples': [], 'end': None}
        return pid

    def kill(self, name, sig=signal.SIGKILL):
        pid = self.current.get(name)
        if pid is None:
            pid = node_pid(name)
        if pid is None:
            return None
        if not process_alive(pid):
            # Killed by an earlier fault and not back yet (faults closer together than a
            # respawn): its pid is stale. The node as registered now, if it is back.
            pid = node_pid(name)
            if pid is None or not process_alive(pid):
                return None
        if sig == signal.SIGKILL:
            self.killed.add(pid)
        elif sig == signal.SIGSTOP:
            self.stopped.add(pid)
        try:
            os.kill(pid, sig)
        except ProcessLookupError:  # died between the look and the signal
            return None
        return pid

    def resume(self, pid):
        """SIGCONT to a process the soak stopped."""
        self.stopped.discard(pid)
        os.kill(pid, signal.SIGCONT)

    def sample(self, now):
        seen = set()
        for pid, inc in self.incarnations.items():
            if inc['end'] is not None or pid in seen:
                continue
            seen.add(pid)
            if not process_alive(pid):
                inc['end'] = now
                if pid not in self.killed:
                    self.crashes.append((now, inc['name'], pid))
                continue
            inc['samples'].append((now, status_kb(pid, 'VmRSS'), fd_count(pid)))

    def growth(self, by_node=None):
        """(max RSS growth %, its node, max fd growth, its node) over the incarnations that
        lived past twice the warm-up: from the first sample after the warm-up to the last.
        `by_node`, a dict, gets each judged incarnation's 'name (pid)': [RSS kB first, last]."""
        rss = (0.0, '')
        fds = (0, '')
        for pid, inc in self.incarnations.items():
            after = [s for s in inc['samples'] if s[0] - inc['start'] >= self.warmup_s]
            if len(after) < 2 or after[-1][0] - inc['start'] < 2 * self.warmup_s:
                continue
            first, last = after[0], after[-1]
            if first[1] and last[1] is not None:
                pct = 100.0 * (last[1] - first[1]) / first[1]
                if by_node is not None:
                    by_node['%s (%d)' % (inc['name'], pid)] = [first[1], last[1]]
                if pct > rss[0] or not rss[1]:
                    rss = (pct, inc['name'])
            if first[2] is not None and last[2] is not None:
                grown = last[2] - first[2]
                if grown > fds[0] or not fds[1]:
                    fds = (grown, inc['name'])
        return rss[0], rss[1], fds[0], fds[1]

    def rss_mb(self):
        total = 0
        for inc in self.incarnations.values():
            if inc['end'] is None and inc['samples'] and inc['samples'][-1][1]:
                total += inc['samples'][-1][1]
        return total / 1024.0


def invalid_orders(count, first_id):
    """`count` orders every robot and the dispatcher must refuse: NaN or infinite coordinates,
    an inverted range, more leaders than robots, a target outside the arena."""
    from swarm_transport.msg import New_Mission
    nan, inf = float('nan'), float('inf')
    out = []
    for k in range(count):
        m = New_Mission()
        m.mission_id = first_id + k
        m.robot_index_from, m.robot_index_to = 0, 3
        m.leader_number = 1
        m.object_position_x, m.object_position_y = 5.0, 5.0
        m.object_size_x, m.object_size_y = 1.0, 1.0
        m.target_x, m.target_y = 3.0, 3.0
        bad = k % 5
        if bad == 0:
            m.target_x = nan
        elif bad == 1:
            m.object_position_y = inf
        elif bad == 2:
            m.robot_index_from, m.robot_index_to = 9, 2
        elif bad == 3:
            m.leader_number = 9
        else:
            m.target_x = -40.0
        out.append(m)
    return out


def wait(predicate, timeout_s, period_s=0.2):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if predicate():
            return True
        time.sleep(period_s)
    return predicate()
