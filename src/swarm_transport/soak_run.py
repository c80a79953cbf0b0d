"""One soak run (scripts/soak, issue 29): the swarm, the dispatcher and the recorder each in its
own roslaunch (so that each can be killed and started again), the missions source, the faults and
what each did, and the figures of the RESULT line."""

import os
import random
import signal
import time

from swarm_transport import soak_faults as sf
from swarm_transport.robot_views import ask_describe, pose_text, world_poses
from swarm_transport.soak_missions import (ABORTED, DONE, REJECTED, STATE, Missions,
                                           recorded_rows, submit)

SAMPLE_S = 5.0        # memory, descriptors and crashes are sampled this often
EFFECT_S = 15.0       # a fault's effect is read this long after it
STOP_S = 2.0          # SIGSTOP of a robot lasts this long
RESPAWN_S = 5.0       # a killed robot comes back after this long
RESTART_S = 3.0       # a killed dispatcher or recorder is started again after this long
BACK_S = 60.0         # ... and must be registered again within this long
LOSS_S = 10.0         # a burst of radio loss lasts this long
LEADER_WAIT_S = 30.0  # leader_kill waits this long at most for a mission to gather
FLOOD = 500           # invalid orders in a flood
FLOOD_FIRST_ID = 60000


class Run(object):

    def __init__(self, a, ros, log):
        self.a = a
        self.ros = ros
        self.log = log
        self.rng = random.Random(a.seed)
        self.missions = Missions()
        self.watch = sf.Watch(a.warmup_s)
        self.schedule = sf.Schedule(a.seed, a.robots, a.gap_s[0], a.gap_s[1],
                                    first_s=a.first_fault_s, kinds=a.faults)
        self.pending = []    # (at, what, callable)
        self.faults = []     # dicts: kind, at_s, what, effect
        self.launches = {}   # role -> Popen of its roslaunch
        self.starts = {}     # role -> how often it was started
        self.hung = set()
        self.leader_killed = set()  # missions whose first leader a leader_kill hit
        self.record_dir = os.path.join(a.out, 'record')
        self.run_dir = os.path.join(self.record_dir, 'soak')
        self.t0 = None

    # --- the nodes ------------------------------------------------------------------------

    def start(self):
        import rospy
        from swarm_transport.msg import Mission_Status, New_Mission, Robot_Positions
        a = self.a
        self.launches['swarm'] = self.ros.launch('swarm.launch', {
            'robots': a.robots, 'seed': a.seed, 'deploy': a.deploy, 'dispatcher': 'false',
            'recorder': 'false', 'robot_output': 'log'}, name='swarm')
        rospy.init_node('soak', disable_signals=True)
        for topic in ('/flock/mission/status', '/flock/mission/progress'):
            rospy.Subscriber(topic, Mission_Status, self.missions.on_status, queue_size=1000)
        self.flood_pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=FLOOD)
        rospy.wait_for_message('/flock/world_poses', Robot_Positions, timeout=120)
        names = self.robot_names()
        if not sf.wait(lambda: all(sf.node_pid(n) for n in names), 120, 1.0):
            raise RuntimeError('not every robot registered within 120 s (logs: %s)'
                               % self.ros.log_dir)
        # One roslaunch after the other: roslaunches started together on a fresh master race
        # for its /run_id, and the losers exit.
        for name, start in ((sf.DISPATCHER, self.start_dispatcher),
                            (sf.RECORDER, self.start_recorder)):
            start()
            if not sf.wait(lambda: sf.node_pid(name), 60, 0.5):
                raise RuntimeError('%s did not register within 60 s (logs: %s)'
                                   % (name, self.ros.log_dir))
        self.log('swarm up: %d robots (%s), logs in %s' % (a.robots, a.deploy, self.ros.log_dir))

    def robot_names(self):
        if self.a.deploy == 'host':
            return ['/robot_host']
        return [sf.robot_node(r, 'process') for r in range(self.a.robots)]

    def start_dispatcher(self):
        self.launches['dispatcher'] = self.ros.launch(
            'dispatcher.launch', {'output': 'log'}, name=self.log_name('dispatcher'))

    def start_recorder(self):
        self.launches['recorder'] = self.ros.launch(
            'recorder.launch', {'output': 'log', 'output_dir': self.record_dir,
                                'run_name': 'soak'}, name=self.log_name('recorder'))

    def log_name(self, role):
        """role_K: the K-th start of that role (each start its own log file)."""
        self.starts[role] = self.starts.get(role, 0) + 1
        return '%s_%d' % (role, self.starts[role])

    def stop_launch(self, role):
        p = self.launches.pop(role, None)
        if p is None or p.poll() is not None:
            return
        try:
            os.killpg(p.pid, signal.SIGINT)
            p.wait(timeout=15)
        except Exception:  # noqa: BLE001 - already gone, or stuck: then SIGKILL
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

    def stop(self):
        self.ros.stop()

    # --- faults ---------------------------------------------------------------------------

    def later(self, delay_s, what, fn):
        self.pending.append((time.time() + delay_s, what, fn))

    def inject(self, kind, rid, loss):
        now = time.time()
        fault = {'kind': kind, 'at_s': round(now - self.t0, 1), 'what': '', 'effect': ''}
        self.faults.append(fault)
        node = sf.robot_node(rid, self.a.deploy)
        if kind == 'robot_kill':
            self.kill_robot(rid, fault)
        elif kind == 'leader_kill':
            fault['what'] = 'waiting for a mission in GATHERING'
            self.leader_kill(fault, now + LEADER_WAIT_S)
        elif kind == 'robot_stop':
            pid = self.watch.kill(node, signal.SIGSTOP)
            fault['what'] = 'SIGSTOP %s (pid %s) for %.0f s' % (node, pid, STOP_S)
            if pid is not None:
                self.later(STOP_S, 'SIGCONT %s' % node, lambda: self.watch.resume(pid))
            self.later(EFFECT_S, 'effect', lambda: self.effect_alive(fault, node, pid))
        elif kind in ('dispatcher_restart', 'recorder_restart'):
            role = kind.split('_')[0]
            name = sf.DISPATCHER if role == 'dispatcher' else sf.RECORDER
            pid = self.watch.kill(name)
            fault['what'] = 'SIGKILL %s (pid %s), started again after %.0f s' % (
                name, pid, RESTART_S)
            self.stop_launch(role)
            start = self.start_dispatcher if role == 'dispatcher' else self.start_recorder
            self.later(RESTART_S, 'restart ' + name, start)
            self.later(RESTART_S + 1.0, 'effect',
                       lambda: self.effect_restart(fault, name, pid, time.time() + BACK_S))
        elif kind == 'radio_loss':
            self.set_radio_loss(loss)
            fault['what'] = 'radio_loss %.2f for %.0f s' % (loss, LOSS_S)
            self.later(LOSS_S, 'radio_loss back', lambda: self.set_radio_loss(0.0))
            self.later(EFFECT_S, 'effect', lambda: self.effect_missions(fault))
        elif kind == 'flood':
            for m in sf.invalid_orders(FLOOD, FLOOD_FIRST_ID):
                self.flood_pub.publish(m)
            fault['what'] = '%d invalid orders on /flock/mission/new' % FLOOD
            self.later(EFFECT_S, 'effect',
                       lambda: self.effect_alive(fault, sf.DISPATCHER, None))
        self.log('fault %d %s: %s' % (len(self.faults), kind, fault['what']))

    def leader_kill(self, fault, deadline):
        """SIGKILL of the first leader of the newest mission in GATHERING (polled until one
        gathers, at most until `deadline`), then its respawn as robot_kill's."""
        target = self.missions.leader_target(exclude=self.leader_killed)
        if target is None:
            if time.time() < deadline:
                self.later(0.1, 'leader_kill', lambda: self.leader_kill(fault, deadline))
                return
            fault['what'] = 'no mission gathered within %.0f s: nothing killed' % LEADER_WAIT_S
            fault['effect'] = self.mission_line()
            self.log('fault %s: %s' % (fault['kind'], fault['what']))
            return
        mission, rid, state = target
        self.leader_killed.add(mission)  # once per mission: its leader is gone already
        fault['at_s'] = round(time.time() - self.t0, 1)
        self.kill_robot(rid, fault, 'first leader of mission %d in %s' % (mission, state))
        self.log('fault %s: %s' % (fault['kind'], fault['what']))

    def kill_robot(self, rid, fault, who=''):
        """Robot `rid` killed (its process SIGKILLed; in a host, /kill) and back: /spawn and,
        for a process, robot.launch after RESPAWN_S. `who` (what the robot was) goes into the
        fault's description."""
        if self.a.deploy == 'host':
            fault['what'] = 'robot %d%s removed (/kill) and added again (/spawn)' % (
                rid, ', %s,' % who if who else '')
            self.respawn(rid, fault, launch=False)
            return
        pid = self.watch.kill(sf.robot_node(rid, 'process'))
        fault['what'] = ('SIGKILL robot %d (pid %s)' % (rid, pid) if pid else
                         'robot %d not running (killed by an earlier fault and not back '
                         'yet): respawned' % rid) + (', %s' % who if who else '')
        self.later(RESPAWN_S, 'respawn robot %d' % rid,
                   lambda: self.respawn(rid, fault, launch=True))

    def respawn(self, rid, fault, launch):
        import rospy
        from swarm_transport.srv import Kill, Spawn
        try:
            rospy.ServiceProxy('/kill', Kill)(robot_id=rid)
            x, y = self.rng.uniform(4.5, 6.5), self.rng.uniform(4.5, 6.5)
            answer = rospy.ServiceProxy('/spawn', Spawn)(robot_id=rid, x=x, y=y, theta=0.0)
        except Exception as e:  # noqa: BLE001
            fault['effect'] = 'respawn failed: %s' % e
            return
        if launch:
            role = 'robot_%d' % rid
            # An earlier respawn's launch of this id (a fault on it again, sooner than its next
            # respawn): the robot it started ends with it, stopped by the soak, no crash.
            earlier = self.watch.current.get(sf.robot_node(rid, self.a.deploy))
            if earlier is not None and role in self.launches:
                self.watch.killed.add(earlier)
            self.stop_launch(role)
            self.launches[role] = self.ros.launch(
                'robot.launch', {'id': rid, 'output': 'log'}, name=self.log_name(role))
        node = sf.robot_node(rid, self.a.deploy)
        self.later(EFFECT_S, 'effect', lambda: self.effect_alive(
            fault, node, None, 'spawn: %s' % answer.message))

    def set_radio_loss(self, loss):
        import dynamic_reconfigure.client
        try:
            client = dynamic_reconfigure.client.Client(sf.SIMULATOR, timeout=5.0)
            client.update_configuration({'radio_loss': loss})
        except Exception as e:  # noqa: BLE001
            self.log('radio_loss %.2f not set: %s' % (loss, e))

    def effect_alive(self, fault, node, old_pid, note='', deadline=None):
        """Whether `node` answers (polled until it does, at most BACK_S), and the missions."""
        deadline = deadline or time.time() + BACK_S
        pid = sf.node_pid(node)
        if not pid and time.time() < deadline:
            self.later(1.0, 'effect', lambda: self.effect_alive(fault, node, old_pid, note,
                                                                deadline))
            return
        state = ('%s answers (pid %s)' % (node, pid)) if pid else ('%s does not answer' % node)
        fault['effect'] = '; '.join(x for x in (note, state, self.mission_line()) if x)
        self.log('effect of fault %s: %s' % (fault['kind'], fault['effect']))

    def effect_restart(self, fault, name, old_pid, deadline):
        """Polls until the node is registered again (a roslaunch on a busy machine takes
        seconds), at most until `deadline`."""
        pid = sf.node_pid(name)
        back = pid is not None and pid != old_pid
        if not back and time.time() < deadline:
            self.later(1.0, 'effect', lambda: self.effect_restart(fault, name, old_pid, deadline))
            return
        killed_at = self.t0 + fault['at_s']
        what = ('back as pid %s after %.1f s' % (pid, time.time() - killed_at) if back
                else 'NOT back within %.0f s' % (time.time() - killed_at))
        fault['effect'] = '%s %s; %s' % (name, what, self.mission_line())
        self.log('effect of fault %s: %s' % (fault['kind'], fault['effect']))

    def effect_missions(self, fault):
        fault['effect'] = self.mission_line()
        self.log('effect of fault %s: %s' % (fault['kind'], fault['effect']))

    def mission_line(self):
        m = self.missions
        live = m.live()
        with m.lock:
            phases = ', '.join('%d %s' % (i, STATE[m.final(i)] if m.final(i) is not None
                                          else 'sent') for i in sorted(live))
        return 'live missions: %s' % (phases or 'none')

    # --- the run --------------------------------------------------------------------------

    def go(self):
        a = self.a
        self.start()
        self.t0 = time.time()
        end_faults = self.t0 + a.minutes * 60.0
        next_fault = self.schedule.draw()
        next_sample = next_progress = self.t0
        next_submit = self.t0
        while True:
            now = time.time()
            faulting = now < end_faults
            if faulting and now - self.t0 >= next_fault[0]:
                self.inject(*next_fault[1:])
                next_fault = self.schedule.draw()
            for item in [p for p in self.pending if p[0] <= now]:
                self.pending.remove(item)
                try:
                    item[2]()
                except Exception as e:  # noqa: BLE001 - logged, the soak goes on
                    self.log('%s failed: %s' % (item[1], e))
            if faulting and now >= next_submit and len(self.missions.live()) < a.live:
                submit(self.missions, a, self.rng, self.log)
                next_submit = now + 2.0
            if now >= next_sample:
                self.sample(now)
                next_sample = now + SAMPLE_S
            if now >= next_progress:
                self.progress(now)
                next_progress = now + a.progress_s
            if not faulting and not self.pending and (
                    not self.missions.live() or now > end_faults + a.drain_s):
                break
            time.sleep(0.2)
        self.sample(time.time())
        return self.result()

    def sample(self, now):
        for name in [sf.SIMULATOR, sf.DISPATCHER, sf.RECORDER] + self.robot_names():
            self.watch.track(name, now)
        self.watch.sample(now)
        hung = set(self.missions.hung(now, self.a.hung_s))
        for mission_id in sorted(hung - self.hung):
            self.describe(mission_id, 'hung (no progress for %.0f s)' % self.a.hung_s)
        self.hung.update(hung)

    def describe(self, mission_id, what):
        """A mission found hung, or still live at the end: its last status, where its robots
        are, and what each says of itself (its ~describe). Its cause is read from there."""
        with self.missions.lock:
            robots = list(self.missions.robots.get(mission_id, []))
            last = self.missions.last.get(mission_id)
        self.log('mission %d %s; its robots %s say:' % (mission_id, what, robots))
        if last is not None:
            self.log('  its last status: %s, tick %d, object at (%.2f, %.2f), %.2f m to its '
                     'target, %d of %d robots inside, lost %s'
                     % (STATE[last.state] if last.state < len(STATE) else last.state, last.tick,
                        last.object_position_x, last.object_position_y,
                        last.distance_to_target, last.robots_inside, last.robots_assigned,
                        list(last.lost)))
        self.log('  where they are: %s' % self.poses_of(robots))
        if self.a.deploy != 'process':
            return
        for r in robots:
            self.log('  robot %d: %s' % (r, ask_describe(sf.robot_node(r, 'process'))))
        # Whether they move at all (a robot that plans a move the world does not make).
        time.sleep(2.0)
        self.log('  2 s later: %s' % self.poses_of(robots))

    @staticmethod
    def poses_of(robots):
        """The robots' poses in the simulator's world (one /flock/world_poses message)."""
        try:
            poses = world_poses()
        except Exception as e:  # noqa: BLE001 - a stopped simulator: say so
            return 'unknown (%s)' % type(e).__name__
        return ', '.join('%d %s' % (r, pose_text(poses[r]))
                         for r in sorted(poses) if r in set(robots)) or 'none of them listed'

    def progress(self, now):
        m = self.missions
        self.log('missions %d: done %d, aborted %d, live %d; faults %d; crashes %d; '
                 'RSS of the nodes %.0f MB' % (
                     len(m.states), m.count(DONE), m.count(ABORTED), len(m.live()),
                     len(self.faults), len(self.watch.crashes), self.watch.rss_mb()))

    def result(self):
        m = self.missions
        rows = recorded_rows(self.run_dir)
        with m.lock:
            ended = [i for i in m.states if m.final(i) in (DONE, ABORTED)]
        lost = sorted(i for i in ended if i not in rows)
        duplicate = sum(n - 1 for i, n in rows.items() if n > 1)
        by_node = {}
        rss, rss_node, fds, fds_node = self.watch.growth(by_node)
        for t, name, pid in self.watch.crashes:
            self.log('CRASH %s (pid %d) at %.0f s' % (name, pid, t - (self.t0 or t)))
        if lost:
            self.log('missions ended without a row in %s/missions.csv: %s' % (self.run_dir, lost))
        self.hung.update(m.hung(time.time(), self.a.hung_s))
        for mission_id in sorted(set(m.live()) - self.hung):
            self.describe(mission_id, 'still live after the drain (unfinished)')
        return {
            'ok': True, 'missions': len(m.states), 'done': m.count(DONE),
            'aborted': m.count(ABORTED), 'rejected': m.count(REJECTED),
            'unfinished': len(m.live()),
            'hung': len(self.hung), 'lost_rows': len(lost), 'duplicate_rows': duplicate,
            'crashes': len(self.watch.crashes), 'rss_growth_pct': round(rss, 1),
            'rss_growth_node': rss_node, 'rss_kb_by_node': by_node,
            'fd_growth': fds, 'fd_growth_node': fds_node,
            'faults': len(self.faults), 'fault_log': self.faults,
            'fault_kinds': list(self.a.faults),
            'minutes': self.a.minutes, 'seed': self.a.seed, 'robots': self.a.robots,
            'deploy': self.a.deploy}
