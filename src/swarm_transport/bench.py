"""scripts/bench: scale benchmark of the swarm (issue 5). Starts the simulator and N robots on a
private ROS master, lets them tick, and measures over a window of --seconds:

  tick_hz            achieved ticks per second per robot (lock-step: = simulator ticks/s)
  late_pct           % of ticks late: started > 10% over the period after the previous one
                     (lock-step: % of rounds a robot never got, so never answered)
  delivered_pct      % of in-range robots' position updates a robot had within one tick when
                     it ticked (docs/scale.md defines it for both comms)
  cpu_pct            machine CPU busy % (/proc/stat; includes anything else running)
  swarm_cpu_pct      CPU % of the machine used by this run's processes (master, roslaunch,
                     simulator, robots), from /proc/<pid>/stat
  background_cpu_pct machine CPU busy % in the second before the run started (other jobs)
  cpu_us_per_robot_tick  CPU time of this run's processes per robot tick, microseconds (less
                     sensitive to other jobs than the rates are)
  rss_mb_per_robot   VmRSS of the robot processes (host: its VmRSS / N), MiB
  pss_mb_per_robot   the same as proportional set size (shared libraries split), MiB
  lockstep_ticks_per_s  simulator ticks per wall second in lock-step
  startup_s          from roslaunch until every robot has ticked

The robots publish these figures themselves (~diagnostics: true), once per second on
/flock/robot_stats; --comm broadcast switches them to the thesis's all-to-all wiring.
Each run uses its own master in a child process; all processes are stopped by pid. Figures
only, no pass/fail. The last line is one `RESULT key=value ...` line. --deploy batch runs the
lock-step swarm in the experiments' batch engine instead, without ROS (bench_batch.py);
--deploy hardware robots as on real robots over the stand-in's bases (docs/hardware.md)."""

import argparse
import csv
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from swarm_transport import bench_batch, st_ros
from swarm_transport.bench_proc import (COLUMNS, fmt, machine_cpu, ratio, status_kb, table,
                                        tree)

PYTHON = '/usr/bin/python3'
STATS_TOPIC = '/flock/robot_stats'
ROBOT_COMMS = ('robot', 'robot_host')
RESULT_KEYS = ('robots', 'clock', 'deploy', 'comm', 'tick_hz', 'late_pct', 'delivered_pct',
               'cpu_pct', 'swarm_cpu_pct', 'background_cpu_pct', 'rss_mb_per_robot',
               'pss_mb_per_robot',
               'lockstep_ticks_per_s', 'startup_s', 'robots_ticking', 'max_period_ms',
               'cpu_us_per_robot_tick', 'max_latency_ms', 'missed_rounds_pct', 'arena_m',
               'neighbourhood', 'chain_hops')


def log(msg):
    sys.stdout.write('[bench] %s\n' % msg)
    sys.stdout.flush()


def parse_args(argv):
    p = argparse.ArgumentParser(prog='scripts/bench', description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--robots', type=int, default=25, help='robots (default 25)')
    p.add_argument('--clock', default='realtime', choices=('realtime', 'lockstep', 'both'))
    p.add_argument('--deploy', default='process',
                   choices=('process', 'hardware', 'host', 'host_sim', 'batch'),
                   help='process: a process per robot; hardware: a process per robot as on '
                        'real robots (robot.launch hardware:=true) over the stand-in\'s bases '
                        'node, no simulator (real time, local comm only); host: all robots in '
                        'one robot_host '
                        'process (both via swarm.launch); host_sim: robots and simulator in '
                        'one robot_host process (~deploy host_sim); batch: lock-step in the '
                        'experiments\' batch engine, no ROS (bench_batch.py)')
    p.add_argument('--ticks', type=int, default=40, help='batch: ticks of the run (default 40)')
    p.add_argument('--mission', action='store_true',
                   help='batch: a transport mission of robots 0-11 (2 leaders) from tick 0')
    p.add_argument('--batch-binary', default='',
                   help='batch: the experiment_batch of another build (its libraries beside '
                        'it), to compare two builds back to back')
    p.add_argument('--no-build', action='store_true',
                   help='skip the quiet build first (scripts/bench; ST_NO_BUILD=1 too)')
    p.add_argument('--comm', default='local', choices=('local', 'broadcast', 'both'),
                   help='local: the radio relays in-range positions (SPEC 7); broadcast: every '
                        'robot hears every /flock/position (the thesis); both: run both and '
                        'print the ratio')
    p.add_argument('--seconds', type=float, default=10.0, help='measuring window (default 10)')
    p.add_argument('--warmup', type=float, default=3.0,
                   help='s after every robot ticks before the window opens (default 3)')
    p.add_argument('--seed', type=int, default=1, help='seed (default 1)')
    p.add_argument('--arena', default=None,
                   help="room: the thesis's 11.09 m room for any N (crowded at large N); "
                        "density: the side grows with sqrt(N / 25), so every N has the "
                        "thesis's 25 robots per room area; or a side in m (default room, "
                        "--deploy batch density)")
    p.add_argument('--neighbourhood', choices=['chain', 'disc'], default='chain',
                   help='whom a robot flocks with (config neighbourhood): chain relays '
                   'positions hop by hop up to --chain-hops, disc hears only robots in range '
                   '(default chain, the default config)')
    p.add_argument('--chain-hops', type=int, default=16,
                   help='hop limit of the chain relay (config chain_hops, default 16)')
    p.add_argument('--threads', type=int, default=1,
                   help='host / host_sim: robot threads (robot_host ~threads; in real time each '
                   'a worker that ticks its share of the robots; default 1)')
    p.add_argument('--no-robot-services', action='store_true',
                   help='host / host_sim: robots offer no per-robot services (robot_host '
                   '~robot_services false; their registration is O(N^2) at start-up)')
    p.add_argument('--startup-timeout', type=float, default=0.0,
                   help='s to wait for every robot to tick (default 60 + 0.5 s per robot)')
    p.add_argument('--csv', default='', help='also write the table to this CSV file')
    p.add_argument('--keep-logs', action='store_true', help='keep the runs\' ROS logs')
    p.add_argument('--child', default='', help=argparse.SUPPRESS)  # internal: JSON out path
    a = p.parse_args(argv)
    if not 1 <= a.robots <= 65535:
        p.error('--robots must be in [1, 65535]')
    if a.chain_hops < 1:
        p.error('--chain-hops must be >= 1')
    if not a.seconds > 0 or a.warmup < 0 or not 1 <= a.threads <= 64:
        p.error('--seconds must be > 0, --warmup >= 0, --threads in [1, 64]')
    if a.ticks < 1:
        p.error('--ticks must be >= 1')
    if a.deploy == 'hardware' and (a.clock != 'realtime' or a.comm != 'local'):
        p.error('--deploy hardware needs --clock realtime and --comm local (a robot on '
                'hardware ticks on the wall clock and is its own radio)')
    if a.arena is None:
        a.arena = 'density' if a.deploy == 'batch' else 'room'
    if a.startup_timeout <= 0:
        a.startup_timeout = 60.0 + 0.5 * a.robots
    try:
        a.arena_m = arena_side(a.arena, a.robots)
    except ValueError as e:
        p.error(str(e))
    return a


THESIS_ROOM_M = 11.088889  # config/swarm.yaml world_size_m
THESIS_ROBOTS = 25


def arena_side(arena, robots):
    """The arena side (m) for --arena: room, density or a number."""
    if arena == 'room':
        return THESIS_ROOM_M
    if arena == 'density':
        return THESIS_ROOM_M * math.sqrt(max(1, robots) / float(THESIS_ROBOTS))
    try:
        side = float(arena)
    except ValueError:
        raise ValueError("--arena must be room, density or a side in m, not %r" % arena)
    if not (side > 0 and math.isfinite(side)):
        raise ValueError('--arena must be a finite side > 0 m, not %r' % arena)
    return side


# ---------------------------------------------------------------- one run (child process)


def parse_stats(line):
    out = {}
    for item in line.split():
        k, _, v = item.partition('=')
        out[k] = v
    return out


def run_one(a):
    """One run on its own master; returns a dict of figures."""
    log_dir = tempfile.mkdtemp(prefix='st_bench_')
    result = {'robots': a.robots, 'clock': a.clock, 'deploy': a.deploy, 'comm': a.comm,
              'threads': a.threads, 'seconds': a.seconds, 'log_dir': log_dir,
              'arena_m': a.arena_m, 'neighbourhood': a.neighbourhood,
              'chain_hops': a.chain_hops, 'robot_services': not a.no_robot_services}
    ok = False
    with st_ros.PrivateRos(log_dir=log_dir) as ros:
        import rosgraph.masterapi
        import rospy
        from std_msgs.msg import String
        master = rosgraph.masterapi.Master('/bench')
        # The robots' private options, set before roslaunch starts them (swarm.launch passes
        # only id and clock).
        if a.deploy == 'host_sim':
            set_host_sim_params(master, a)
        elif a.deploy == 'host':
            master.setParam('/robot_host/comm', a.comm)
            master.setParam('/robot_host/diagnostics', True)
            master.setParam('/robot_host/threads', a.threads)
        else:
            for rid in range(a.robots):
                master.setParam('/robot_%d/robot' % rid, {'comm': a.comm, 'diagnostics': True})
        # Before roslaunch (or, host_sim, we) set /use_sim_time: this process keeps wall time
        # (with sim time it would subscribe /clock, a TCP message per lock-step tick).
        rospy.init_node('bench', anonymous=True, disable_signals=True)
        if a.deploy == 'host_sim':
            master.setParam('/use_sim_time', a.clock == 'lockstep')
        stats = {}  # id -> list of (recv wall, fields)

        def on_stats(msg):
            # One robot's line, or a robot_host's lines of many robots (one per line).
            now = time.time()
            for line in msg.data.splitlines():
                f = parse_stats(line)
                stats.setdefault(int(f['id']), []).append((now, f))

        rospy.Subscriber(STATS_TOPIC, String, on_stats, queue_size=100000)
        # What else keeps the machine busy (other users' jobs skew every figure).
        cpu0 = machine_cpu()
        time.sleep(1.0)
        cpu1 = machine_cpu()
        result['background_cpu_pct'] = 100.0 * (cpu1[0] - cpu0[0]) / max(1, cpu1[1] - cpu0[1])
        t0 = time.time()
        if a.deploy == 'host_sim':
            launch = ros.start(['rosrun', 'swarm_transport', 'robot_host', '__name:=robot_host'],
                               'roslaunch')
        else:
            arena_yaml = os.path.join(log_dir, 'arena.yaml')
            with open(arena_yaml, 'w') as f:
                f.write('world_size_m: %.6f\nneighbourhood: %s\nchain_hops: %d\n'
                        % (a.arena_m, a.neighbourhood, a.chain_hops))
            launch = ros.launch('swarm.launch', {
                'robots': a.robots, 'seed': a.seed, 'deploy': a.deploy,
                'lockstep': 'true' if a.clock == 'lockstep' else 'false',
                'dispatcher': 'false', 'observers': 0, 'robot_output': 'log',
                'robot_services': 'false' if a.no_robot_services else 'true',
                'extra_config': arena_yaml})
        try:
            ok = measure(a, ros, launch.pid, stats, t0, result)
        finally:
            stop_run(ros, launch.pid)
    result['ok'] = ok
    if ok and not a.keep_logs:
        shutil.rmtree(log_dir, ignore_errors=True)
    return result


def set_host_sim_params(master, a):
    """What swarm.launch would set, for one robot_host process that also runs the simulator
    (linked directly to its robots: no per-robot topics between them); /use_sim_time is set by
    the caller after its own node is up."""
    import yaml
    with open(os.path.join(st_ros.ROOT, 'config', 'swarm.yaml')) as f:
        swarm = yaml.safe_load(f)
    swarm['seed'] = a.seed
    swarm['world_size_m'] = a.arena_m
    swarm['neighbourhood'] = a.neighbourhood
    swarm['chain_hops'] = a.chain_hops
    master.setParam('/swarm', swarm)
    master.setParam('/robot_host', {
        'from': 0, 'to': a.robots, 'clock': a.clock, 'comm': a.comm, 'diagnostics': True,
        'threads': a.threads, 'deploy': 'host_sim',
        'robot_services': not a.no_robot_services,
        'simulator': {'robots': a.robots, 'clock': a.clock}})


def measure(a, ros, launch_pid, stats, t0, result):
    roots = [launch_pid] + [p.pid for p, name, _ in ros.procs if name == 'rosmaster']
    deadline = t0 + a.startup_timeout
    last_count = -1
    while time.time() < deadline:
        if not ros.alive('roslaunch'):
            log('roslaunch ended early; logs in %s' % result['log_dir'])
            return False
        count = len(stats)
        if count == a.robots:
            break
        if count != last_count and count > 0:
            last_count = count
        time.sleep(0.2)
    started = dict(stats)
    firsts = [float(msgs[-1][1]['first_tick_wall']) for msgs in started.values()]
    result['robots_started'] = len(started)
    result['startup_s'] = max(firsts) - t0 if len(started) == a.robots else float('nan')
    log('%d of %d robots ticking after %.1f s' % (len(started), a.robots, time.time() - t0))
    if not started:
        return False
    time.sleep(a.warmup)

    cpu0 = machine_cpu()
    tree0 = tree(roots)
    w0 = time.time()
    time.sleep(a.seconds / 2.0)
    rss_tree = tree(roots)  # mid-window memory sample
    rss, pss = [], []
    for pid, (comm, _) in rss_tree.items():
        if comm in ROBOT_COMMS:
            rss.append(status_kb(pid, 'VmRSS') or 0)
            pss.append(status_kb(pid, 'Pss', 'smaps_rollup') or 0)
        if comm in ('simulator', 'bases') or (comm == 'robot_host' and a.deploy == 'host_sim'):
            result['sim_rss_mb'] = (status_kb(pid, 'VmRSS') or 0) / 1024.0
    time.sleep(a.seconds / 2.0)
    w1 = time.time()
    cpu1 = machine_cpu()
    tree1 = tree(roots)

    ncpu = os.cpu_count() or 1
    hz = os.sysconf('SC_CLK_TCK')
    result['cpu_pct'] = 100.0 * (cpu1[0] - cpu0[0]) / max(1, cpu1[1] - cpu0[1])
    used = sum(cpu - tree0.get(pid, (None, 0))[1] for pid, (_, cpu) in tree1.items())
    result['swarm_cpu_pct'] = 100.0 * used / hz / (w1 - w0) / ncpu
    by_comm = {}
    for pid, (comm, cpu) in tree1.items():
        by_comm[comm] = by_comm.get(comm, 0) + cpu - tree0.get(pid, (None, 0))[1]
    result['cpu_by_process_pct'] = {k: round(100.0 * v / hz / (w1 - w0) / ncpu, 2)
                                    for k, v in sorted(by_comm.items())}
    robot_procs = max(1, len(rss))
    per = robot_procs if a.deploy in ('process', 'hardware') else a.robots
    result['robot_processes'] = len(rss)
    result['rss_mb_per_robot'] = sum(rss) / 1024.0 / per
    result['pss_mb_per_robot'] = sum(pss) / 1024.0 / per

    # Per robot: cumulative counters at the last report before the window and the last in it.
    ticks = late = updates = delivered = rounds = missed = 0
    rates, max_period, max_latency = [], 0.0, 0.0
    for rid, msgs in list(stats.items()):
        before = [m for m in msgs if m[0] <= w0]
        inside = [m for m in msgs if w0 < m[0] <= w1]
        if not inside:
            continue
        base = before[-1][1] if before else inside[0][1]
        end = inside[-1][1]
        span = float(end['wall']) - float(base['wall'])
        if span <= 0:
            continue
        d = {k: int(end[k]) - int(base[k])
             for k in ('ticks', 'late', 'updates', 'delivered', 'rounds', 'missed_rounds')}
        ticks += d['ticks']
        late += d['late']
        updates += d['updates']
        delivered += d['delivered']
        rounds += d['rounds']
        missed += d['missed_rounds']
        rates.append(d['ticks'] / span)
        later = [m[1] for m in inside if m[1] is not base]
        max_period = max([max_period] + [float(f['max_period_ms']) for f in later])
        max_latency = max([max_latency] + [float(f['max_latency_ms']) for f in later])
    used_s = sum(cpu - tree0.get(pid, (None, 0))[1] for pid, (_, cpu) in tree1.items()) / hz
    # Ticks counted over each robot's own reporting span, scaled to the window.
    result['cpu_us_per_robot_tick'] = (1e6 * used_s / (sum(rates) * (w1 - w0))
                                       if rates and sum(rates) > 0 else float('nan'))
    result['robots_ticking'] = len(rates)
    result['tick_hz'] = sum(rates) / len(rates) if rates else 0.0
    denominator = ticks + late if a.clock == 'lockstep' else ticks
    result['late_pct'] = 100.0 * late / denominator if denominator else float('nan')
    result['delivered_pct'] = 100.0 * delivered / updates if updates else 100.0
    result['updates'] = updates
    # Local comm counts updates per radio round, broadcast per tick.
    per = rounds + missed if a.comm == 'local' else ticks
    result['neighbours'] = updates / per if per else 0.0
    result['max_period_ms'] = max_period
    result['max_latency_ms'] = max_latency if a.clock == 'realtime' else float('nan')
    result['missed_rounds_pct'] = 100.0 * missed / (rounds + missed) if rounds + missed else 0.0
    result['lockstep_ticks_per_s'] = result['tick_hz'] if a.clock == 'lockstep' else float('nan')
    return True


def stop_run(ros, launch_pid):
    """Stops the robots and the simulator by pid, in parallel (roslaunch would stop them one
    after the other), then roslaunch and the master; whatever is left is killed by pid."""
    roots = [launch_pid] + [p.pid for p, name, _ in ros.procs if name == 'rosmaster']
    nodes = [pid for pid in tree([launch_pid]) if pid != launch_pid]
    everything = set(tree(roots))
    for pid in nodes:
        _signal(pid, signal.SIGINT)
    deadline = time.time() + 20
    while time.time() < deadline and any(st_ros.process_alive(pid) for pid in nodes):
        time.sleep(0.1)
    ros.stop()
    deadline = time.time() + 10
    while time.time() < deadline and any(st_ros.process_alive(pid) for pid in everything):
        time.sleep(0.1)
    left = [pid for pid in everything if st_ros.process_alive(pid)]
    for pid in left:
        _signal(pid, signal.SIGKILL)
    if left:
        log('killed %d processes that outlived the run' % len(left))


def _signal(pid, sig):
    try:
        os.kill(pid, sig)
    except OSError:
        pass


# ---------------------------------------------------------------- driver


def child_run(a, clock, comm):
    """Runs one configuration in a child process (one rospy node per master)."""
    fd, out = tempfile.mkstemp(prefix='st_bench_', suffix='.json')
    os.close(fd)
    args = [PYTHON, '-m', 'swarm_transport.bench', '--robots', str(a.robots), '--clock', clock,
            '--deploy', a.deploy, '--comm', comm, '--seconds', str(a.seconds),
            '--warmup', str(a.warmup), '--seed', str(a.seed), '--threads', str(a.threads),
            '--startup-timeout', str(a.startup_timeout), '--arena', a.arena,
            '--neighbourhood', a.neighbourhood, '--chain-hops', str(a.chain_hops), '--child', out]
    if a.keep_logs:
        args.append('--keep-logs')
    if a.no_robot_services:
        args.append('--no-robot-services')
    log('run: %d robots, %s clock, %s comm, deploy %s, arena %.2f m, %s neighbourhood (%d hops)'
        % (a.robots, clock, comm, a.deploy, a.arena_m, a.neighbourhood, a.chain_hops))
    p = subprocess.Popen(args)
    try:
        p.wait()
    except BaseException:
        p.send_signal(signal.SIGTERM)
        p.wait()
        raise
    try:
        with open(out) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {'robots': a.robots, 'clock': clock, 'deploy': a.deploy, 'comm': comm,
                'ok': False}
    finally:
        os.unlink(out)


def result_line(a, rows):
    def pick(clock, comm):
        for r in rows:
            if r.get('ok') and r['clock'] == clock and r['comm'] == comm:
                return r
        return None

    clocks = ['realtime', 'lockstep'] if a.clock == 'both' else [a.clock]
    comms = ['local', 'broadcast'] if a.comm == 'both' else [a.comm]
    primary = pick(clocks[0], comms[0]) or {}
    out = {'robots': a.robots, 'clock': a.clock, 'deploy': a.deploy, 'comm': a.comm}
    for key in RESULT_KEYS[4:]:
        out[key] = primary.get(key)
    lockstep = pick('lockstep', comms[0])
    out['lockstep_ticks_per_s'] = lockstep.get('lockstep_ticks_per_s') if lockstep else None
    if a.clock == 'both' and lockstep:
        out['lockstep_startup_s'] = lockstep.get('startup_s')
    if a.comm == 'both':
        bc = pick(clocks[0], 'broadcast') or {}
        for key in ('tick_hz', 'late_pct', 'delivered_pct', 'cpu_pct', 'swarm_cpu_pct',
                    'rss_mb_per_robot'):
            out['bc_' + key] = bc.get(key)
        out['ratio_swarm_cpu'] = ratio(bc.get('swarm_cpu_pct'), primary.get('swarm_cpu_pct'))
        bc_lockstep = pick('lockstep', 'broadcast')
        if lockstep and bc_lockstep:
            out['bc_lockstep_ticks_per_s'] = bc_lockstep.get('lockstep_ticks_per_s')
            out['ratio_lockstep_speed'] = ratio(lockstep.get('lockstep_ticks_per_s'),
                                                 bc_lockstep.get('lockstep_ticks_per_s'))
    out['runs_ok'] = sum(1 for r in rows if r.get('ok'))
    out['runs'] = len(rows)
    return 'RESULT ' + ' '.join('%s=%s' % (k, fmt(v)) for k, v in out.items())


def main(argv):
    a = parse_args(argv)
    if a.child:
        result = run_one(a)
        with open(a.child, 'w') as f:
            json.dump(result, f)
        return 0 if result.get('ok') else 1
    if a.deploy == 'batch':
        return bench_batch.main(a, log, fmt)
    clocks = ['realtime', 'lockstep'] if a.clock == 'both' else [a.clock]
    comms = ['local', 'broadcast'] if a.comm == 'both' else [a.comm]
    rows = [child_run(a, clock, comm) for clock in clocks for comm in comms]
    print('')
    print('swarm_transport scale benchmark: %d robots, deploy %s, window %.0f s, %d cores'
          % (a.robots, a.deploy, a.seconds, os.cpu_count() or 1))
    for line in table(rows):
        print(line)
    for r in rows:
        if r.get('cpu_by_process_pct'):
            print('  %s/%s cpu %% by process: %s' % (r['clock'], r['comm'], ' '.join(
                '%s=%.1f' % kv for kv in r['cpu_by_process_pct'].items())))
        if not r.get('ok'):
            print('  %s/%s FAILED (logs: %s)' % (r['clock'], r['comm'], r.get('log_dir', '?')))
    if a.comm == 'both':
        for clock in clocks:
            lo = [r for r in rows if r['clock'] == clock and r['comm'] == 'local' and r.get('ok')]
            bc = [r for r in rows if r['clock'] == clock and r['comm'] == 'broadcast'
                  and r.get('ok')]
            if lo and bc:
                print('  %s broadcast / local: swarm CPU x%s, tick rate x%s, delivered %s%% vs '
                      '%s%%' % (clock, fmt(ratio(bc[0]['swarm_cpu_pct'], lo[0]['swarm_cpu_pct'])),
                                fmt(ratio(bc[0]['tick_hz'], lo[0]['tick_hz'])),
                                fmt(bc[0]['delivered_pct']), fmt(lo[0]['delivered_pct'])))
    if a.csv:
        keys = ['clock', 'comm', 'deploy', 'robots', 'threads', 'seconds'] + [
            k for k, _ in COLUMNS if k not in ('clock', 'comm', 'deploy', 'robots')] + [
            'updates', 'max_latency_ms', 'missed_rounds_pct', 'arena_m', 'sim_rss_mb',
            'robot_processes', 'robot_services',
            'ok']
        with open(a.csv, 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=keys, extrasaction='ignore')
            w.writeheader()
            for r in rows:
                w.writerow({k: fmt(r.get(k), '%.4f') for k in keys})
        print('  CSV: %s' % a.csv)
    print(result_line(a, rows))
    return 0 if all(r.get('ok') for r in rows) else 1


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
