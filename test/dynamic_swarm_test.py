#!/usr/bin/env python3
"""A swarm that changes size while it runs (issue 11, SPEC 9.1). With one process per robot
(~deploy process, lock-step):
- /spawn and then `roslaunch swarm_transport robot.launch id:=N` add a robot: it is listed on
  /flock/robots, moves with the swarm, and the next mission can name it (a leader-only mission
  of that robot ends DONE);
- /kill removes it: it leaves the list and its process stops (a re-spawned id gets a fresh one);
- New_Robot (type 0) adds a robot at a free place, Delete_Robot (sub_id 0) removes one; a
  Delete_Robot naming no robot changes nothing, and the good one after it takes effect;
- a robot process whose id the simulator does not have idles (and says so once) until the id
  is spawned; then it joins;
- a robot process started for a new id (`roslaunch swarm_transport robot.launch id:=N`) joins
  the running lock-step swarm when the id is spawned beside the others: per tick of
  /flock/world_poses it moves in the first or second tick after it first appears there (the
  bound is argued in dynamic_swarm.test), it is within local range of a neighbour and hears
  the others, and the next mission naming it ends DONE;
- a mission naming a spawned robot whose process starts only after the mission was sent
  reaches it in its first round (as a latched topic would): it ends DONE.
With all robots in one robot_host (~deploy host_sim or host, either clock): the host starts a
robot for every robot spawned (/spawn, New_Robot) and removes it when it leaves (/kill,
Delete_Robot); it moves with the swarm and can be named by the next mission."""

import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import Delete_Robot, New_Mission, New_Robot, Robot_Positions
from swarm_transport.srv import Hold, Kill, Spawn

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RobotList(object):
    """The latest latched /flock/robots (the simulator's list of robots)."""

    def __init__(self):
        self.ids = None
        self.sub = rospy.Subscriber('/flock/robots', Robot_Positions, self._cb, queue_size=10)

    def _cb(self, msg):
        self.ids = sorted(r.robot_id for r in msg.robots if r.type == 0)


class DynamicSwarm(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.timeout = g('timeout_s')
        cls.log = st.PositionLog()
        cls.deploy = g('deploy')
        cls.lockstep = g('lockstep')
        cls.swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=cls.lockstep,
                                    max_ticks=0, deploy=cls.deploy)
        assert cls.log.wait_tick(3, cls.timeout), 'the swarm never ticked'
        cls.list = RobotList()
        cls.extra = []

    @classmethod
    def tearDownClass(cls):
        for parent in cls.extra:
            parent.shutdown()
        cls.swarm.shutdown()
        cls.log.close()

    def listed(self, ids):
        return st.wait_for(lambda: self.list.ids == sorted(ids), self.timeout)

    def moves(self, robot, start):
        return st.wait_for(
            lambda: st.moved(self.log.at(self.log.latest_tick()).get(robot, start), start)
            >= g('moves_m'), self.timeout)

    def order(self, mission_id, robot, target=None):
        """Sends a leader-only mission of `robot`; returns the StatusLog that follows it."""
        status = st.StatusLog()
        self.assertTrue(status.wait_connected(self.timeout), 'the status log never connected')
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10, latch=True)
        self.assertTrue(st.wait_connected(pub, self.timeout))
        pub.publish(st.mission(mission_id, robot, robot + 1, 1, (0.0, 0.0, 0.0, 0.0),
                               g('lead_target') if target is None else target))
        return status

    def lead(self, mission_id, robot, target=None):
        """A leader-only mission of `robot` ends DONE (the next mission can name it)."""
        status = self.order(mission_id, robot, target)
        self.assertTrue(st.wait_for(lambda: status.final(mission_id), self.timeout),
                        'the mission of robot %d did not end: %s'
                        % (robot, status.states(mission_id)))
        self.assertEqual(status.states(mission_id)[-1], 'DONE', status.states(mission_id))

    def start(self):
        """The initial robots listed; returns their ids and the /spawn and /kill services."""
        base = list(range(g('robots')))
        self.assertTrue(self.listed(base), self.list.ids)
        rospy.wait_for_service('/spawn', self.timeout)
        return base, rospy.ServiceProxy('/spawn', Spawn), rospy.ServiceProxy('/kill', Kill)

    def test_a_host_starts_and_removes_robots(self):
        if self.deploy == 'process':
            self.skipTest('one process per robot: see the other tests')
        base, spawn, kill = self.start()
        new = len(base)
        self.assertEqual(spawn(robot_id=new, x=2.0, y=9.0, theta=0.0).code, 0)
        self.assertTrue(self.listed(base + [new]), self.list.ids)
        self.assertTrue(self.moves(new, (2.0, 9.0)), 'robot %d never moved' % new)
        self.assertTrue(st.wait_for(lambda: st.robot_state(new, self.timeout).ticks > 0,
                                    self.timeout))
        self.lead(32, new)
        # Killed, it leaves the list and the host: its services go with it.
        self.assertEqual(kill(robot_id=new).code, 0)
        self.assertTrue(self.listed(base), self.list.ids)
        self.assertTrue(st.wait_for(
            lambda: '/robot_%d/robot/state' % new not in st.service_names(), self.timeout),
            'the host still runs robot %d' % new)
        # A New_Robot joins the same way, a Delete_Robot removes it.
        joins = rospy.Publisher('/flock/robot/new', New_Robot, queue_size=10)
        leaves = rospy.Publisher('/flock/robot/delete', Delete_Robot, queue_size=10)
        self.assertTrue(st.wait_connected(joins, self.timeout))
        self.assertTrue(st.wait_connected(leaves, self.timeout))
        joins.publish(New_Robot(robot_id=new + 1, sub_id=0, type=0))
        self.assertTrue(self.listed(base + [new + 1]), self.list.ids)
        self.assertTrue(st.wait_for(lambda: st.robot_state(new + 1, self.timeout).ticks > 0,
                                    self.timeout))
        leaves.publish(Delete_Robot(robot_id=new + 1, sub_id=0))
        self.assertTrue(self.listed(base), self.list.ids)
        self.assertTrue(st.wait_for(
            lambda: '/robot_%d/robot/state' % (new + 1) not in st.service_names(), self.timeout))

    def test_robots_join_and_leave_while_the_swarm_runs(self):
        if self.deploy != 'process':
            self.skipTest('a process per robot only')
        base, spawn, kill = self.start()
        n = len(base)

        # /spawn + its own process: listed, moving, and named by the next mission.
        new = n
        self.assertEqual(spawn(robot_id=new, x=2.0, y=9.0, theta=0.0).code, 0)
        self.assertTrue(self.listed(base + [new]), self.list.ids)
        self.extra.append(st.launch_file('robot.launch', id=new, clock='lockstep'))
        self.assertTrue(self.moves(new, (2.0, 9.0)), 'robot %d never moved after joining' % new)
        self.lead(31, new)

        # /kill: it leaves the list and its process stops.
        pid = st.node_pid('/robot_%d/robot' % new)
        self.assertEqual(kill(robot_id=new).code, 0)
        self.assertTrue(self.listed(base), self.list.ids)
        self.assertTrue(st.wait_for(lambda: not st.process_alive(pid), self.timeout),
                        'the process of the killed robot %d still runs' % new)

        # New_Robot / Delete_Robot on their topics.
        joins = rospy.Publisher('/flock/robot/new', New_Robot, queue_size=10)
        leaves = rospy.Publisher('/flock/robot/delete', Delete_Robot, queue_size=10)
        self.assertTrue(st.wait_connected(joins, self.timeout))
        self.assertTrue(st.wait_connected(leaves, self.timeout))
        other = n + 1
        joins.publish(New_Robot(robot_id=other, sub_id=0, type=0))
        self.assertTrue(self.listed(base + [other]), self.list.ids)
        # It stands in the world (at a free place drawn from the seed).
        self.assertTrue(st.wait_for(lambda: other in self.log.at(self.log.latest_tick()),
                                    self.timeout))
        leaves.publish(Delete_Robot(robot_id=n + 40, sub_id=0))  # no such robot: nothing
        leaves.publish(Delete_Robot(robot_id=other, sub_id=0))
        self.assertTrue(self.listed(base), self.list.ids)

    def test_a_joining_robot_flocks_from_its_first_ticks(self):
        if self.deploy != 'process' or not self.lockstep:
            self.skipTest('a process per robot in lock-step only')
        base = list(range(g('robots')))
        self.assertTrue(self.listed(base), self.list.ids)
        joiner = g('robots') + g('joiner_offset')
        self.extra.append(st.launch_file('robot.launch', id=joiner, clock='lockstep'))
        self.assertFalse(st.robot_state(joiner, self.timeout).listed)
        # Beside a robot of the swarm, half a local range from it towards the arena's centre:
        # the run holds (~hold) while the place is chosen and the robot spawned, so that the
        # others do not move on meanwhile (unpaced lock-step runs hundreds of ticks per second).
        local_range = rospy.get_param('/swarm/local_range_m')
        centre = rospy.get_param('/swarm/world_size_m') / 2.0
        hold = rospy.ServiceProxy('/simulator/hold', Hold)
        hold.wait_for_service(self.timeout)
        at = None
        while at is None or hold(tick=at).code != 0:
            at = self.log.latest_tick() + 50
        self.assertTrue(st.wait_for(lambda: hold(tick=at).holding, self.timeout), 'never held')
        self.addCleanup(hold, tick=0)
        self.assertTrue(self.log.wait_tick(at - 1, self.timeout))
        near = self.log.at(at - 1)[base[0]]
        d = st.moved((centre, centre), near)
        step = 0.5 * local_range / max(d, 1e-9)
        place = (near[0] + (centre - near[0]) * step, near[1] + (centre - near[1]) * step)
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        spawn.wait_for_service(self.timeout)
        kill = rospy.ServiceProxy('/kill', Kill)
        self.assertEqual(spawn(robot_id=joiner, x=place[0], y=place[1], theta=0.0).code, 0)
        self.addCleanup(kill, robot_id=joiner)  # also when an assertion fails: the next tests
        self.assertEqual(hold(tick=0).code, 0)
        self.assertTrue(st.wait_for(lambda: any(joiner in self.log.at(k)
                                                for k in self.log.ticks()), self.timeout),
                        'robot %d never appeared on /flock/world_poses' % joiner)
        first = min(k for k in self.log.ticks() if joiner in self.log.at(k))
        bound = g('moves_within_ticks')
        self.assertTrue(self.log.wait_tick(first + g('in_swarm_within_ticks'), self.timeout))
        track = [self.log.at(k).get(joiner) for k in range(first, first + bound + 1)]
        self.assertNotIn(None, track, 'a tick of /flock/world_poses is missing (from %d)' % first)
        moved = [k for k in range(1, bound + 1)
                 if st.moved(track[k], track[0]) >= g('tick_move_m')]
        self.assertTrue(moved, 'robot %d first appeared at tick %d and had not moved by tick %d: '
                        '%s' % (joiner, first, first + bound, track))
        # In the others' swarm: within local range of one of them at every tick until then.
        for k in range(first, first + g('in_swarm_within_ticks') + 1):
            now = self.log.at(k)
            gap = min(st.moved(now[joiner], p) for r, p in now.items() if r != joiner)
            self.assertLessEqual(gap, local_range, 'robot %d is %.2f m from its nearest '
                                 'neighbour at tick %d (it appeared at tick %d)'
                                 % (joiner, gap, k, first))
        state = st.robot_state(joiner, self.timeout)
        self.assertTrue(state.listed)
        self.assertGreater(state.ticks, 0)
        # The next mission can name it.
        self.lead(33, joiner, [min(max(place[0] + 0.5, 1.0), 2 * centre - 1.0),
                               min(max(place[1] - 0.5, 1.0), 2 * centre - 1.0)])

    def test_a_mission_reaches_a_robot_whose_process_connects_after_it(self):
        if self.deploy != 'process' or not self.lockstep:
            self.skipTest('a process per robot in lock-step only')
        # Spawned without a process it stands; a mission naming it is sent and relayed to the
        # live robots; its process starts only then. Its first round carries the order (a
        # latched topic would give it too): the mission ends DONE.
        late = g('robots') + g('late_offset')
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        spawn.wait_for_service(self.timeout)
        kill = rospy.ServiceProxy('/kill', Kill)
        self.assertEqual(spawn(robot_id=late, x=9.0, y=9.0, theta=0.0).code, 0)
        self.addCleanup(kill, robot_id=late)
        self.assertTrue(st.wait_for(lambda: late in self.log.at(self.log.latest_tick()),
                                    self.timeout))
        status = self.order(35, late, g('late_target'))
        t = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(t + g('late_after_ticks'), self.timeout))
        self.assertFalse(status.final(35), status.states(35))
        self.extra.append(st.launch_file('robot.launch', id=late, clock='lockstep'))
        self.assertTrue(st.wait_for(lambda: status.final(35), self.timeout),
                        'the mission of robot %d, whose process connected after it was sent, '
                        'did not end: %s' % (late, status.states(35)))
        self.assertEqual(status.states(35)[-1], 'DONE', status.states(35))

    def test_a_robot_process_without_a_robot_idles_until_spawned(self):
        if self.deploy != 'process':
            self.skipTest('a process per robot only')
        ghost = g('robots') + 20
        self.extra.append(st.launch_file('robot.launch', id=ghost, clock='lockstep'))
        state = st.robot_state(ghost, self.timeout)
        self.assertFalse(state.listed)
        t = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(t + 20, self.timeout))
        state = st.robot_state(ghost, self.timeout)
        self.assertFalse(state.listed)
        self.assertEqual(state.ticks, 0, 'robot %d ticked without a robot in the world' % ghost)
        # Spawned, the waiting process joins: listed, ticking, moving.
        spawn = rospy.ServiceProxy('/spawn', Spawn)
        spawn.wait_for_service(self.timeout)
        self.assertEqual(spawn(robot_id=ghost, x=9.0, y=2.0, theta=0.0).code, 0)
        self.assertTrue(st.wait_for(lambda: st.robot_state(ghost, self.timeout).listed,
                                    self.timeout))
        self.assertTrue(self.moves(ghost, (9.0, 2.0)),
                        'robot %d never moved after it was spawned' % ghost)
        self.assertGreater(st.robot_state(ghost, self.timeout).ticks, 0)
        kill = rospy.ServiceProxy('/kill', Kill)
        self.assertEqual(kill(robot_id=ghost).code, 0)


if __name__ == '__main__':
    rospy.init_node('dynamic_swarm_test')
    rostest.rosrun('swarm_transport', 'dynamic_swarm', DynamicSwarm, sys.argv)
