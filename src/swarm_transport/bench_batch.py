"""scripts/bench --deploy batch: the lock-step swarm through the batch engine of the experiments
(experiment_batch, no ROS master), one flocking job of --robots robots on an arena of --arena
(default density: the thesis's 25 robots per 11.09 m room at every N) for --ticks ticks.

It writes the job as scripts/experiment does (config.yaml over config/swarm.yaml, job.json),
hands its path to one experiment_batch process on stdin, and measures:

  lockstep_ticks_per_s   ticks / ticking_s (result.json)
  startup_s              the job's set-up (world, placement, robots) (result.json)
  ticking_s              the ticks (result.json)
  files_s                writing the run's files at its end: the last metrics and the rows
                         (result.json shutdown_s)
  cpu_us_per_robot_tick  the process's CPU time during the ticks / (robots * ticks), from
                         /proc/<pid>/task/*/schedstat sampled around the ticking window
  cpu_s                  the process's whole CPU time (wait4's rusage: set-up, ticks, files)
  startup_cpu_s, ticking_cpu_s, files_cpu_s   its CPU time in each phase (the same samples)
  peak_rss_mb            the process's peak resident memory (rusage ru_maxrss)

The last line is one `RESULT key=value ...` line. Figures only, no pass/fail."""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from swarm_transport import st_ros

BATCH_KEYS = ('robots', 'clock', 'deploy', 'ticks', 'arena_m', 'neighbourhood', 'chain_hops',
              'lockstep_ticks_per_s', 'cpu_us_per_robot_tick', 'cpu_us_per_robot_tick_whole',
              'ticking_s', 'startup_s', 'files_s', 'wall_s', 'cpu_s', 'startup_cpu_s',
              'ticking_cpu_s', 'files_cpu_s', 'peak_rss_mb', 'background_cpu_pct',
              'final_swarm_count', 'binary')


def default_binary():
    return os.path.join(st_ros.ROOT, '.catkin_ws', 'devel', 'lib', 'swarm_transport',
                        'experiment_batch')


def write_job(a, run_dir):
    """The job of one flocking run (with --mission a transport run), as
    experiment.prepare_jobs writes it; returns its path."""
    config_path = os.path.join(run_dir, 'config.yaml')
    with open(config_path, 'w') as f:
        f.write('# scripts/bench --deploy batch: config/swarm.yaml + these\n'
                'world_size_m: %.6f\nneighbourhood: %s\nchain_hops: %d\n'
                % (a.arena_m, a.neighbourhood, a.chain_hops))
    job = {'preset': 'bench', 'kind': 'flocking', 'setting': 'bench', 'run': 0,
           'seed': a.seed, 'robots': a.robots, 'max_ticks': a.ticks,
           'config_path': config_path, 'run_dir': run_dir, 'record_dir': run_dir,
           'run_name': 'run_0', 'placement': 'random', 'placement_file': '', 'trace': False}
    if getattr(a, 'mission', False):
        # Every robot checks the order against the swarm at tick 0 (what a mission costs).
        c = a.arena_m / 2.0
        job.update(kind='transport', mission={
            'id': 7, 'group': min(12, a.robots), 'leaders': 2, 'mode': 0,
            'object': [c, c, 1.0, 1.0], 'target': [c / 2.0, c / 2.0]})
    path = os.path.join(run_dir, 'job.json')
    with open(path, 'w') as f:
        json.dump(job, f, indent=1, sort_keys=True)
    return path


def cpu_ns(pid):
    """CPU time (ns) of every thread of a process (schedstat's run time), or None."""
    total = 0
    try:
        tasks = os.listdir('/proc/%d/task' % pid)
    except OSError:
        return None
    for tid in tasks:
        try:
            with open('/proc/%d/task/%s/schedstat' % (pid, tid)) as f:
                total += int(f.read().split()[0])
        except (OSError, ValueError, IndexError):
            pass
    return total


class CpuSampler(threading.Thread):
    """(wall, cpu ns) of a process every `period` s until stopped."""

    def __init__(self, pid, period=0.005):
        threading.Thread.__init__(self, daemon=True)
        self.pid, self.period = pid, period
        self.samples = []
        self.done = threading.Event()

    def run(self):
        while not self.done.is_set():
            ns = cpu_ns(self.pid)
            if ns is not None:
                self.samples.append((time.time(), ns))
            time.sleep(self.period)

    def at(self, t):
        """CPU ns at wall time t, interpolated between the samples around it."""
        s = self.samples
        if not s:
            return None
        if t <= s[0][0]:
            return s[0][1]
        for (t0, c0), (t1, c1) in zip(s, s[1:]):
            if t0 <= t <= t1:
                return c0 + (c1 - c0) * ((t - t0) / (t1 - t0) if t1 > t0 else 1.0)
        return s[-1][1]


def wait_idle(pid, timeout=20.0):
    """Until the process waits for its first job (asleep, its CPU time unchanged for 50 ms)."""
    deadline = time.time() + timeout
    last = None
    while time.time() < deadline:
        ns = cpu_ns(pid)
        try:
            with open('/proc/%d/stat' % pid) as f:
                state = f.read().rsplit(')', 1)[1].split()[0]
        except (OSError, IndexError):
            return False
        if state == 'S' and ns is not None and ns == last:
            return True
        last = ns
        time.sleep(0.05)
    return False


def run_batch(a, log):
    """One job in one experiment_batch process; a dict of figures ('ok' says whether it ran)."""
    binary = os.path.abspath(a.batch_binary or default_binary())
    out = {'robots': a.robots, 'clock': 'lockstep', 'deploy': 'batch', 'ticks': a.ticks,
           'arena_m': a.arena_m, 'neighbourhood': a.neighbourhood, 'chain_hops': a.chain_hops,
           'binary': binary, 'ok': False}
    if not os.access(binary, os.X_OK):
        out['error'] = '%s is not built (scripts/build)' % binary
        return out
    run_dir = tempfile.mkdtemp(prefix='st_bench_batch_')
    out['run_dir'] = run_dir
    job_path = write_job(a, run_dir)
    env = os.environ.copy()
    if a.batch_binary:
        # Another build's binary must load its own build's libraries: beside it, or (a catkin
        # devel or install space) one folder up. Its RUNPATH names them, but a sourced
        # workspace's LD_LIBRARY_PATH comes first and would give it this build's libraries (the
        # comparison was then this build against itself; found 2026-11-28).
        own = [os.path.dirname(binary), os.path.dirname(os.path.dirname(binary))]
        env['LD_LIBRARY_PATH'] = os.pathsep.join(
            own + [p for p in env.get('LD_LIBRARY_PATH', '').split(os.pathsep) if p])
    out['background_cpu_pct'] = background_cpu_pct()
    with open(os.path.join(run_dir, 'batch.log'), 'w') as err:
        p = subprocess.Popen([binary, '--base-config',
                              os.path.join(st_ros.ROOT, 'config', 'swarm.yaml')],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=err, env=env)
    sampler = CpuSampler(p.pid)
    try:
        wait_idle(p.pid)
        sampler.start()
        time.sleep(0.02)
        t_job = time.time()
        p.stdin.write((job_path + '\n').encode())
        p.stdin.flush()
        answer = p.stdout.readline().decode(errors='replace').strip()
        time.sleep(0.02)
        sampler.done.set()
        sampler.join()
        p.stdin.close()
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status) if hasattr(
            os, 'waitstatus_to_exitcode') else status
    except BaseException:
        sampler.done.set()
        p.kill()
        p.wait()
        raise
    out['cpu_s'] = usage.ru_utime + usage.ru_stime
    out['peak_rss_mb'] = usage.ru_maxrss / 1024.0  # KiB on Linux
    try:
        with open(os.path.join(run_dir, 'result.json')) as f:
            result = json.load(f)
    except (OSError, ValueError):
        result = {}
    if not answer.startswith('ok ') or result.get('status') != 'ok':
        out['error'] = answer or result.get('error') or 'experiment_batch wrote no answer'
        log('experiment_batch failed: %s (files in %s)' % (out['error'], run_dir))
        return out
    ticks = int(result['ticks'])
    out['ticks'] = ticks
    out['startup_s'] = float(result['startup_s'])
    out['ticking_s'] = float(result['ticking_s'])
    out['files_s'] = float(result['shutdown_s'])
    out['wall_s'] = float(result['wall_s'])
    out['lockstep_ticks_per_s'] = ticks / out['ticking_s'] if out['ticking_s'] > 0 else None
    stats = result.get('final_stats') or {}
    out['final_swarm_count'] = stats.get('swarm_count')
    robot_ticks = float(a.robots * ticks)
    # The process's CPU time in each phase (less sensitive to other jobs than the wall times).
    ends = [t_job, t_job + out['startup_s']]
    ends += [ends[-1] + out['ticking_s'], ends[-1] + out['ticking_s'] + out['files_s']]
    cpu = [sampler.at(t) for t in ends]
    if None not in cpu and robot_ticks > 0:
        out['startup_cpu_s'] = (cpu[1] - cpu[0]) / 1e9
        out['ticking_cpu_s'] = (cpu[2] - cpu[1]) / 1e9
        out['files_cpu_s'] = (cpu[3] - cpu[2]) / 1e9
        out['cpu_us_per_robot_tick'] = 1e6 * out['ticking_cpu_s'] / robot_ticks
    out['cpu_us_per_robot_tick_whole'] = 1e6 * out['cpu_s'] / robot_ticks if robot_ticks else None
    out['ok'] = p.returncode == 0
    if out['ok'] and not a.keep_logs:
        shutil.rmtree(run_dir, ignore_errors=True)
    else:
        log('the run\'s files: %s' % run_dir)
    return out


def background_cpu_pct():
    """The machine's busy CPU % over one second (other jobs skew every figure)."""
    def busy():
        with open('/proc/stat') as f:
            fields = [int(x) for x in f.readline().split()[1:]]
        idle = fields[3] + (fields[4] if len(fields) > 4 else 0)
        total = sum(fields[:8])
        return total - idle, total
    b0, t0 = busy()
    time.sleep(1.0)
    b1, t1 = busy()
    return 100.0 * (b1 - b0) / max(1, t1 - t0)


def main(a, log, fmt):
    log('batch: %d robots, %d ticks, arena %.2f m, %s neighbourhood (%d hops), %s'
        % (a.robots, a.ticks, a.arena_m, a.neighbourhood, a.chain_hops,
           a.batch_binary or 'experiment_batch of this workspace'))
    r = run_batch(a, log)
    print('')
    print('swarm_transport scale benchmark: %d robots through the batch engine, %d cores'
          % (a.robots, os.cpu_count() or 1))
    for key, unit in (('lockstep_ticks_per_s', 'ticks/s'), ('cpu_us_per_robot_tick', 'us'),
                      ('cpu_us_per_robot_tick_whole', 'us (whole process)'),
                      ('startup_s', 's'), ('ticking_s', 's'), ('files_s', 's'),
                      ('wall_s', 's'), ('cpu_s', 's'), ('startup_cpu_s', 's'),
                      ('ticking_cpu_s', 's'), ('files_cpu_s', 's'),
                      ('peak_rss_mb', 'MiB'), ('background_cpu_pct', '%'),
                      ('final_swarm_count', '')):
        print('  %-28s %12s %s' % (key, fmt(r.get(key), '%.3f'), unit))
    if not r.get('ok'):
        print('  FAILED: %s' % r.get('error', '?'))
    out = dict((k, r.get(k)) for k in BATCH_KEYS)
    out['runs_ok'] = 1 if r.get('ok') else 0
    out['runs'] = 1
    print('RESULT ' + ' '.join('%s=%s' % (k, fmt(v, '%.6g')) for k, v in out.items()))
    sys.stdout.flush()
    return 0 if r.get('ok') else 1
