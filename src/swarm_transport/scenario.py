"""scripts/scenario: runs a swarm scenario written as data (docs/scenarios.md) and checks its
expectations.

  scripts/scenario run FILE.yaml [--deploy process|host|host_sim] [--clock lockstep|realtime]
  scripts/scenario check FILE.yaml      # validate only

`run` starts a private ROS master, launches swarm.launch with the scenario's world (its config
merged over the base config), gives the dispatcher the missions (each at its tick) and the
simulator the timed events, records every tick, and prints each expectation as PASS or FAIL with
the measured value. With a `reproducible` expectation it runs the scenario twice. Exit 0 when
every expectation holds, 1 when one fails, 2 on a malformed file or a run that broke."""

import argparse
import csv
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

import yaml

from swarm_transport import scenario_checks as checks
from swarm_transport import scenario_format as fmt

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..'))
STATE_NAMES = dict(enumerate(fmt.STATES))


class RunError(RuntimeError):
    pass


def write_inputs(s, directory):
    """The launch arguments of a scenario, with its config, missions and events files."""
    base = os.path.join(ROOT, 'config', s['world']['base_config'])
    if not os.path.isfile(base):
        raise RunError('world.base_config: no file %s' % base)
    extra = dict(s['world']['config'])
    if s['world']['danger_zones'] is not None:
        extra['danger_zones'] = s['world']['danger_zones']
    args = {'robots': s['world']['robots'], 'seed': s['world']['seed'],
            'lockstep': 'true' if s['world']['clock'] == 'lockstep' else 'false',
            'deploy': s['world']['deploy'], 'placement': s['world']['placement'],
            'config': base, 'max_ticks': s['max_ticks'], 'recorder': 'true',
            'record_dir': directory, 'run_name': 'run', 'observers': 1,
            'robot_output': 'log'}
    args.update(s['world'].get('bases', {}))  # deploy: hardware: the stand-in's bases
    if s['world']['placement'] == 'file':
        path = s['world']['placement_file']
        if not os.path.isabs(path):
            path = os.path.join(os.path.dirname(os.path.abspath(s['path'])), path)
        args['placement_file'] = path
    if extra:
        args['extra_config'] = os.path.join(directory, 'config.yaml')
        with open(args['extra_config'], 'w') as f:
            yaml.safe_dump(extra, f)
    if s['missions']:
        missions = []
        for m in s['missions']:
            entry = {'id': m['id'], 'leaders': m['leaders'],
                     'target': m['target'], 'mode': m['mode'], 'at_tick': m['at_tick']}
            if m.get('recruit'):
                entry['recruit'] = m['recruit']  # statist as dispatcher: no robots named
            else:
                entry['robot_ids'] = m['robot_ids']
            if m['object']:
                entry['object'] = m['object']
            missions.append(entry)
        args['missions_file'] = os.path.join(directory, 'missions.yaml')
        with open(args['missions_file'], 'w') as f:
            yaml.safe_dump({'missions': missions}, f)
    if s['events']:
        events = []
        for e in s['events']:
            entry = {'tick': e['at_tick'], 'kind': e['kind']}
            if e['kind'] in ('freeze', 'continue'):
                entry.update({'from': e['range'][0], 'to': e['range'][1]})
            elif e['kind'] == 'kill':
                entry['robot'] = e['robot']
            elif e['kind'] == 'spawn':
                entry.update({'robot': e['robot'], 'x': e['x'], 'y': e['y'],
                              'theta_deg': e['theta_deg']})
            elif e['kind'] in ('statist', 'remove_statist'):
                entry.update({'robot': e['robot'], 'sub_id': e['sub_id']})
                if e['kind'] == 'statist':
                    entry.update({'x': e['x'], 'y': e['y']})
            elif e['kind'] == 'object_update':
                entry.update({'mission': e['mission'], 'x': e['x'], 'y': e['y']})
            elif e['kind'] == 'odom_stop':
                entry.update({'robot': e['robot'], 'ticks': e['ticks']})
            else:
                entry.update({'mission': e['mission'], 'event': e['event']})
            events.append(entry)
        args['events_file'] = os.path.join(directory, 'events.yaml')
        with open(args['events_file'], 'w') as f:
            yaml.safe_dump({'events': events}, f)
    return args


class Recorder(object):
    """What the run did, from the aggregated topics (subscribed once, reset per run)."""

    def __init__(self):
        import rospy
        from swarm_transport.msg import Mission_Objects, Mission_Status, Robot_Positions
        self.lock = threading.Lock()
        self.reset()
        self.subs = [
            rospy.Subscriber('/flock/world_poses', Robot_Positions, self._positions,
                             queue_size=100000, tcp_nodelay=True),
            rospy.Subscriber('/flock/mission/status', Mission_Status, self._status,
                             queue_size=10000),
            rospy.Subscriber('/flock/objects', Mission_Objects, self._objects,
                             queue_size=100000, tcp_nodelay=True)]

    def reset(self):
        with self.lock:
            self.positions, self.statuses, self.objects, self.last_tick = {}, [], {}, -1
            self.unstamped = []

    def _positions(self, msg):
        with self.lock:
            self.positions[msg.tick] = {r.robot_id: (r.pos_x, r.pos_y, r.angle)
                                        for r in msg.robots if r.type == 0}
            self.last_tick = max(self.last_tick, msg.tick)

    def _status(self, msg):
        with self.lock:
            stamped = msg.tick > 0
            tick = msg.tick if stamped else max(self.last_tick, 0)
            if not stamped:
                self.unstamped.append(len(self.statuses))
            self.statuses.append((msg.mission_id, STATE_NAMES.get(msg.state, str(msg.state)),
                                  tick))

    def _objects(self, msg):
        with self.lock:
            self.objects[msg.tick] = {mid: (x, y, sx, sy) for mid, x, y, sx, sy in zip(
                msg.mission_ids, msg.x, msg.y, msg.size_x, msg.size_y)}

    def log(self, metrics, params, robot_states=None):
        with self.lock:
            return checks.RunLog(dict(self.positions), list(self.statuses), dict(self.objects),
                                 metrics, params, robot_states, self.unstamped)


def robot_states(recorder):
    """Every robot's (mission ids, zone ids, frozen) from its ~state service at the end."""
    import rospy
    from swarm_transport.srv import Robot_State
    with recorder.lock:
        ids = sorted(recorder.positions[recorder.last_tick]) if recorder.last_tick >= 0 else []
    out = {}
    for rid in ids:
        srv = rospy.ServiceProxy('/robot_%d/robot/state' % rid, Robot_State)
        srv.wait_for_service(30.0)
        r = srv()
        out[rid] = (list(r.mission_ids), list(r.zone_ids), bool(r.frozen))
    return out


def start_launch(args, log_path, env=None):
    cli = ['roslaunch', 'swarm_transport', 'swarm.launch']
    cli += ['%s:=%s' % (k, v) for k, v in args.items()]
    log = open(log_path, 'w')
    proc = subprocess.Popen(cli, env=env, stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    return proc, log


# A real-time run ends this many ticks after its last mission ended (and its last event and
# checked tick passed) instead of at max_ticks: the wall clock is the cost of real time.
SETTLE_TICKS = 30


def last_needed_tick(s):
    """The latest tick a scenario's missions, events or checks name (its by_tick bounds aside)."""
    ticks = [m['at_tick'] for m in s['missions']] + [e['at_tick'] for e in s['events']]
    for e in s['expect']:
        ticks += [e[k] for k in ('at_tick', 'from_tick', 'to_tick') if e.get(k) is not None]
    return max(ticks + [0])


def all_ended(s, recorder):
    """The tick by which every mission of the scenario had a final state, else None."""
    if not s['missions']:
        return None
    ended = {}
    with recorder.lock:
        for mission_id, state, tick in recorder.statuses:
            if state in fmt.FINAL_STATES:
                ended.setdefault(mission_id, tick)
    if any(m['id'] not in ended for m in s['missions']):
        return None
    return max(ended.values())


def stop_launch(proc, log, timeout=20):
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    log.close()


def read_metrics(directory):
    path = os.path.join(directory, 'run', 'missions.csv')
    if not os.path.isfile(path):
        return {}
    with open(path) as f:
        return {int(row['mission_id']): row for row in csv.DictReader(f)}


def run_once(s, recorder, directory, env=None, say=print):
    """Launches the scenario once and returns its RunLog."""
    import rospy
    os.makedirs(directory, exist_ok=True)
    args = write_inputs(s, directory)
    recorder.reset()
    proc, log = start_launch(args, os.path.join(directory, 'roslaunch.log'), env)
    lockstep = s['world']['clock'] == 'lockstep'
    robots = s['world']['robots']
    try:
        # Generous: start-up, then the ticks (lock-step: ~0.5 ms per robot tick on a slow
        # machine; real time: the ticks' own time).
        tick_s = rospy.get_param('/swarm/tick_period_s', 0.1) if not lockstep else 0.0
        limit = 120.0 + s['max_ticks'] * (robots * 0.0005 if lockstep else 0.0)
        deadline = time.time() + limit
        started = None
        needed = last_needed_tick(s)
        while time.time() < deadline:
            if proc.poll() is not None:
                raise RunError('the swarm stopped early (see %s)' % log.name)
            with recorder.lock:
                last = recorder.last_tick
            if last >= 0 and started is None:
                started = time.time()
                if not lockstep:
                    tick_s = rospy.get_param('/swarm/tick_period_s', 0.1)
                    deadline = started + s['max_ticks'] * tick_s + 30.0
            if lockstep and last >= s['max_ticks']:
                break
            if not lockstep and started is not None and \
                    time.time() - started >= s['max_ticks'] * tick_s:
                break
            if not lockstep and last >= 0:
                ended = all_ended(s, recorder)
                if ended is not None and last >= max(ended + SETTLE_TICKS, needed):
                    break
            time.sleep(0.05)
        else:
            raise RunError('the run did not reach tick %d within %.0f s (last tick %d; see %s)'
                           % (s['max_ticks'], limit, recorder.last_tick, log.name))
        params = {k: rospy.get_param('/swarm/' + k) for k in
                  ('world_size_m', 'robot_radius_m', 'local_range_m')
                  if rospy.has_param('/swarm/' + k)}
        states = robot_states(recorder) \
            if any(e['kind'] == 'released' for e in s['expect']) else None
    finally:
        stop_launch(proc, log)  # the recorder writes its files as it stops
    return recorder.log(read_metrics(directory), params, states)


def evaluate(s, first, second=None):
    """[(passed, description, measured)] for every expectation."""
    return [(ok, 'expect[%d] %s' % (i, fmt.describe(e)), measured)
            for i, e in enumerate(s['expect'])
            for ok, measured in [checks.check(e, first, s, second)]]


def needs_second_run(s):
    return any(e['kind'] == 'reproducible' for e in s['expect'])


def main(argv):
    parser = argparse.ArgumentParser(prog='scripts/scenario', description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest='cmd', required=True)
    for name in ('run', 'check'):
        p = sub.add_parser(name)
        p.add_argument('file')
        if name == 'run':
            p.add_argument('--deploy', choices=fmt.DEPLOYS, help='overrides world.deploy')
            p.add_argument('--clock', choices=fmt.CLOCKS, help='overrides world.clock')
            p.add_argument('--keep', help='keep the run files in this directory')
    a = parser.parse_args(argv)
    try:
        s = fmt.load(a.file)
    except (OSError, fmt.ScenarioError) as e:
        print('scenario: %s' % e, file=sys.stderr)
        return 2
    if a.cmd == 'check':
        print('%s: valid (%d missions, %d events, %d expectations)'
              % (a.file, len(s['missions']), len(s['events']), len(s['expect'])))
        return 0
    if a.deploy:
        s['world']['deploy'] = a.deploy
    if a.clock:
        s['world']['clock'] = a.clock
    from swarm_transport import st_ros
    directory = a.keep or tempfile.mkdtemp(prefix='st_scenario_')
    try:
        with st_ros.PrivateRos(log_dir=os.path.join(directory, 'logs')) as ros:
            import rospy
            rospy.init_node('scenario', anonymous=True, disable_signals=True)
            recorder = Recorder()
            print('[scenario] %s: %d robots, %s, %s, %d ticks' % (
                s['name'], s['world']['robots'], s['world']['clock'], s['world']['deploy'],
                s['max_ticks']))
            started = time.time()
            first = run_once(s, recorder, os.path.join(directory, 'run1'), ros.env)
            second = run_once(s, recorder, os.path.join(directory, 'run2'), ros.env) \
                if needs_second_run(s) else None
            rospy.signal_shutdown('scenario done')
    except RunError as e:
        print('[scenario] FAILED to run: %s' % e)
        return 2
    finally:
        if not a.keep:
            shutil.rmtree(directory, ignore_errors=True)
    results = evaluate(s, first, second)
    for ok, what, measured in results:
        print('%s  %s: %s' % ('PASS' if ok else 'FAIL', what, measured))
    failed = sum(1 for ok, _, _ in results if not ok)
    print('[scenario] %s: %d of %d expectations hold (%.1f s)'
          % (s['name'], len(results) - failed, len(results), time.time() - started))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
