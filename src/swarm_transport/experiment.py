"""scripts/experiment: the thesis's chapter 7 experiments as named presets
(config/experiments/*.yaml), run in lock-step far faster than real time, aggregated like the
thesis (mean, median, mean of the middle runs), plotted and written up.

  scripts/experiment list
  scripts/experiment run PRESET [--runs K] [--jobs J] [--out DIR] [--seed-base S] [--report]
  scripts/experiment report DIR [DIR ...] [--out docs/results.md]

By default (--engine batch) runs go through experiment_batch: the lock-step tick of a host_sim
launch, the dispatcher's and the recorder's part composed in one process without a ROS master,
a fresh world and swarm per run (the same rows as a launched run, no start-up cost). With
--engine launch each run is a separate process with its own private ROS master and roslaunch
(experiment_worker.py, --deploy chooses the robots' processes). docs/experiments.md describes
presets, metrics and output files."""

import argparse
import json
import os
import shutil
import select
import signal
import subprocess
import sys
import time

import yaml

from swarm_transport import experiment_presets as presets

ROOT = presets.ROOT
DEFAULT_OUT_ROOT = os.path.join(ROOT, 'results')        # git-ignored
DEFAULT_REPORT = os.path.join(ROOT, 'docs', 'results.md')
PYTHON = '/usr/bin/python3'


def log(msg=''):
    sys.stdout.write(msg + '\n')
    sys.stdout.flush()


def parse_args(argv):
    p = argparse.ArgumentParser(prog='scripts/experiment', description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest='command', required=True)
    sub.add_parser('list', help='preset names and their one-line descriptions')
    r = sub.add_parser('run', help='run a preset: every setting x run, then aggregate and plot')
    r.add_argument('preset')
    r.add_argument('--runs', type=int, help='runs per setting (default: the preset\'s, i.e. '
                   'the thesis\'s 10 or 15)')
    r.add_argument('--jobs', type=int, default=1,
                   help='runs in parallel, each with its own master (default 1)')
    r.add_argument('--out', help='output directory (default results/<preset>)')
    r.add_argument('--seed-base', type=int,
                   help='run k of every setting uses seed S + k (default: the preset\'s)')
    r.add_argument('--settings', help='comma-separated subset of the preset\'s settings')
    r.add_argument('--report', action='store_true',
                   help='then regenerate the results page over every preset output next to '
                        'DIR (see --report-out)')
    r.add_argument('--report-out', default=DEFAULT_REPORT,
                   help='results page written by --report (default docs/results.md)')
    r.add_argument('--keep-logs', action='store_true',
                   help='keep every run\'s ROS logs (default: only of failed runs)')
    r.add_argument('--engine', default='batch', choices=('batch', 'launch'),
                   help='batch (default): every run in an experiment_batch process without a '
                        'ROS master, J processes in parallel; launch: each run a roslaunch of '
                        'swarm.launch on its own master (see --deploy)')
    r.add_argument('--deploy', default='process', choices=('process', 'host', 'host_sim'),
                   help='--engine launch: process: one process per robot (the thesis\'s '
                        'architecture, default); host_sim: simulator and robots in one process '
                        'over direct links, the same runs much faster (swarm.launch deploy:=...)')
    r.add_argument('--trace', action='store_true',
                   help='also write every run\'s trace.csv: each robot\'s pose at every tick')
    r.add_argument('--retries', type=int, default=1,
                   help='restarts of a run whose ROS side failed (default 1)')
    rep = sub.add_parser('report', help='aggregate, plot and write the results page from '
                         'output directories (a preset output or a folder of them)')
    rep.add_argument('dirs', nargs='+')
    rep.add_argument('--out', default=DEFAULT_REPORT, help='default docs/results.md')
    st = sub.add_parser('stability', help='how firmly each trend line stands: judge blocks of '
                        'the preset\'s run count of an output with many runs per setting')
    st.add_argument('dir', help='an output of scripts/experiment run PRESET --runs K*N')
    st.add_argument('--block', type=int,
                    help='runs per block (default: the preset\'s run count, the thesis\'s)')
    w = sub.add_parser('_worker', help=argparse.SUPPRESS)
    w.add_argument('job')
    a = p.parse_args(argv)
    if a.command == 'run':
        if a.runs is not None and a.runs < 1:
            p.error('--runs must be >= 1')
        if a.jobs < 1:
            p.error('--jobs must be >= 1')
        if a.retries < 0:
            p.error('--retries must be >= 0')
    if a.command == 'stability' and a.block is not None and a.block < 2:
        p.error('--block must be >= 2')
    return a


def main(argv):
    a = parse_args(argv)
    try:
        if a.command == 'list':
            return cmd_list()
        if a.command == 'run':
            return cmd_run(a)
        if a.command == 'report':
            from swarm_transport import experiment_report as report
            return report.cmd_report(a.dirs, a.out)
        if a.command == 'stability':
            from swarm_transport import experiment_stability
            return experiment_stability.cmd_stability(a.dir, a.block)
        from swarm_transport import experiment_worker
        return experiment_worker.main(a.job)
    except presets.PresetError as e:
        log('experiment: %s' % e)
        return 2
    except BrokenPipeError:  # `scripts/experiment list | head`
        sys.stderr.close()
        return 0


def cmd_list():
    """Preset names with their descriptions, in the order of the thesis's chapter 7."""
    rows = []
    for name in presets.preset_names():
        try:
            p = presets.load_preset(name)
            rows.append((p['order'], name, p['description']))
        except presets.PresetError as e:
            rows.append((10 ** 6, name, 'INVALID: %s' % e))
    width = max(len(r[1]) for r in rows)
    for _, name, desc in sorted(rows):
        log('%-*s  %s' % (width, name, desc))
    return 0


# ---------------------------------------------------------------------------------------------
# run

def prepare_jobs(preset, out, runs, seed_base, only, keep_logs, trace=False,
                 deploy='process'):
    """Writes every run's directory (config.yaml, placement, job.json) and returns the jobs in
    execution order: run 0 of every setting first, so partial results cover every setting."""
    views = [v for v in presets.settings(preset) if not only or v['name'] in only]
    missing = set(only or []) - {v['name'] for v in views}
    if missing:
        raise presets.PresetError('unknown settings %s (have: %s)' % (
            sorted(missing), ', '.join(v['name'] for v in presets.settings(preset))))
    # The recorder must see tick 0 (its samples are on the grid of its first frame): the lock-
    # step gate waits for it unless swarm.launch already counts it among the observers.
    extra_observers = 0 if recorder_counted_by_launch() else 1
    for view in views:  # earlier runs of these settings go; other settings' runs stay
        shutil.rmtree(os.path.join(out, 'raw', view['name']), ignore_errors=True)
    jobs = []
    for k in range(runs):
        for view in views:
            seed = seed_base + k
            setting_dir = os.path.join(out, 'raw', view['name'])
            run_dir = os.path.join(setting_dir, 'run_%d' % k)
            os.makedirs(run_dir)
            config = presets.swarm_config(preset, view)
            config_path = os.path.join(run_dir, 'config.yaml')
            with open(config_path, 'w') as f:
                f.write('# %s / %s / run %d (seed %d): %s + overrides\n' % (
                    preset['name'], view['name'], k, seed, preset['base_config']))
                yaml.safe_dump(config, f, default_flow_style=False, sort_keys=True)
            job = {'preset': preset['name'], 'kind': preset['kind'], 'setting': view['name'],
                   'run': k, 'seed': seed, 'robots': view['robots'],
                   'max_ticks': view['max_ticks'], 'config_path': config_path,
                   'run_dir': run_dir, 'record_dir': setting_dir, 'run_name': 'run_%d' % k,
                   'placement': view['placement'], 'placement_file': '',
                   'dispatcher': preset['kind'] != 'flocking',
                   # A mission run's worker follows /flock/world_poses; so does a traced one.
                   'observers': (0 if preset['kind'] == 'flocking' and not trace else 1) +
                                extra_observers,
                   'trace': trace, 'deploy': deploy,
                   'tick_period_s': float(config['tick_period_s']),
                   'mission': view['mission'] or None, 'leader_id': None,
                   'local_range_m': float(config['local_range_m']), 'keep_logs': keep_logs}
            if view['placement'] == 'cluster':
                poses = presets.cluster_placement(
                    view['robots'], seed, float(config['local_range_m']),
                    float(config['robot_radius_m']), float(config['world_size_m']),
                    preset.get('cluster'))
                job['placement'] = 'file'
                job['placement_file'] = os.path.join(run_dir, 'placement.txt')
                with open(job['placement_file'], 'w') as f:
                    f.write('# x y theta_deg: one connected cluster (seed %d)\n' % seed)
                    for x, y, th in poses:
                        f.write('%.6f %.6f %.3f\n' % (x, y, th))
            if preset['kind'] == 'leader':
                job['leader_id'] = presets.leader_of(seed, view['robots'])
            with open(os.path.join(run_dir, 'job.json'), 'w') as f:
                json.dump(job, f, indent=1, sort_keys=True)
            jobs.append(job)
    return jobs


def recorder_counted_by_launch():
    """True when swarm.launch adds the recorder to the simulator's lockstep_observers."""
    import re
    with open(os.path.join(ROOT, 'launch', 'swarm.launch')) as f:
        m = re.search(r'name="lockstep_observers"\s+value="([^"]*)"', f.read())
    return bool(m) and 'recorder' in m.group(1)


class Pool(object):
    """Runs the jobs in worker processes: at most `jobs` ticking at a time; a worker whose run
    has finished ticking (it wrote ticked.flag) only stops its ROS processes, mostly waiting,
    so the next run starts meanwhile (at most 2 * jobs workers alive). A failed run is
    restarted `retries` times."""

    def __init__(self, jobs, retries):
        self.size, self.retries = jobs, retries
        self.running = []  # (Popen, job, attempt, logfile)

    def start(self, job, attempt):
        flag = os.path.join(job['run_dir'], experiment_worker_flag())
        if os.path.exists(flag):
            os.remove(flag)
        logfile = open(os.path.join(job['run_dir'], 'worker.log'), 'a')
        p = subprocess.Popen([PYTHON, '-m', 'swarm_transport.experiment_worker',
                              os.path.join(job['run_dir'], 'job.json')],
                             stdout=logfile, stderr=subprocess.STDOUT)
        self.running.append((p, job, attempt, logfile))

    def ticking(self):
        return sum(1 for p, job, _, _ in self.running if not os.path.exists(
            os.path.join(job['run_dir'], experiment_worker_flag())))

    def run(self, jobs, on_done):
        queue = [(j, 0) for j in jobs]
        try:
            while queue or self.running:
                while queue and self.ticking() < self.size and len(self.running) < 2 * self.size:
                    self.start(*queue.pop(0))
                time.sleep(0.05)
                for entry in list(self.running):
                    p, job, attempt, logfile = entry
                    if p.poll() is None:
                        continue
                    self.running.remove(entry)
                    logfile.close()
                    result = _read_result(job)
                    if result.get('status') != 'ok' and attempt < self.retries:
                        log('  %s run %d failed (%s); restarting it'
                            % (job['setting'], job['run'], result.get('error', '?')))
                        path = os.path.join(job['run_dir'], 'result.json')
                        if os.path.exists(path):
                            os.remove(path)
                        logs = os.path.join(job['run_dir'], 'ros_log')
                        if os.path.isdir(logs):  # kept as evidence of the failed attempt
                            os.rename(logs, '%s_attempt%d' % (logs, attempt))
                        queue.insert(0, (job, attempt + 1))
                        continue
                    on_done(job, result)
        except BaseException:
            self.stop()
            raise

    def stop(self):
        for p, _, _, _ in self.running:
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)  # the worker's PrivateRos stops its processes
        for p, _, _, logfile in self.running:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
            logfile.close()
        self.running = []


class BatchPool(object):
    """Runs the jobs in `size` experiment_batch processes: each takes one job.json path per
    line on stdin and answers one line when the run's files are written; a process gets its
    next job when it answered. A process that dies fails its job (restarted `retries` times
    in a new process)."""

    def __init__(self, size, retries):
        self.size, self.retries = size, retries
        self.exe = os.path.join(ROOT, '.catkin_ws', 'devel', 'lib', 'swarm_transport',
                                'experiment_batch')
        self.procs = []  # [Popen, job or None, attempt, logfile, buffer]

    def _spawn(self, log_path):
        logfile = open(log_path, 'a')
        p = subprocess.Popen([self.exe, '--base-config', os.path.join(ROOT, 'config',
                                                                        'swarm.yaml')],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=logfile)
        return [p, None, 0, logfile, b'']

    def _give(self, slot, job, attempt):
        slot[1], slot[2] = job, attempt
        path = os.path.join(job['run_dir'], 'result.json')
        if os.path.exists(path):
            os.remove(path)
        slot[0].stdin.write((os.path.join(job['run_dir'], 'job.json') + '\n').encode())
        slot[0].stdin.flush()

    def run(self, jobs, on_done, log_dir):
        if not os.path.exists(self.exe):
            raise presets.PresetError('%s is not built (scripts/build)' % self.exe)
        queue = [(j, 0) for j in jobs]
        os.makedirs(log_dir, exist_ok=True)
        try:
            for k in range(min(self.size, len(queue))):
                self.procs.append(self._spawn(os.path.join(log_dir, 'batch_%d.log' % k)))
            for slot in self.procs:
                if queue:
                    self._give(slot, *queue.pop(0))
            while any(slot[1] is not None for slot in self.procs):
                busy = [slot for slot in self.procs if slot[1] is not None]
                ready, _, _ = select.select([slot[0].stdout for slot in busy], [], [], 1.0)
                for slot in busy:
                    if slot[0].stdout not in ready:
                        continue
                    chunk = os.read(slot[0].stdout.fileno(), 65536)
                    if not chunk:  # the process died with this job
                        job, attempt = slot[1], slot[2]
                        slot[0].wait()
                        slot[3].close()
                        log_path = slot[3].name
                        slot[:] = self._spawn(log_path)
                        if attempt < self.retries:
                            log('  %s run %d: experiment_batch exited (%s); restarting it'
                                % (job['setting'], job['run'], slot[0].returncode))
                            self._give(slot, job, attempt + 1)
                        else:
                            on_done(job, {'status': 'error', 'error': 'experiment_batch '
                                          'exited during the run (see %s)' % log_path})
                            if queue:
                                self._give(slot, *queue.pop(0))
                        continue
                    slot[4] += chunk
                    if b'\n' not in slot[4]:
                        continue
                    slot[4] = slot[4].split(b'\n', 1)[1]
                    job = slot[1]
                    slot[1] = None
                    on_done(job, _read_result(job))
                    if queue:
                        self._give(slot, *queue.pop(0))
        finally:
            self.stop()

    def stop(self):
        for slot in self.procs:
            try:
                slot[0].stdin.close()
            except OSError:
                pass
        for slot in self.procs:
            try:
                slot[0].wait(timeout=10)
            except subprocess.TimeoutExpired:
                slot[0].kill()
                slot[0].wait()
            slot[3].close()
        self.procs = []


def experiment_worker_flag():
    from swarm_transport import experiment_worker
    return experiment_worker.TICKED_FLAG


def _read_result(job):
    try:
        with open(os.path.join(job['run_dir'], 'result.json')) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {'status': 'error', 'error': 'the worker wrote no result.json (see %s)'
                % os.path.join(job['run_dir'], 'worker.log')}


def _duration(s):
    s = int(round(s))
    return '%dh%02dm%02ds' % (s // 3600, s % 3600 // 60, s % 60) if s >= 3600 else \
        '%dm%02ds' % (s // 60, s % 60)


def cmd_run(a):
    preset = presets.load_preset(a.preset)
    runs = a.runs or preset['runs']
    seed_base = preset['seed_base'] if a.seed_base is None else a.seed_base
    out = os.path.abspath(a.out or os.path.join(DEFAULT_OUT_ROOT, preset['name']))
    only = [s.strip() for s in a.settings.split(',')] if a.settings else None
    os.makedirs(out, exist_ok=True)
    thesis_runs = preset['runs']
    preset['runs'] = runs  # what the tables and the trimmed mean refer to
    deploy = 'batch' if a.engine == 'batch' else a.deploy
    jobs = prepare_jobs(preset, out, runs, seed_base, only, a.keep_logs,
                        a.trace or presets.needs_trace(preset), deploy)
    settings_run = sorted({j['setting'] for j in jobs}, key=[
        v['name'] for v in presets.settings(preset)].index)
    log('experiment %s: %s' % (preset['name'], preset['description']))
    log('  %d settings x %d runs = %d runs, seeds %d..%d, %d in parallel, %s, output %s'
        % (len(settings_run), runs, len(jobs), seed_base, seed_base + runs - 1, a.jobs,
           'engine batch' if a.engine == 'batch' else 'deploy %s' % a.deploy, out))
    started = time.time()
    done = []

    def on_done(job, result):
        done.append((job, result))
        n, total = len(done), len(jobs)
        elapsed = time.time() - started
        eta = elapsed / n * (total - n)
        if result.get('status') == 'ok':
            what = '%-10s %5.1f s: start %.1f + ticks %.1f (%d ticks, %.0f/s) + stop %.1f' % (
                result.get('end', ''), result.get('wall_s', 0), result.get('startup_s', 0),
                result.get('ticking_s', 0), result.get('ticks', 0),
                result.get('ticks_per_s', 0), result.get('shutdown_s', 0))
        else:
            what = 'FAILED: %s' % result.get('error', '?')
        log('[%*d/%d] %s run %d (seed %d) %s | %s elapsed, ETA %s'
            % (len(str(total)), n, total, job['setting'], job['run'], job['seed'], what,
               _duration(elapsed), _duration(eta)))

    meta = {'preset': preset, 'runs': runs, 'preset_runs': thesis_runs,
            'seed_base': seed_base, 'jobs': a.jobs, 'deploy': deploy, 'engine': a.engine,
            'settings': settings_run, 'started': time.strftime('%Y-%m-%d %H:%M:%S'),
            'command': 'scripts/experiment ' + ' '.join(sys.argv[1:])}
    if a.engine == 'batch':
        BatchPool(a.jobs, a.retries).run(jobs, on_done, os.path.join(out, 'logs'))
    else:
        Pool(a.jobs, a.retries).run(jobs, on_done)
    wall = time.time() - started
    ok = [r for _, r in done if r.get('status') == 'ok']
    failed = [(j, r) for j, r in done if r.get('status') != 'ok']
    timing = {
        'wall_s': wall, 'runs': len(done), 'failed': len(failed),
        'sim_ticks': sum(r.get('ticks', 0) for r in ok),
        'startup_s': sum(r.get('startup_s', 0) for r in ok),
        'ticking_s': sum(r.get('ticking_s', 0) for r in ok),
        'shutdown_s': sum(r.get('shutdown_s', 0) for r in ok),
        'run_wall_s': sum(r.get('wall_s', 0) for r in ok),
    }
    meta['timing'] = timing
    with open(os.path.join(out, 'experiment.json'), 'w') as f:
        json.dump(meta, f, indent=1, sort_keys=True)

    from swarm_transport import experiment_report as report
    report.aggregate_dir(out, preset, print_table=True)
    log('')
    for j, r in failed:
        log('FAILED %s run %d (seed %d): %s%s' % (j['setting'], j['run'], j['seed'],
                                                   r.get('error', '?'),
                                                   ' (logs: %s)' % r['ros_log']
                                                   if r.get('ros_log') else ''))
    n = max(1, len(ok))
    log('RESULT preset=%s deploy=%s runs=%d wall_s=%.1f sim_ticks=%d ticks_per_s=%.1f'
        % (preset['name'], deploy, len(done), wall, timing['sim_ticks'],
           timing['sim_ticks'] / wall if wall > 0 else 0.0))
    log('  wall time split (per-run clocks summed; %d ticking at a time%s): start-up %.1f s '
        '(%.2f s/run: %s), ticking %.1f s (%.2f s/run, %.0f ticks/s per run), %s %.1f s '
        '(%.2f s/run); wall per run %.2f s'
        % (a.jobs, '' if a.engine == 'batch' else
           ', a run\'s shutdown overlaps the next start-up', timing['startup_s'],
           timing['startup_s'] / n, 'configuration, placement, robots' if a.engine == 'batch'
           else 'master, roslaunch, first tick', timing['ticking_s'],
           timing['ticking_s'] / n,
           timing['sim_ticks'] / timing['ticking_s'] if timing['ticking_s'] > 0 else 0,
           'writing files' if a.engine == 'batch' else 'shutdown',
           timing['shutdown_s'], timing['shutdown_s'] / n, wall / max(1, len(done))))
    if a.report:
        report.cmd_report([os.path.dirname(out)], a.report_out)
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
