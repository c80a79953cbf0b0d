#!/usr/bin/env python3
"""deploy:=host (all robots in one robot_host process) behaves exactly like deploy:=process (a
robot process each), and so does a robot_host that runs the simulator too (~deploy host_sim,
deploy:=host_sim), whose robots are linked to the simulator directly, not by topics: in
lock-step with the same seed all give identical poses at tick N. In every deployment and clock
an observer of /flock/position hears every robot."""

import os
import re
import signal
import subprocess
import sys
import threading
import time
import unittest

import rosgraph.masterapi
import rospkg
import rospy
import rostest
import yaml

import swarm_testing as st
from swarm_transport.msg import Robot_Position


PER_ROBOT_TOPIC = re.compile(r'^/robot_\d+/(neighbors|cmd_vel|answer|pose)$')


def per_robot_topics():
    """The per-robot topics between robots and simulator that someone publishes or subscribes."""
    pubs, subs, _ = rosgraph.masterapi.Master('/deploy_equivalence').getSystemState()
    return sorted(t for t, _ in pubs + subs if PER_ROBOT_TOPIC.match(t))


class PositionObserver(object):
    """An observer of /flock/position (as rostopic echo is): the robots it heard."""

    def __init__(self):
        self.lock = threading.Lock()
        self.ids = set()
        self.sub = rospy.Subscriber('/flock/position', Robot_Position, self._cb, queue_size=1000)

    def _cb(self, msg):
        if msg.type == Robot_Position.TYPE_PHYSICAL:
            with self.lock:
                self.ids.add(msg.robot_id)

    def heard(self):
        with self.lock:
            return sorted(self.ids)

    def wait_all(self, robots, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline and len(self.heard()) < robots:
            time.sleep(0.05)
        return self.heard()

    def close(self):
        self.sub.unregister()


def poses(deploy, seed, robots, ticks, timeout, topics=None, heard=None):
    """Poses at tick 0 and `ticks`; `topics` (a list) gets the per-robot topics of the run,
    `heard` (a dict) the robots an observer of /flock/position heard by deployment."""
    log = st.PositionLog()
    observer = PositionObserver()
    swarm = st.launch_swarm(robots=robots, seed=seed, lockstep=True, max_ticks=ticks,
                            deploy=deploy)
    try:
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('deploy %s: the run stopped at tick %d'
                                 % (deploy, log.latest_tick()))
        if topics is not None:
            topics.extend(per_robot_topics())
        if heard is not None:
            heard[deploy] = observer.heard()
        return log.at(0), log.at(ticks)
    finally:
        swarm.shutdown()
        log.close()
        observer.close()


def poses_one_process(seed, robots, ticks, timeout):
    """The same swarm with robots and simulator in one robot_host process (no swarm.launch):
    the parameters swarm.launch would set, the simulator's under ~simulator/; two callback
    queues, which lock-step runs from the simulator's thread like one."""
    pkg = rospkg.RosPack().get_path('swarm_transport')
    with open(os.path.join(pkg, 'config', 'swarm.yaml')) as f:
        swarm = yaml.safe_load(f)
    swarm['seed'] = seed
    rospy.set_param('/use_sim_time', True)
    rospy.set_param('/swarm', swarm)
    name = 'robot_host_sim'
    rospy.set_param('/' + name, {
        'from': 0, 'to': robots, 'clock': 'lockstep', 'deploy': 'host_sim', 'threads': 2,
        'simulator': {'robots': robots, 'clock': 'lockstep', 'lockstep_max_ticks': ticks,
                      'lockstep_observers': 1}})
    log = st.PositionLog()
    host = subprocess.Popen(['rosrun', 'swarm_transport', 'robot_host', '__name:=' + name],
                            env=os.environ.copy(), start_new_session=True)
    try:
        if not log.wait_tick(ticks, timeout):
            raise AssertionError('one process: the run stopped at tick %d' % log.latest_tick())
        return log.at(0), log.at(ticks)
    finally:
        os.killpg(host.pid, signal.SIGINT)
        try:
            host.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(host.pid, signal.SIGKILL)
            host.wait()
        log.close()


class DeployEquivalence(unittest.TestCase):

    def test_host_and_processes_end_identical(self):
        robots = rospy.get_param('~robots')
        ticks = rospy.get_param('~ticks')
        seed = rospy.get_param('~seed')
        timeout = rospy.get_param('~timeout_s')
        tol_m = rospy.get_param('~identical_tolerance_m')
        tol_deg = rospy.get_param('~identical_tolerance_deg')
        process_topics, host_sim_topics, heard = [], [], {}
        start, by_process = poses('process', seed, robots, ticks, timeout, process_topics, heard)
        _, by_host = poses('host', seed, robots, ticks, timeout, heard=heard)
        start_sim, by_host_sim = poses('host_sim', seed, robots, ticks, timeout, host_sim_topics,
                                       heard)
        start_one, by_one = poses_one_process(seed, robots, ticks, timeout)
        self.assertEqual(sorted(by_process), list(range(robots)))
        # The processes talk to the simulator on per-robot topics; with deploy:=host_sim the
        # robots and the simulator are linked directly and no such topic exists.
        self.assertIn('/robot_0/neighbors', process_topics)
        self.assertEqual(host_sim_topics, [], 'deploy:=host_sim still uses per-robot topics')
        self.assertEqual(start_sim, start, 'the host_sim run started elsewhere')
        self.assertEqual(start_one, start, 'the one-process run started elsewhere')
        for name, other in (('the host', by_host), ('host_sim', by_host_sim),
                            ('one process', by_one)):
            self.assertEqual(sorted(other), list(range(robots)), name)
            for rid in range(robots):
                self.assertLessEqual(st.moved(by_process[rid], other[rid]), tol_m,
                                     'robot %d ended at %s as a process but %s in %s'
                                     % (rid, by_process[rid], other[rid], name))
                turn = abs(by_process[rid][2] - other[rid][2]) % 360.0
                self.assertLessEqual(min(turn, 360.0 - turn), tol_deg,
                                     'robot %d heading %s vs %s in %s'
                                     % (rid, by_process[rid], other[rid], name))
        self.assertGreater(max(st.moved(start[r], by_host[r]) for r in range(robots)),
                           rospy.get_param('~min_move_m'), 'nobody moved: a trivial run')
        for deploy in ('process', 'host', 'host_sim'):
            self.assertEqual(heard[deploy], list(range(robots)),
                             'lock-step deploy:=%s: an observer of /flock/position heard only '
                             'these robots' % deploy)

    def test_position_observer_realtime(self):
        """In real time too an observer of /flock/position hears every robot, whatever the
        deployment (host_sim: test_host_sim_realtime_runs)."""
        robots = 5
        for deploy in ('process', 'host'):
            observer = PositionObserver()
            swarm = st.launch_swarm(robots=robots, seed=rospy.get_param('~seed'),
                                    lockstep=False, deploy=deploy)
            try:
                heard = observer.wait_all(robots, rospy.get_param('~timeout_s'))
            finally:
                swarm.shutdown()
                observer.close()
            self.assertEqual(heard, list(range(robots)),
                             'real time deploy:=%s: an observer of /flock/position heard only '
                             'these robots' % deploy)

    def test_host_sim_realtime_runs(self):
        """Real time has no equivalence to check, but its direct links must carry rounds to the
        robots (on their own threads) and commands back: the robots move, without per-robot
        topics."""
        robots = 5
        log = st.PositionLog()
        observer = PositionObserver()
        swarm = st.launch_swarm(robots=robots, seed=rospy.get_param('~seed'), lockstep=False,
                                deploy='host_sim')
        try:
            self.assertTrue(log.wait_tick(30, rospy.get_param('~timeout_s')),
                            'real time host_sim stopped at radio round %d' % log.latest_tick())
            topics = per_robot_topics()
            ticks = log.ticks()
            first, last = log.at(ticks[0]), log.at(ticks[-1])
            heard = observer.wait_all(robots, rospy.get_param('~timeout_s'))
        finally:
            swarm.shutdown()
            log.close()
            observer.close()
        self.assertEqual(heard, list(range(robots)),
                         'real time deploy:=host_sim: an observer of /flock/position heard only '
                         'these robots')
        self.assertEqual(topics, [], 'deploy:=host_sim still uses per-robot topics')
        self.assertEqual(sorted(last), list(range(robots)))
        self.assertGreater(max(st.moved(first[r], last[r]) for r in range(robots)),
                           rospy.get_param('~min_move_m'),
                           'nobody moved in %d radio rounds' % (ticks[-1] - ticks[0]))

    def test_host_rejects_bad_parameters(self):
        cases = ((['_from:=5', '_to:=5'], '~to must be in'),
                 (['_to:=3', '_threads:=0'], '~threads must be in'),
                 (['_to:=3', '_comm:=shout'], '~comm must be'),
                 # The simulator's clock defaults to realtime.
                 (['_to:=3', '_clock:=lockstep', '_deploy:=host_sim'],
                  '~clock is \'lockstep\' but ~simulator/clock is \'realtime\''))
        for i, (args, expect) in enumerate(cases):
            # A node name per case: private parameters from the command line stay set.
            p = subprocess.run(['rosrun', 'swarm_transport', 'robot_host',
                                '__name:=robot_host_bad%d' % i] + args, env=os.environ.copy(),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
            out = p.stdout.decode(errors='replace')
            self.assertNotEqual(p.returncode, 0, '%s exited 0:\n%s' % (args, out))
            self.assertIn(expect, out)
            self.assertEqual(len([l for l in out.splitlines() if 'FATAL' in l]), 1, out)


if __name__ == '__main__':
    rospy.init_node('deploy_equivalence_test')
    rostest.rosrun('swarm_transport', 'deploy_equivalence', DeployEquivalence, sys.argv)
