#!/usr/bin/env python3
"""The simulator's and the dispatcher's service interfaces (issue 10, item 6): status codes for
good and bad calls, and every bad call followed by a good one that takes effect (the refusal
changed nothing and stopped nothing). Typed results only: codes, /flock/robots, /flock/world_poses,
/flock/mission/new and /flock/mission/status counts.
- simulator (real time, 3 robots, no robot processes): /spawn of a used id, outside the arena,
  with a NaN -> ERROR; a good spawn -> OK and listed; /kill of an unknown id -> ERROR, of the
  spawned one -> OK and unlisted; teleport_absolute with a NaN or outside -> ERROR, a good one ->
  OK and the robot there.
- dispatcher: ~submit of a valid order -> OK and exactly one New_Mission on /flock/mission/new;
  the same id again, a NaN object, an unknown robot, an inverted range -> REJECTED with no
  New_Mission and a REJECTED status each."""

import math
import sys
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import Mission_Status, New_Mission, Robot_Positions
from swarm_transport.srv import Kill, Spawn, Submit_Mission, TeleportAbsolute

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class Latest(object):
    def __init__(self, topic, kind):
        self.msgs = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, kind, self._cb, queue_size=1000)

    def _cb(self, msg):
        with self.lock:
            self.msgs.append(msg)

    def last(self):
        with self.lock:
            return self.msgs[-1] if self.msgs else None

    def all(self):
        with self.lock:
            return list(self.msgs)


class ServiceInterface(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.timeout = g('timeout_s')
        for name in ('/spawn', '/kill', '/robot_0/teleport_absolute',
                     '/mission_dispatcher/submit'):
            rospy.wait_for_service(name, cls.timeout)
        cls.robots = Latest('/flock/robots', Robot_Positions)
        cls.positions = Latest('/flock/world_poses', Robot_Positions)

    def ids(self):
        last = self.robots.last()
        return sorted(r.robot_id for r in last.robots) if last else None

    def test_simulator_services(self):
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        kill = rospy.ServiceProxy('/kill', Kill)
        teleport = rospy.ServiceProxy('/robot_0/teleport_absolute', TeleportAbsolute)
        self.assertTrue(st.wait_for(lambda: self.ids() == [0, 1, 2], self.timeout), self.ids())
        self.assertEqual(spawn(robot_id=1, x=5.0, y=5.0, theta=0.0).code, 1)
        self.assertEqual(spawn(robot_id=7, x=50.0, y=5.0, theta=0.0).code, 1)
        self.assertEqual(spawn(robot_id=7, x=float('nan'), y=5.0, theta=0.0).code, 1)
        self.assertEqual(self.ids(), [0, 1, 2])
        ok = spawn(robot_id=7, x=5.0, y=5.0, theta=0.0)
        self.assertEqual(ok.code, 0, ok.message)
        self.assertTrue(st.wait_for(lambda: self.ids() == [0, 1, 2, 7], self.timeout), self.ids())
        self.assertEqual(kill(robot_id=9).code, 1)
        self.assertEqual(kill(robot_id=7).code, 0)
        self.assertTrue(st.wait_for(lambda: self.ids() == [0, 1, 2], self.timeout), self.ids())
        self.assertEqual(teleport(x=float('nan'), y=2.0, theta=0.0).code, 1)
        self.assertEqual(teleport(x=-3.0, y=2.0, theta=0.0).code, 1)
        self.assertEqual(teleport(x=3.0, y=2.0, theta=0.0).code, 0)

        def at_target():
            last = self.positions.last()
            r0 = [r for r in last.robots if r.robot_id == 0] if last else []
            return bool(r0) and math.hypot(r0[0].pos_x - 3.0, r0[0].pos_y - 2.0) < g('tolerance_m')
        self.assertTrue(st.wait_for(at_target, self.timeout), 'robot 0 is not at (3, 2)')

    def test_dispatcher_submit(self):
        submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
        orders = Latest('/flock/mission/new', New_Mission)
        statuses = Latest('/flock/mission/status', Mission_Status)
        # Connected to the dispatcher's publications: from now on we hear all it sends.
        for latest in (orders, statuses):
            self.assertTrue(st.wait_hears(latest.sub, ['/mission_dispatcher'], self.timeout),
                            latest.sub.name)
        base = len([m for m in orders.all() if m.mission_id == 21])
        good = st.mission(21, 0, 2, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 3.0))
        res = submit(mission=good)
        self.assertEqual(res.code, 0, res.message)
        self.assertTrue(st.wait_for(
            lambda: len([m for m in orders.all() if m.mission_id == 21]) == base + 1,
            self.timeout))
        bad = [st.mission(21, 0, 2, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 3.0)),      # live id
               st.mission(22, 0, 2, 1, (float('nan'), 6.0, 1.0, 1.0), (3.0, 3.0)),
               st.mission(23, 0, 9, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 3.0)),      # no robot 8
               st.mission(24, 2, 0, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 3.0))]      # inverted
        for order in bad:
            res = submit(mission=order)
            self.assertEqual(res.code, 1, 'mission %d accepted' % order.mission_id)
            self.assertTrue(res.message, 'no reason for mission %d' % order.mission_id)
        # A good order after the bad ones: once its New_Mission is here, any the dispatcher sent
        # before it is here too (one publisher, one connection, in order).
        sentinel = st.mission(25, 0, 2, 1, (6.0, 6.0, 1.0, 1.0), (3.0, 3.0))
        res = submit(mission=sentinel)
        self.assertEqual(res.code, 0, res.message)
        self.assertTrue(st.wait_for(lambda: any(m.mission_id == 25 for m in orders.all()),
                                    self.timeout), 'no New_Mission of the good mission 25')
        self.assertEqual(len([m for m in orders.all() if m.mission_id == 21]), base + 1)
        self.assertEqual([m for m in orders.all() if m.mission_id in (22, 23, 24)], [])
        self.assertTrue(st.wait_for(
            lambda: {22, 23, 24} <= {m.mission_id for m in statuses.all()
                                     if m.state == Mission_Status.REJECTED}, self.timeout),
            [(m.mission_id, m.state) for m in statuses.all()])


if __name__ == '__main__':
    rospy.init_node('service_interface_test')
    rostest.rosrun('swarm_transport', 'service_interface', ServiceInterface, sys.argv)
