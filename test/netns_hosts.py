"""Three machines on one network, on this one (test/across_hosts*.test): network namespaces, a
core with a bridge and one veth pair per robot host, one IP each. Processes start inside a
namespace with that host's ROS_IP and the core's master; everything is stopped by pid and the
namespaces are deleted at the end. Needs root (CAP_NET_ADMIN) for `ip netns`: without it
NetHosts raises Unavailable."""

import os
import re
import subprocess

import swarm_testing as st
from swarm_transport import st_ros


class Unavailable(Exception):
    pass


def ip(*args):
    subprocess.run(('ip',) + args, check=True, capture_output=True, text=True)


class NetHosts:

    def __init__(self, tag, tmp, port, robot_hosts=('a', 'b')):
        self.ns = {'core': tag + 'c'}
        self.addr = {'core': '10.77.0.1'}
        self.link = {}  # robot host -> (its veth in the core, its veth in its namespace)
        self.tmp, self.port, self.procs = tmp, port, []
        try:
            ip('netns', 'add', self.ns['core'])
        except (OSError, subprocess.CalledProcessError) as e:
            raise Unavailable('network namespaces are not available here (%s)'
                              % getattr(e, 'stderr', e))
        core = self.ns['core']
        ip('-n', core, 'link', 'set', 'lo', 'up')
        ip('-n', core, 'link', 'add', 'br0', 'type', 'bridge')
        ip('-n', core, 'addr', 'add', self.addr['core'] + '/24', 'dev', 'br0')
        ip('-n', core, 'link', 'set', 'br0', 'up')
        for i, host in enumerate(robot_hosts):
            ns = self.ns[host] = tag + host
            self.addr[host] = '10.77.0.%d' % (i + 2)
            ip('netns', 'add', ns)
            ip('-n', ns, 'link', 'set', 'lo', 'up')
            outer, inner = tag + 'v' + host, tag + 'p' + host
            self.link[host] = (outer, inner)
            ip('link', 'add', outer, 'type', 'veth', 'peer', 'name', inner)
            ip('link', 'set', outer, 'netns', core)
            ip('link', 'set', inner, 'netns', ns)
            ip('-n', core, 'link', 'set', outer, 'master', 'br0')
            ip('-n', core, 'link', 'set', outer, 'up')
            ip('-n', ns, 'addr', 'add', self.addr[host] + '/24', 'dev', inner)
            ip('-n', ns, 'link', 'set', inner, 'up')

    def close(self):
        st.stop_process_groups([proc for proc, _ in self.procs])
        for ns in self.ns.values():
            subprocess.run(['ip', 'netns', 'del', ns], capture_output=True)

    def env(self, host):
        env = dict(os.environ)
        env.pop('ROS_HOSTNAME', None)  # it would win over ROS_IP
        env['ROS_IP'] = self.addr[host]
        env['ROS_MASTER_URI'] = 'http://%s:%d' % (self.addr['core'], self.port)
        env['ROS_HOME'] = os.path.join(self.tmp, host)
        return env

    def command(self, host, *cmd):
        return ('ip', 'netns', 'exec', self.ns[host]) + cmd

    def start(self, host, *cmd, **popen):
        """cmd in `host`'s namespace, its own process group, output in a log file (or as
        `popen` says)."""
        log = open(os.path.join(self.tmp, '%s-%d.log' % (host, len(self.procs))), 'w')
        popen.setdefault('stdout', log)
        popen.setdefault('stderr', subprocess.STDOUT)
        # Under nohup SIGINT arrives ignored and would stay so: the stop's SIGINT must count.
        popen.setdefault('preexec_fn', st_ros.default_sigint)
        proc = subprocess.Popen(self.command(host, *cmd), env=self.env(host),
                                start_new_session=True, **popen)
        self.procs.append((proc, log.name))
        return proc

    def logs(self, tail=3000):
        out = []
        for _, name in self.procs:
            with open(name) as f:
                out.append('--- %s\n%s' % (name, f.read()[-tail:]))
        return '\n'.join(out)

    def grep(self, pattern, per_log):
        """The last `per_log` lines of each process's log that match `pattern` (a regex),
        each after its log's name."""
        out = []
        for _, name in self.procs:
            with open(name, errors='replace') as f:
                hits = [l.rstrip() for l in f if re.search(pattern, l)]
            out += ['%s: %s' % (os.path.basename(name), l) for l in hits[-per_log:]]
        return out

    def limit(self, host, to_host, rate):
        """What `host` sends to `to_host` at most `rate` (tc, e.g. '250kbit'): a token bucket
        (tbf; the kernel here has no netem) under an htb class that only that traffic enters;
        the rest of the link is not limited."""
        ns, dev = self.ns[host], self.link[host][1]
        tc = ('ip', 'netns', 'exec', ns, 'tc')
        for args in (('qdisc', 'add', 'dev', dev, 'root', 'handle', '1:', 'htb'),
                     ('class', 'add', 'dev', dev, 'parent', '1:', 'classid', '1:10', 'htb',
                      'rate', '1gbit'),
                     ('qdisc', 'add', 'dev', dev, 'parent', '1:10', 'handle', '10:', 'tbf',
                      'rate', rate, 'burst', '4kb', 'latency', '100ms'),
                     ('filter', 'add', 'dev', dev, 'parent', '1:', 'protocol', 'ip', 'u32',
                      'match', 'ip', 'dst', self.addr[to_host] + '/32', 'flowid', '1:10')):
            subprocess.run(tc + args, check=True, capture_output=True, text=True)

    def set_link(self, host, up):
        """`host`'s link in the core up or down (a partition)."""
        ip('-n', self.ns['core'], 'link', 'set', self.link[host][0], 'up' if up else 'down')

    def sent_bytes(self, host):
        """Bytes `host` sent on its link so far."""
        out = subprocess.run(('ip', '-n', self.ns[host], '-s', 'link', 'show',
                              self.link[host][1]), check=True, capture_output=True,
                             text=True).stdout.splitlines()
        i = next(k for k, line in enumerate(out) if line.strip().startswith('TX:'))
        return int(out[i + 1].split()[0])
