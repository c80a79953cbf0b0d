#!/usr/bin/env python3
"""A flood of orders and freeze toggles (issue 11): 2,000 New_Mission (valid and invalid mixed)
and 10,000 Robot_Freeze / Robot_Continue toggles, published as fast as a publisher can send.
No node dies; the resident memory of the simulator, the dispatcher and a robot stays bounded;
robots act only on orders the dispatcher admitted (one admission decision); every admitted
order ends; and a valid mission sent afterwards completes."""

import math
import sys
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status, New_Mission, Robot_Continue, Robot_Freeze

import swarm_testing as st

DISPATCHER = '/mission_dispatcher'


def g(key):
    return rospy.get_param('~' + key)


def rss_mb(pid):
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def leader_only(mid, robot, target):
    return st.mission(mid, robot, robot + 1, 1, (0.0, 0.0, 0.0, 0.0), target)


class Orders(object):
    """Every order on /flock/mission/new and every status, with their publishers."""

    def __init__(self):
        self.lock = threading.Lock()
        self.admitted = set()      # ids of orders the dispatcher published
        self.robot_phases = {}     # id -> states reported by others than the dispatcher
        self.rejected = {}         # id -> reasons of the dispatcher's REJECTED
        self.subs = [rospy.Subscriber('/flock/mission/new', New_Mission, self._order,
                                      queue_size=5000),
                     rospy.Subscriber('/flock/mission/status', Mission_Status, self._status,
                                      queue_size=5000)]

    def _order(self, msg):
        if msg._connection_header.get('callerid') == DISPATCHER:
            with self.lock:
                self.admitted.add(msg.mission_id)

    def _status(self, msg):
        with self.lock:
            if msg._connection_header.get('callerid') == DISPATCHER:
                if msg.state == Mission_Status.REJECTED:
                    self.rejected.setdefault(msg.mission_id, []).append(msg.reason)
            else:
                self.robot_phases.setdefault(msg.mission_id, []).append(msg.state)

    def ended(self, mid):
        with self.lock:
            return any(s in (Mission_Status.DONE, Mission_Status.ABORTED)
                       for s in self.robot_phases.get(mid, []))

    def snapshot(self):
        with self.lock:
            return set(self.admitted), dict(self.robot_phases), dict(self.rejected)


class Flood(unittest.TestCase):

    def test_a_flood_changes_nothing_it_should_not(self):
        robots, timeout = g('robots'), g('timeout_s')
        lockstep = g('lockstep')
        orders = Orders()
        swarm = st.launch_swarm(robots=robots, seed=g('seed'), lockstep=lockstep, max_ticks=0,
                                extra_config=g('extra_config'))
        self.addCleanup(swarm.shutdown)
        log = st.PositionLog()
        self.addCleanup(log.close)
        self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
        names = ['/simulator', DISPATCHER] + ['/robot_%d/robot' % r for r in range(robots)]
        pids = {n: st.node_pid(n) for n in names}
        watched = ['/simulator', DISPATCHER, '/robot_0/robot']
        before = {n: rss_mb(pids[n]) for n in watched}

        new_pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=100000)
        freeze_pub = rospy.Publisher('/flock/freeze', Robot_Freeze, queue_size=100000)
        cont_pub = rospy.Publisher('/flock/continue', Robot_Continue, queue_size=100000)
        # Orders: the dispatcher and the simulator (lock-step) or the robots; the toggles: the
        # simulator's relay (lock-step) or the robots.
        for pub, at_least in ((new_pub, 2), (freeze_pub, 1), (cont_pub, 1)):
            self.assertTrue(st.wait_connected(pub, timeout, at_least=at_least),
                            pub.resolved_name)

        # Valid orders: leader-only trips of one robot between two points 0.5 m apart, done one
        # after the other (two leaders heading for each other's side block each other for good:
        # a leader does not swerve, SPEC 5). The rest are bad in one way each.
        nan = float('nan')
        n_missions, n_toggles = g('missions'), g('toggles')
        for i in range(n_missions):
            mid = i + 1
            kind = i % 8
            robot = 0
            target = (5.5, 5.0 + 0.5 * ((i // 8) % 2))
            if kind in (0, 4):
                msg = leader_only(mid, robot, target)
            elif kind == 1:
                msg = leader_only(mid, robot, (nan, 3.0))                    # NaN target
            elif kind == 2:
                msg = st.mission(mid, 5, 2, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0))  # inverted
            elif kind == 3:
                msg = leader_only(mid, 500, target)                          # unknown robot
            elif kind == 5:
                msg = st.mission(mid, 0, 4, 1, (7.0, 7.0, 3e38, 3e38), (3.0, 3.0))  # huge
            elif kind == 6:
                msg = leader_only(mid, robot, (40.0, 3.0))                   # outside
            else:
                msg = leader_only(mid - 3, robot, target)                    # a duplicate id
            new_pub.publish(msg)
            for _ in range(n_toggles // n_missions):
                lo = (mid * 7) % robots
                freeze = Robot_Freeze(robot_index_from=lo, robot_index_to=lo + 3)
                freeze_pub.publish(freeze)
                cont_pub.publish(Robot_Continue(robot_index_from=lo, robot_index_to=lo + 3))
        # The last toggles' freezes and a final continue travel on two topics and may arrive in
        # either order: a continue for everyone (idempotent) goes out every second from now on.
        release = rospy.Timer(rospy.Duration(1.0), lambda _: cont_pub.publish(
            Robot_Continue(robot_index_from=0, robot_index_to=65535)))
        self.addCleanup(release.shutdown)

        # Every order the dispatcher admitted ends; robots acted on nothing else.
        def all_admitted_ended():
            admitted, _, _ = orders.snapshot()
            return admitted and all(orders.ended(mid) for mid in admitted)
        if not st.wait_for(all_admitted_ended, timeout, period=0.2):
            still = sorted(m for m in orders.snapshot()[0] if not orders.ended(m))
            states = [st.robot_state(r, 5) for r in range(robots)]
            now = log.latest_tick()
            _, phases, _ = orders.snapshot()
            self.fail('admitted orders still open: %s; statuses robots said of %d: %s; robot 0 '
                      'says: %s; robots at tick %d (and 1000 before): %s'
                      % (still[:20], still[0], phases.get(still[0]),
                         st.describe_robots([0]), now, ['%d frozen=%s mission=%s at %s (%s)' % (
                             r, s.frozen, s.active_mission,
                             ['%.2f' % v for v in log.at(now).get(r, ())],
                             ['%.2f' % v for v in log.at(now - 1000).get(r, ())])
                             for r, s in enumerate(states)]))
        admitted, phases, rejected = orders.snapshot()
        rogue = sorted(set(phases) - admitted)
        self.assertEqual(rogue, [], 'robots acted on orders the dispatcher did not admit')
        self.assertGreater(len(rejected), 0, 'the flood made no rejection at all')
        rospy.loginfo('flood: %d orders admitted, %d rejected (%d for the limit of live '
                      'missions)', len(admitted), len(rejected),
                      sum(1 for r in rejected.values() if 'too many live' in ' '.join(r)))

        # A valid mission afterwards is admitted and completes.
        after = 3000
        new_pub.publish(leader_only(after, 1, (5.5, 5.5)))
        self.assertTrue(st.wait_for(lambda: orders.ended(after), timeout, period=0.1),
                        'the mission sent after the flood never ended: %s'
                        % orders.snapshot()[1].get(after))
        self.assertIn(Mission_Status.DONE, orders.snapshot()[1][after])

        for name, pid in pids.items():
            self.assertTrue(st.process_alive(pid), '%s died in the flood' % name)
        bound = g('max_rss_growth_mb')
        for name in watched:
            grew = rss_mb(pids[name]) - before[name]
            rospy.loginfo('flood: %s resident memory %.1f MB -> %.1f MB', name, before[name],
                          before[name] + grew)
            self.assertLessEqual(grew, bound, '%s grew by %.1f MB' % (name, grew))


if __name__ == '__main__':
    rospy.init_node('flood_test')
    rostest.rosrun('swarm_transport', 'flood', Flood, sys.argv)
