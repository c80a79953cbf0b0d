"""One run of an experiment in its own process and its own private ROS master (rospy can join
one master per process): launches swarm.launch in lock-step with the recorder, submits the
mission if there is one, waits for the end, stops everything by pid and writes result.json
into the run's directory. Called by experiment.py as `experiment.py _worker JOB.json`.

The recorder writes the run's data (swarm_count.csv, missions.csv, run.csv) into the same
directory; this process only adds what the recorder does not know: how the run ended from the
runner's side, wall-clock timings, and for leader runs the leader's swarm along its path."""

import json
import math
import os
import shutil
import signal
import sys
import tempfile
import threading
import time

from swarm_transport import core_metrics
from swarm_transport import st_ros

FINAL = {5: 'DONE', 6: 'ABORTED', 7: 'REJECTED'}
STARTUP_TIMEOUT_S = 90.0      # launch -> first tick
MIN_TICKS_PER_S = 10.0        # slower than this counts as hung
RECORDER_FLUSH_TIMEOUT_S = 20.0
TICKED_FLAG = 'ticked.flag'   # written when the ticking is over
END_GRACE_S = 0.5           # after the final /clock, when the last tick is no sample


class RunFailed(Exception):
    pass


def main(job_path):
    # Started in the background by a non-interactive shell (nohup, CI), this process may have
    # inherited SIGINT ignored; the master and roslaunch would inherit that, ignore the SIGINT
    # that stops them and cost the 15 s kill timeout of every run.
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    with open(job_path) as f:
        job = json.load(f)
    result = {'setting': job['setting'], 'run': job['run'], 'seed': job['seed'],
              'robots': job['robots'], 'status': 'error', 'error': '',
              'mission_id': (job.get('mission') or {}).get('id')}
    log_dir = tempfile.mkdtemp(prefix='st_experiment_')
    started = time.time()
    try:
        with st_ros.PrivateRos(log_dir=log_dir) as ros:
            try:
                result.update(_run(job, ros, started))
                result['status'] = 'ok'
            finally:
                # The ticking is over: the runner may start the next run while this one stops.
                open(os.path.join(job['run_dir'], TICKED_FLAG), 'w').close()
                stop_from = time.time()
                ros.stop()
                result['shutdown_s'] = time.time() - stop_from
    except Exception as e:  # every failure ends up in result.json
        result['error'] = '%s: %s' % (type(e).__name__, e)
    result['wall_s'] = time.time() - started
    if result['status'] == 'ok' and not job.get('keep_logs'):
        shutil.rmtree(log_dir, ignore_errors=True)
    else:
        kept = os.path.join(job['run_dir'], 'ros_log')
        shutil.rmtree(kept, ignore_errors=True)
        shutil.move(log_dir, kept)
        result['ros_log'] = kept
    with open(os.path.join(job['run_dir'], 'result.json'), 'w') as f:
        json.dump(result, f, indent=1, sort_keys=True)
    return 0 if result['status'] == 'ok' else 1


def _launch_args(job):
    args = {'robots': job['robots'], 'seed': job['seed'], 'lockstep': 'true',
            'max_ticks': job['max_ticks'], 'extra_config': job['config_path'],
            'placement': job['placement'], 'observers': job['observers'],
            'dispatcher': 'true' if job['dispatcher'] else 'false',
            'recorder': 'true', 'record_dir': job['record_dir'], 'run_name': job['run_name'],
            'deploy': job.get('deploy', 'process')}
    if job.get('placement_file'):
        args['placement_file'] = job['placement_file']
    return args


def _run(job, ros, started):
    t_launch = time.time()
    ros.launch('swarm.launch', _launch_args(job))
    import rospy
    from rosgraph_msgs.msg import Clock
    from swarm_transport.msg import Swarm_Stats
    rospy.init_node('experiment_run', anonymous=True, disable_signals=True)
    state = {'tick': -1, 'first_wall': None, 'last_wall': None, 'stats': None, 'clock': -1.0,
             'clock_wall': None}
    lock = threading.Lock()

    def on_clock(msg):
        with lock:
            now = time.time()
            if state['first_wall'] is None:
                state['first_wall'] = now
            state['clock'] = msg.clock.to_sec()
            state['clock_wall'] = now
            state['last_wall'] = now

    def on_stats(msg):
        with lock:
            state['stats'] = msg

    rospy.Subscriber('/clock', Clock, on_clock, queue_size=10, tcp_nodelay=True)
    rospy.Subscriber('/flock/stats', Swarm_Stats, on_stats, queue_size=100, tcp_nodelay=True)
    waiter = Waiter(ros, job, state, lock, t_launch)
    trace = Trace(os.path.join(job['run_dir'], 'trace.csv')) if job.get('trace') else None
    if trace is not None and job['kind'] == 'flocking':
        # Counted among the observers: the lock-step gate waits for it, so tick 0 is traced.
        from swarm_transport.msg import Robot_Positions
        rospy.Subscriber('/flock/world_poses', Robot_Positions, trace.add, queue_size=10000,
                         tcp_nodelay=True)
    out = {}
    period = job['tick_period_s']
    end_time = job['max_ticks'] * period - 1e-6 * period
    if job['kind'] == 'flocking':
        # The end: the recorder's sample of the final tick (presets end on a sample time), or,
        # when the last tick is no sample time, the final /clock plus a grace for the recorder
        # to take in the final /flock/world_poses (it writes no row for it anyway).
        def finished():
            if state['stats'] is not None and state['stats'].tick >= job['max_ticks']:
                return True
            return (state['clock'] >= end_time and
                    time.time() - state['clock_wall'] > END_GRACE_S)
        waiter.until(finished, 'the run did not reach tick %d' % job['max_ticks'])
        if trace is not None:
            # The recorder may be done before this process has taken in the last frames.
            waiter.until(lambda: trace.last_tick >= job['max_ticks'] - 1,
                         'the trace did not reach tick %d' % (job['max_ticks'] - 1))
        out['end'] = 'max_ticks'
    else:
        out.update(_run_mission(job, ros, state, lock, waiter, trace))
    if trace is not None:
        trace.write()
    with lock:
        first, last = state['first_wall'], state['last_wall']
        st = state['stats']
        # Ticks simulated: the clock (every tick), or the last tick the recorder or we saw
        # when /clock messages were dropped under load.
        out['ticks'] = max(0, int(round(state['clock'] / period)),
                           st.tick if st is not None else 0, state.get('positions_tick', 0))
        out['final_stats'] = None if st is None else {
            'tick': st.tick, 'sim_time': st.sim_time, 'robots': st.robots,
            'swarm_count': st.swarm_count, 'largest_swarm': st.largest_swarm}
    out['startup_s'] = (first or time.time()) - started   # master, launch, first tick
    out['ticking_s'] = (last or time.time()) - (first or time.time())
    out['ticks_per_s'] = out['ticks'] / out['ticking_s'] if out['ticking_s'] > 0 else 0.0
    rospy.signal_shutdown('run done')
    return out


class Waiter(object):
    """Waits on a condition while watching roslaunch, the start-up limit (launch to the first
    /clock) and a wall-clock limit that scales with the run's ticks."""

    def __init__(self, ros, job, state, lock, t_launch):
        self.ros, self.state, self.lock = ros, state, lock
        self.startup_deadline = t_launch + STARTUP_TIMEOUT_S
        self.deadline = self.startup_deadline + job['max_ticks'] / MIN_TICKS_PER_S

    def until(self, predicate, what, startup=False):
        """startup: the clock is not expected to run yet (the gate waits for us)."""
        while time.time() < self.deadline:
            with self.lock:
                if predicate():
                    return
                started = self.state['first_wall'] is not None
            if not self.ros.alive('roslaunch'):
                raise RunFailed('roslaunch ended early (%s)' % what)
            if startup and time.time() > self.startup_deadline:
                raise RunFailed('start-up: %s within %.0f s' % (what, STARTUP_TIMEOUT_S))
            if not startup and not started and time.time() > self.startup_deadline:
                raise RunFailed('the lock-step clock did not start within %.0f s of the '
                                'launch' % STARTUP_TIMEOUT_S)
            time.sleep(0.05)
        raise RunFailed('timeout: %s (sim time %.1f s)' % (what, self.state['clock']))


def _run_mission(job, ros, state, lock, waiter, trace=None):
    """Submits the mission before tick 0 (the lock-step waits for this process's
    /flock/world_poses subscription), follows it to DONE/ABORTED or the tick limit, and waits
    for the recorder's missions.csv row."""
    import rospy
    from swarm_transport.msg import Mission_Status, New_Mission, Robot_Positions
    from swarm_transport.srv import Submit_Mission
    m = job['mission']
    mid = int(m['id'])
    phases = []
    last = {}

    def on_status(msg):
        if msg.mission_id == mid:
            with lock:
                if not phases or phases[-1][0] != msg.state:
                    phases.append((msg.state, msg.tick))
                if msg.tick > 0:
                    last.update(tick=msg.tick, state=msg.state, reason=msg.reason,
                                object=[msg.object_position_x, msg.object_position_y],
                                distance_to_target=msg.distance_to_target)

    rospy.Subscriber('/flock/mission/status', Mission_Status, on_status, queue_size=1000)
    submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
    up_by = time.time() + STARTUP_TIMEOUT_S
    while True:
        try:
            submit.wait_for_service(1.0)
            break
        except rospy.ROSException:
            if not ros.alive('roslaunch'):
                raise RunFailed('roslaunch ended before the mission dispatcher came up')
            if time.time() > up_by:
                raise RunFailed('the mission dispatcher did not come up')
    # The recorder must hear the order and every status, QUEUED included (statuses are not
    # latched): on a loaded machine it may subscribe after the dispatcher is up. Once it is
    # registered, the dispatcher waits for its connection before publishing the order, and the
    # first leader for its connection before publishing a status.
    _wait_subscribed('/recorder', ('/flock/mission/status', '/flock/mission/new'), up_by, ros)
    msg = New_Mission(mission_id=mid, target_x=m['target'][0], target_y=m['target'][1],
                      transport_mode=int(m.get('mode', 0)))
    if job['kind'] == 'leader':
        lead = job['leader_id']
        msg.robot_index_from, msg.robot_index_to, msg.leader_number = lead, lead + 1, 1
    else:
        # (ext) count: the dispatcher picks that many robots (robot_count, no range).
        msg.robot_count = int(m.get('count', 0))
        msg.robot_index_from = 0
        msg.robot_index_to = 0 if msg.robot_count else int(m.get('group', job['robots']))
        msg.leader_number = int(m['leaders'])
        (msg.object_position_x, msg.object_position_y,
         msg.object_size_x, msg.object_size_y) = m['object']
    answer = submit(msg)
    if answer.code != 0:
        raise RunFailed('the dispatcher rejected the mission: %s' % answer.message)
    # The dispatcher published the (latched) New_Mission before answering. The robots take in
    # topics only within their ticks (SPEC 4), so it waits in their queues and enters at tick 0.

    track = LeaderTrack(job) if job['kind'] == 'leader' else None
    pos_state = {'tick': -1}

    def on_positions(p):
        # Tracked before the tick counts as seen: the arrival's row must be in the track when
        # the wait for it below ends (it was missing from 1 of 52 leader runs).
        if track is not None:
            track.add(p)
        if trace is not None:
            trace.add(p)
        with lock:
            pos_state['tick'] = p.tick
            state['positions_tick'] = p.tick

    # Subscribing opens the lock-step gate (observers:=1): tick 0 follows.
    rospy.Subscriber('/flock/world_poses', Robot_Positions, on_positions, queue_size=10000,
                     tcp_nodelay=True)
    limit = job['max_ticks']
    waiter.until(lambda: (phases and phases[-1][0] in FINAL) or pos_state['tick'] >= limit,
                 'mission %d did not end' % mid)
    with lock:
        final = FINAL.get(phases[-1][0]) if phases and phases[-1][0] in FINAL else 'TICK_LIMIT'
        out = {'end': final, 'phases': [[s, t] for s, t in phases],
               'end_tick': pos_state['tick'], 'last_status': dict(last)}
    if final in ('DONE', 'ABORTED') and (track is not None or trace is not None):
        # The poses up to the end (the final report's tick): its status travels on another
        # connection and can overtake them (a host_sim run's trace once ended before tick 0).
        end_tick = phases[-1][1]
        waiter.until(lambda: pos_state['tick'] >= end_tick,
                     'no /flock/world_poses up to the end at tick %d' % end_tick)
    if track is not None and final == 'DONE':
        # The track up to the arrival (the DONE report's tick) for the leader's swarm at 100 %.
        track.arrived(phases[-1][1])
    if final in ('DONE', 'ABORTED'):
        path = os.path.join(job['record_dir'], job['run_name'], 'missions.csv')
        flushed = time.time() + RECORDER_FLUSH_TIMEOUT_S
        while time.time() < flushed and not _has_row(path, mid):
            time.sleep(0.05)
        out['recorder_row'] = _has_row(path, mid)
    if track is not None:
        track.write(os.path.join(job['run_dir'], 'leader_track.csv'))
    return out


class Trace(object):
    """Every physical robot's pose at every tick (--trace), from /flock/world_poses: columns
    tick,robot_id,x,y,heading_deg; written when the run ends."""

    def __init__(self, path):
        self.path = path
        self.rows = []
        self.last_tick = -1
        self.lock = threading.Lock()

    def add(self, msg):
        rows = ['%d,%d,%.4f,%.4f,%.2f' % (msg.tick, r.robot_id, r.pos_x, r.pos_y, r.angle)
                for r in msg.robots if r.type == 0]
        with self.lock:
            self.rows.extend(rows)
            self.last_tick = max(self.last_tick, msg.tick)

    def write(self):
        with self.lock:
            rows = list(self.rows)
        with open(self.path, 'w') as f:
            f.write('tick,robot_id,x,y,heading_deg\n')
            for row in rows:
                f.write(row + '\n')


def _wait_subscribed(node, topics, deadline, ros):
    """Waits until the master lists `node` as a subscriber of every topic in `topics`."""
    import rosgraph
    master = rosgraph.Master('/experiment_run')
    while True:
        _, subscribers, _ = master.getSystemState()
        have = {topic for topic, nodes in subscribers if node in nodes}
        if all(t in have for t in topics):
            return
        if not ros.alive('roslaunch'):
            raise RunFailed('roslaunch ended before %s subscribed' % node)
        if time.time() > deadline:
            raise RunFailed('%s did not subscribe to %s' % (node, ', '.join(topics)))
        time.sleep(0.02)


def _has_row(path, mid):
    try:
        with open(path) as f:
            return any(line.split(',', 1)[0].strip() == str(mid) for line in f)
    except OSError:
        return False


class LeaderTrack(object):
    """The leader's progress along its straight path and the size of its swarm (the connected
    component holding it, leader excluded) at every tick: the data of the thesis's Fig. 7.6."""

    def __init__(self, job):
        self.leader = job['leader_id']
        self.target = job['mission']['target']
        self.local_range = job['local_range_m']
        self.start = None
        self.rows = []
        self.end = None  # the arrival tick, once known
        self.lock = threading.Lock()

    def add(self, msg):
        if self.end is not None and msg.tick > self.end:
            return  # the leader flocks again: frames after its arrival are no part of the track
        robots = [r for r in msg.robots if r.type == 0]
        pts = [(r.pos_x, r.pos_y) for r in robots]
        ids = [r.robot_id for r in robots]
        if self.leader not in ids:
            return
        li = ids.index(self.leader)
        lp = pts[li]
        if self.start is None:
            self.start = lp
        total = math.hypot(self.target[0] - self.start[0], self.target[1] - self.start[1])
        left = math.hypot(self.target[0] - lp[0], self.target[1] - lp[1])
        progress = min(1.0, max(0.0, 1.0 - left / total)) if total > 0 else 1.0
        count, labels = core_metrics.components(pts, self.local_range)
        swarm = sum(1 for lab in labels if lab == labels[li]) - 1
        with self.lock:
            # Checked again here: arrived() may have ended the track while this frame was
            # being measured.
            if self.end is not None and msg.tick > self.end:
                return
            self.rows.append((msg.tick, progress, swarm, count))

    def arrived(self, tick):
        """Ends the track at the arrival: later rows go (the leader flocks again), the row of
        the arrival tick counts as 100 % of the path (it is within goal tolerance)."""
        with self.lock:
            self.end = tick
            rows = sorted(r for r in set(self.rows) if r[0] <= tick)
            if rows and rows[-1][0] == tick:
                rows[-1] = (tick, 1.0) + tuple(rows[-1][2:])
            self.rows = rows

    def write(self, path):
        with self.lock:
            rows = sorted(set(self.rows))
        with open(path, 'w') as f:
            f.write('tick,path_fraction,leader_swarm,swarm_count\n')
            for tick, progress, swarm, count in rows:
                f.write('%d,%.6f,%d,%d\n' % (tick, progress, swarm, count))


if __name__ == '__main__':
    sys.exit(main(sys.argv[1]))
