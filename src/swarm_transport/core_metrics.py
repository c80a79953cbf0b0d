"""The core's swarm metrics for the Python tools: core::SwarmComponents (SPEC 8's swarm count)
and core::TrimmedMean (thesis 7.1), asked of `experiment_batch --metrics` - one process per
Python process, started at the first question and kept open - instead of re-implemented here.
"""

import atexit
import os
import subprocess
import threading

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..'))
EXE = os.path.join(ROOT, '.catkin_ws', 'devel', 'lib', 'swarm_transport', 'experiment_batch')

_lock = threading.Lock()  # rospy callbacks ask from their own threads
_proc = None


def _ask(request):
    global _proc
    with _lock:
        if _proc is None or _proc.poll() is not None:
            _proc = subprocess.Popen([EXE, '--metrics'], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, universal_newlines=True, bufsize=1)
        _proc.stdin.write(request + '\n')
        _proc.stdin.flush()
        answer = _proc.stdout.readline().strip()
    if not answer or answer.startswith('error'):
        raise ValueError('experiment_batch --metrics: %s' % (answer or 'no answer'))
    return answer


def _close():
    if _proc is not None and _proc.poll() is None:
        _proc.stdin.close()
        _proc.wait()


atexit.register(_close)


def components(points, local_range):
    """(number of swarms, swarm of each point) of the graph linking points at most
    local_range apart; swarms are numbered in the order of their first point."""
    request = 'components %r' % float(local_range)
    if points:
        request += ' ' + ' '.join('%r %r' % (float(p[0]), float(p[1])) for p in points)
    words = _ask(request).split()
    return int(words[0]), [int(w) for w in words[1:]]


def trimmed_mean(values, drop_each_end):
    """Mean of the sorted values without `drop_each_end` of them at each end."""
    request = 'trimmed_mean %d %s' % (drop_each_end, ' '.join('%r' % float(v) for v in values))
    return float(_ask(request))
