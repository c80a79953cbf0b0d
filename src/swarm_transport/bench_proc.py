"""What scripts/bench reads of the machine (/proc: the machine's CPU, a process tree's CPU,
a process's memory) and how it prints its table."""

import math
import os

# The table: (key, printf spec) per column, and the titles that differ from the keys.
COLUMNS = (('clock', '%-8s'), ('comm', '%-9s'), ('deploy', '%-8s'), ('robots', '%6d'),
           ('robots_ticking', '%7d'), ('tick_hz', '%8.2f'), ('late_pct', '%7.2f'),
           ('max_period_ms', '%8.1f'), ('delivered_pct', '%9.2f'),
           ('neighbours', '%6.1f'), ('cpu_pct', '%6.1f'), ('swarm_cpu_pct', '%6.1f'),
           ('background_cpu_pct', '%6.1f'), ('rss_mb_per_robot', '%7.2f'),
           ('pss_mb_per_robot', '%7.2f'),
           ('cpu_us_per_robot_tick', '%7.1f'), ('lockstep_ticks_per_s', '%9.1f'),
           ('startup_s', '%7.1f'))
HEADERS = {'robots_ticking': 'ticking', 'tick_hz': 'tick_hz', 'late_pct': 'late_%',
           'max_period_ms': 'max_ms', 'delivered_pct': 'deliv_%', 'neighbours': 'nbrs',
           'cpu_pct': 'cpu_%', 'swarm_cpu_pct': 'swarm%', 'background_cpu_pct': 'bg_%',
           'rss_mb_per_robot': 'rss_MB',
           'pss_mb_per_robot': 'pss_MB', 'lockstep_ticks_per_s': 'ls_tick/s',
           'startup_s': 'start_s', 'cpu_us_per_robot_tick': 'us/tick'}

def machine_cpu():
    """(busy, total) jiffies of the whole machine."""
    with open('/proc/stat') as f:
        fields = [int(x) for x in f.readline().split()[1:]]
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)
    total = sum(fields[:8])
    return total - idle, total


def proc_stat(pid):
    """(comm, ppid, utime + stime jiffies) or None."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            data = f.read()
    except OSError:
        return None
    comm = data[data.index('(') + 1:data.rindex(')')]
    rest = data[data.rindex(')') + 2:].split()
    return comm, int(rest[1]), int(rest[11]) + int(rest[12])


def tree(roots):
    """{pid: (comm, cpu_jiffies)} of the given pids and all their descendants."""
    info = {}
    children = {}
    for name in os.listdir('/proc'):
        if not name.isdigit():
            continue
        st = proc_stat(int(name))
        if st is None:
            continue
        info[int(name)] = st
        children.setdefault(st[1], []).append(int(name))
    out = {}
    todo = [r for r in roots if r in info]
    while todo:
        pid = todo.pop()
        if pid in out:
            continue
        out[pid] = (info[pid][0], info[pid][2])
        todo.extend(children.get(pid, []))
    return out


def status_kb(pid, key, path='status'):
    try:
        with open('/proc/%d/%s' % (pid, path)) as f:
            for line in f:
                if line.startswith(key + ':'):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def fmt(value, spec='%.2f'):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return 'na'
    if isinstance(value, float):
        return spec % value
    return str(value)


def ratio(num, den):
    """num / den, or None when either is missing, NaN or den is 0."""
    if num is None or den is None or not den or math.isnan(num) or math.isnan(den):
        return None
    return num / den


def table(rows, columns=COLUMNS, headers=HEADERS):
    """The rows as a fixed-width table: `columns` (key, printf spec), `headers` key -> title."""
    lines = [' '.join(_pad(headers.get(key, key), spec) for key, spec in columns)]
    for r in rows:
        cells = []
        for key, spec in columns:
            v = r.get(key)
            if v is None or (isinstance(v, float) and math.isnan(v)):
                cells.append(_pad('na', spec))
            else:
                cells.append(spec % v)
        lines.append(' '.join(cells))
    return lines


def _pad(text, spec):
    width = int(''.join(ch for ch in spec.split('.')[0] if ch.isdigit()))
    return text.ljust(width) if spec.startswith('%-') else text.rjust(width)
