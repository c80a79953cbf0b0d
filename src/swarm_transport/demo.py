"""scripts/demo: a swarm of N robots on a private ROS master, headless unless --rviz. By default
it sends the thesis's transport mission (robots [0, 12), 3 leaders, 2x2 object at (7, 7) to
(3, 3)), runs it to DONE and prints the phases; --no-mission only lets the swarm flock for a
bounded time."""

import argparse
import math
import os
import subprocess
import sys
import time

from swarm_transport import st_ros
from swarm_transport.core_metrics import components


def parse_args(argv):
    p = argparse.ArgumentParser(prog='scripts/demo', description=__doc__)
    p.add_argument('--robots', type=int, default=25, help='number of robots (default 25)')
    p.add_argument('--seed', type=int, default=1, help='seed (default 1)')
    p.add_argument('--realtime', action='store_true',
                   help='wall-clock ticks instead of lock-step')
    p.add_argument('--ticks', type=int, default=600,
                   help='lock-step: ticks to run (default 600)')
    p.add_argument('--seconds', type=float, default=30.0,
                   help='real time: seconds to run (default 30); lock-step: wall time limit')
    p.add_argument('--rviz', action='store_true',
                   help='show the swarm in rviz (config/swarm.rviz); lock-step paced at --rate '
                   'so that it can be watched (--realtime: the wall clock instead)')
    p.add_argument('--rate', type=float, default=None,
                   help='lock-step: real_time_factor, simulated s per wall s (default 1.0 with '
                   '--rviz, else 0: as fast as possible)')
    p.add_argument('--screenshot', default='',
                   help='with --rviz: save a PNG of the screen at --screenshot-tick')
    p.add_argument('--screenshot-tick', type=int, default=20,
                   help='with --screenshot: the tick of the picture, counted from the first tick '
                   'of TRANSPORT (default 20; --no-mission: from the start); lock-step holds the '
                   'run at that tick for the picture, real time takes it at that radio round')
    p.add_argument('--trails', type=int, default=0,
                   help='rviz: a line through each robot\'s last K positions (default 0: off)')
    p.add_argument('--range-circles', action='store_true',
                   help='rviz: each robot\'s local range, in its swarm\'s colour')
    p.add_argument('--bag', default='',
                   help='record the run with rosbag into this file (swarm.launch record:=true): '
                   'replay it with replay.launch, or rosbag play it beside rviz')
    p.add_argument('--config', default='', help='extra YAML merged over config/swarm.yaml')
    p.add_argument('--no-mission', action='store_true',
                   help='no transport mission: let the swarm flock for --ticks / --seconds')
    p.add_argument('--group', type=int, default=12,
                   help='mission: robots [0, group) carry the object (default 12)')
    p.add_argument('--leaders', type=int, default=3, help='mission: leaders (default 3)')
    p.add_argument('--mode', choices=['swarm', 'formation'], default='swarm',
                   help='mission: transport mode (default swarm, the thesis\'s; formation '
                   'carries the object as one body)')
    p.add_argument('--timeout', type=float, default=600.0,
                   help='mission: give up after this many wall seconds (default 600)')
    a = p.parse_args(argv)
    if a.robots < 1 or a.robots > 65535:
        p.error('--robots must be in [1, 65535]')
    if a.ticks < 1 or not (a.seconds > 0) or not (a.timeout > 0):
        p.error('--ticks, --seconds and --timeout must be positive')
    if not a.no_mission and not 1 <= a.leaders <= a.group <= a.robots:
        p.error('need 1 <= --leaders <= --group <= --robots')
    if a.screenshot and not a.rviz:
        p.error('--screenshot needs --rviz')
    if not 0 <= a.trails <= 10000:
        p.error('--trails must be in [0, 10000]')
    if a.screenshot_tick < 0:
        p.error('--screenshot-tick must be >= 0')
    if a.rate is None:
        a.rate = 1.0 if a.rviz else 0.0  # paced: rviz draws every tick, people can follow
    if not (a.rate >= 0.0 and math.isfinite(a.rate)):
        p.error('--rate must be a number >= 0')
    return a


def start_display(ros):
    """A virtual display when none is given, so rviz can run headless (and be screenshot);
    returns it and whether it is virtual."""
    if os.environ.get('DISPLAY'):
        return os.environ['DISPLAY'], False
    display = ':%d' % (90 + ros.port % 100)
    ros.start(['Xvfb', display, '-screen', '0', '1280x1024x24'], 'xvfb')
    time.sleep(1.0)
    ros.env['DISPLAY'] = display
    ros.env['LIBGL_ALWAYS_SOFTWARE'] = '1'
    os.environ['DISPLAY'] = display
    return display, True


def main(argv):
    a = parse_args(argv)
    with st_ros.PrivateRos() as ros:
        st_ros.log('[demo] private ROS master on port %d, logs in %s' % (ros.port, ros.log_dir))
        launch_args = {'robots': a.robots, 'seed': a.seed, 'observers': 1,
                       'lockstep': 'false' if a.realtime else 'true',
                       'rviz': 'true' if a.rviz else 'false'}
        if not a.realtime:
            launch_args['real_time_factor'] = a.rate
        if a.trails:
            launch_args['trail_ticks'] = a.trails
        if a.range_circles:
            launch_args['range_circles'] = 'true'
        if a.rviz:
            display, virtual = start_display(ros)
            st_ros.log('[demo] rviz on display %s%s' % (display, ' (virtual)' if virtual else ''))
            if virtual:
                launch_args['rviz_args'] = '--fullscreen'  # nobody sees its panels: all view
        if a.config:
            launch_args['extra_config'] = os.path.abspath(a.config)
        if a.bag:
            launch_args['record'] = 'true'
            launch_args['bag'] = os.path.abspath(a.bag)
        if not a.realtime and a.no_mission:
            launch_args['max_ticks'] = a.ticks
        started = time.time()
        ros.launch('swarm.launch', launch_args)

        import rospy
        from swarm_transport.msg import Robot_Positions
        rospy.init_node('demo', anonymous=True, disable_signals=True)
        local_range = rospy.get_param('/swarm/local_range_m', 1.0) if _wait_param() else 1.0
        state = {'last': None, 'first_tick_wall': None, 'first': None, 'counts': [],
                 'group': {}}

        def on_positions(msg):
            # The mission's robots at every tick, for the transport's slip.
            state['group'][msg.tick] = {r.robot_id: (r.pos_x, r.pos_y) for r in msg.robots
                                        if r.type == 0 and r.robot_id < a.group}
            if state['first'] is None:
                state['first'] = msg
                state['first_tick_wall'] = time.time()
            state['last'] = msg
            if msg.tick % 100 == 0:
                pts = [(r.pos_x, r.pos_y) for r in msg.robots if r.type == 0]
                state['counts'].append((msg.tick, msg.sim_time, components(pts, local_range)[0]))

        if not a.no_mission:
            # Lock-step waits for this demo's subscription before its first tick: the mission
            # goes out first, so it is relayed at tick 0 and a seed gives the same run.
            ok = _run_mission(a, ros, state, lambda: rospy.Subscriber(
                '/flock/world_poses', Robot_Positions, on_positions, queue_size=50))
            if a.rviz and a.screenshot and not state.get('shot'):
                st_ros.log('[demo] no screenshot at TRANSPORT + %d: the mission ended first'
                           % a.screenshot_tick)
            rospy.signal_shutdown('demo done')
            _report(a, state, local_range, time.time() - started)
            return 0 if ok else 1
        rospy.Subscriber('/flock/world_poses', Robot_Positions, on_positions, queue_size=50)
        limit = a.seconds if a.realtime else max(a.seconds, 60.0 + a.ticks * a.robots * 0.002)
        deadline = time.time() + limit + 60.0
        ok = True
        while time.time() < deadline:
            if not ros.alive('roslaunch'):
                st_ros.log('[demo] roslaunch ended early: see %s' % ros.log_dir)
                ok = False
                break
            last = state['last']
            if a.rviz and a.screenshot and not state.get('shot'):
                if a.realtime or a.screenshot_tick < a.ticks:
                    _screenshot_at(ros, a, state, a.screenshot_tick, 'the start')
                else:
                    st_ros.log('[demo] no screenshot: --screenshot-tick is beyond --ticks')
                    state['shot'] = True
                continue
            if last is not None:
                if not a.realtime and last.tick >= a.ticks:
                    break
                if a.realtime and time.time() - state['first_tick_wall'] >= a.seconds:
                    break
            time.sleep(0.2)
        else:
            st_ros.log('[demo] time limit reached')
            ok = state['last'] is not None
        rospy.signal_shutdown('demo done')
        wall = time.time() - started
        _report(a, state, local_range, wall)
        if state['last'] is None:
            st_ros.log('[demo] FAILED: no tick was ever simulated (see %s)' % ros.log_dir)
            ok = False
    return 0 if ok else 1


PHASES = {0: 'QUEUED', 1: 'GATHERING', 2: 'LOADING', 3: 'TRANSPORT', 4: 'UNLOADING',
          5: 'DONE', 6: 'ABORTED', 7: 'REJECTED'}
MISSION_ID = 7
OBJECT = (7.0, 7.0, 2.0, 2.0)
TARGET = (3.0, 3.0)


def _run_mission(a, ros, state, observe):
    """Sends the thesis mission through the dispatcher and follows it to its end."""
    import rospy
    from swarm_transport.msg import Mission_Status, New_Mission
    from swarm_transport.srv import Submit_Mission
    phases = []  # (state, tick, wall)

    def on_status(msg):
        if msg.mission_id == MISSION_ID and (not phases or phases[-1][0] != msg.state):
            phases.append((msg.state, msg.tick, time.time(), msg))
            st_ros.log('[demo] mission %d %-9s tick %6d  inside %2d/%-2d  object (%.2f, %.2f)'
                       % (MISSION_ID, PHASES.get(msg.state, '?'), msg.tick, msg.robots_inside,
                          msg.robots_assigned, msg.object_position_x, msg.object_position_y))

    rospy.Subscriber('/flock/mission/status', Mission_Status, on_status, queue_size=100)
    submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
    try:
        submit.wait_for_service(180)
    except rospy.ROSException:
        st_ros.log('[demo] FAILED: the mission dispatcher did not come up (see %s)' % ros.log_dir)
        return False
    m = New_Mission(robot_index_from=0, robot_index_to=a.group, leader_number=a.leaders,
                    mission_id=MISSION_ID, object_position_x=OBJECT[0],
                    object_position_y=OBJECT[1], object_size_x=OBJECT[2],
                    object_size_y=OBJECT[3], target_x=TARGET[0], target_y=TARGET[1],
                    transport_mode=(New_Mission.MODE_FORMATION if a.mode == 'formation'
                                    else New_Mission.MODE_SWARM))
    sent = time.time()
    answer = submit(m)
    st_ros.log('[demo] submitted: %s' % answer.message)
    if answer.code != 0:
        st_ros.log('[demo] FAILED: the dispatcher rejected the mission')
        return False
    observe()
    deadline = sent + a.timeout
    while time.time() < deadline:
        if phases and phases[-1][0] in (5, 6, 7):
            break
        if a.rviz and a.screenshot and not state.get('shot') and phases and phases[-1][0] == 3:
            # The object on its way, leaders in front: a stated tick of TRANSPORT.
            _screenshot_at(ros, a, state, phases[-1][1] + a.screenshot_tick, 'TRANSPORT')
        if not ros.alive('roslaunch'):
            st_ros.log('[demo] FAILED: roslaunch ended early: see %s' % ros.log_dir)
            return False
        time.sleep(0.1)
    state['phases'], state['sent'] = phases, sent
    if not phases or phases[-1][0] != 5:
        reason = phases[-1][3].reason if phases else 'no status at all'
        st_ros.log('[demo] FAILED: mission %d ended %s after %.0f s: %s'
                   % (MISSION_ID, PHASES.get(phases[-1][0], '?') if phases else 'nowhere',
                      time.time() - sent, reason or 'timeout'))
        return False
    return True


def _wait_param():
    import rospy
    deadline = time.time() + 30
    while time.time() < deadline:
        if rospy.has_param('/swarm/local_range_m'):
            return True
        time.sleep(0.1)
    return False


def _screenshot_at(ros, a, state, tick, since):
    """Takes the screenshot at simulated tick `tick` (`since`: what it counts from, for the
    log). Lock-step: holds the run before that tick (the simulator's ~hold), waits until rviz got
    the markers of that tick, takes it and lets the run go on. Real time: takes it once the
    radio round `tick` went out (markers follow at their wall-clock rate)."""
    import rospy
    from visualization_msgs.msg import MarkerArray
    state['shot'] = True
    if a.realtime:
        while state['last'] is None or state['last'].tick < tick:
            if not ros.alive('roslaunch'):
                return
            time.sleep(0.02)
        time.sleep(0.3)
        _screenshot(ros, a.screenshot, 'radio round %d (%s + %d, real time: about)'
                    % (state['last'].tick, since, a.screenshot_tick))
        return
    from swarm_transport.srv import Hold
    hold = rospy.ServiceProxy('/simulator/hold', Hold)
    hold.wait_for_service(60)
    answer = hold(tick)
    if answer.code != 0:
        st_ros.log('[demo] cannot hold at tick %d (%s): holding at the next one' % (
            tick, answer.message))
        tick = answer.current_tick + 1
        answer = hold(tick)
        if answer.code != 0:
            st_ros.log('[demo] no screenshot: %s' % answer.message)
            return
    shown = {'tick': None}
    label = 'tick %d ' % tick

    def on_markers(msg):
        for m in msg.markers:
            if m.ns == 'status' and m.text.startswith(label):
                shown['tick'] = tick
    sub = rospy.Subscriber('/flock/markers', MarkerArray, on_markers, queue_size=5)
    deadline = time.time() + 120
    while time.time() < deadline and ros.alive('roslaunch'):
        if hold(tick).holding and shown['tick'] == tick:
            break
        time.sleep(0.1)
    else:
        st_ros.log('[demo] no screenshot: the run never held at tick %d' % tick)
        sub.unregister()
        hold(0)
        return
    time.sleep(2.0)  # rviz draws the markers of that tick (30 frames a second, software GL)
    _screenshot(ros, a.screenshot, 'tick %d (%s + %d, held)' % (tick, since,
                                                                 a.screenshot_tick))
    sub.unregister()
    hold(0)


def _screenshot(ros, path, when):
    xwd = os.path.join(ros.log_dir, 'screen.xwd')
    subprocess.call(['xwd', '-root', '-silent', '-out', xwd], env=ros.env)
    subprocess.call(['convert', xwd, path], env=ros.env)
    st_ros.log('[demo] screenshot at %s: %s' % (when, path))


def _report_transport(a, state, phases):
    """Transport ticks and slip (the recorder's definitions) against the ideal: the straight
    distance at full speed with no slip, what a group of all leaders comes close to."""
    import rospy
    ticks = {code: tick for code, tick, _, _ in phases}
    if 3 not in ticks or 4 not in ticks:
        return
    start, end = ticks[3], ticks[4]
    frames = [state['group'].get(t) for t in range(start, end + 1)]
    if any(f is None for f in frames) or not frames[0]:
        st_ros.log('transport: frames missing, no slip computed')
        return
    slip = 0.0
    for before, after in zip(frames, frames[1:]):
        cb = [sum(p[k] for p in before.values()) / len(before) for k in (0, 1)]
        ca = [sum(p[k] for p in after.values()) / len(after) for k in (0, 1)]
        for rid, p in after.items():
            q = before[rid]
            slip += math.hypot((ca[0] - p[0]) - (cb[0] - q[0]), (ca[1] - p[1]) - (cb[1] - q[1]))
    slip /= len(frames[0])
    speed = rospy.get_param('/swarm/speed_m_per_tick', 0.1)
    tolerance = rospy.get_param('/swarm/goal_tolerance_m', 0.05)
    ideal = (math.hypot(OBJECT[0] - TARGET[0], OBJECT[1] - TARGET[1]) - tolerance) / speed
    st_ros.log('transport (%s mode)  %d ticks, slip %.3f m per robot; ideal (straight at full '
               'speed, no slip) %.1f ticks: %.2fx' % (a.mode, end - start, slip, ideal,
                                                      (end - start) / ideal))


def _report(a, state, local_range, wall):
    first, last = state['first'], state['last']
    if last is None:
        return
    pts0 = [(r.pos_x, r.pos_y) for r in first.robots if r.type == 0]
    pts = [(r.pos_x, r.pos_y) for r in last.robots if r.type == 0]
    ticks = last.tick - first.tick
    run_wall = max(time.time() - state['first_tick_wall'], 1e-6)
    st_ros.log('')
    st_ros.log('=== swarm_transport demo ===')
    st_ros.log('robots %d, seed %d, clock %s' % (len(pts), a.seed,
                                                  'realtime' if a.realtime else 'lockstep'))
    st_ros.log('ticks simulated      %d (sim time %.1f s) in %.1f s wall -> %.1f ticks/s'
               % (ticks, last.sim_time, run_wall, ticks / run_wall))
    st_ros.log('swarm count          start %d -> end %d (components within %.2f m)'
               % (components(pts0, local_range)[0], components(pts, local_range)[0], local_range))
    if state['counts']:
        st_ros.log('swarm count by tick  ' + ', '.join('%d:%d' % (t, c)
                                                     for t, _, c in state['counts'][-8:]))
    phases = state.get('phases')
    if phases:
        st_ros.log('mission %d: robots [0, %d), %d leaders, object %.0fx%.0f at (%.0f, %.0f) '
                   '-> (%.0f, %.0f)' % ((MISSION_ID, a.group, a.leaders) + OBJECT[2:] + OBJECT[:2] +
                                        TARGET))
        st_ros.log('  %-10s %8s %8s %10s' % ('phase', 'tick', 'ticks', 'wall s'))
        for i, (code, tick, at, _) in enumerate(phases):
            nxt = phases[i + 1] if i + 1 < len(phases) else None
            # Every phase, QUEUED included, is reported by the first leader with its tick.
            ticks = '%d' % (nxt[1] - tick) if nxt else '-'
            st_ros.log('  %-10s %8s %8s %10s' % (
                PHASES.get(code, '?'), tick, ticks,
                '%.2f' % (nxt[2] - at) if nxt else '-'))
        end = phases[-1][3]
        err = math.hypot(end.object_position_x - TARGET[0], end.object_position_y - TARGET[1])
        st_ros.log('object error at the end %.4f m (tolerance 0.05)' % err)
        _report_transport(a, state, phases)
        st_ros.log('mission wall time      %.2f s (submit to %s)'
                   % (phases[-1][2] - state['sent'], PHASES.get(phases[-1][0], '?')))
    moved = sum(1 for p, q in zip(pts0, pts) if math.hypot(p[0] - q[0], p[1] - q[1]) > 1e-3)
    st_ros.log('robots that moved    %d of %d' % (moved, len(pts)))
    st_ros.log('total wall time      %.1f s' % wall)


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
