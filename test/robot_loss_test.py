#!/usr/bin/env python3
"""Robots lost during a mission (issue 11, SPEC 9.7), their processes killed (SIGKILL):
- a passive robot in GATHERING (lock-step and real time): its radio falls silent, the group
  loses it after lost_after_s, the first leader names it at once on /flock/mission/progress
  (within the bound of the .test) and the group gathers, loads and carries without it (LOADING
  names it);
- the first leader in TRANSPORT (lock-step and real time): the next assigned robot is promoted,
  says so in a TRANSPORT status naming the lost robot, and the mission ends DONE;
- both leaders in TRANSPORT (lock-step and real time): the next two assigned robots are
  promoted, the mission ends DONE;
- a mission ordered after its first leader's process died: the next robot leads it to DONE;
- a leader of a two-robot mission with two leaders: fewer robots than leaders are left, the
  mission ends ABORTED with the reason, and the other robot drops it."""

import os
import signal
import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import New_Mission
from swarm_transport.srv import Hold, Submit_Mission

import swarm_testing as st


def g(key):
    return rospy.get_param('~' + key)


class RobotLoss(unittest.TestCase):

    def kill_in_phase(self, mission_id, phase, robots, group=None, leaders=1, lockstep=True):
        """Launches the swarm, submits a transport mission of robots [0, group) led by its first
        `leaders` before tick 0, and kills the processes of `robots` once the mission reported
        `phase`. Returns (status log, position log, the tick of the kill); the swarm is shut down
        at cleanup."""
        timeout = g('timeout_s')
        status = st.StatusLog()
        self.progress = st.StatusLog('/flock/mission/progress')
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        # Lock-step: the run holds from tick 1 on and the test moves it on a tick at a time
        # until the first leader is in `phase`; the kills fall while it holds, so the kill tick
        # is exact (the last tick simulated), whatever the test's position log lags behind.
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=lockstep,
                                max_ticks=0, hold_at=1 if lockstep else 0)
        self.addCleanup(swarm.shutdown)
        order = st.mission(mission_id, 0, group or g('group'), leaders, (7.0, 7.0, 2.0, 2.0),
                           (3.0, 3.0))
        if lockstep:
            self.assertEqual(st.submit_before_first_tick(pub, order, timeout), '')
        log = st.PositionLog()
        self.addCleanup(log.close)
        if not lockstep:
            self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
            # The dispatcher admits the raw order (the robots take only what it admitted) and
            # the simulator mirrors it: an order sent before either subscribed is lost (on a
            # busy machine they come up after tick 3). The robots, the simulator, the dispatcher.
            self.assertTrue(st.wait_connected(pub, timeout, at_least=g('robots') + 2))
            self.assertTrue(st.wait_on_radio(range(g('robots')), timeout),
                            'not every robot hears its rounds')
            pub.publish(order)
        # Their pids first, then the kills back to back: a lock-step run notices a dead robot
        # at once (its connections close), so a lookup between two kills let the second robot
        # outlive the first by more than the 5 ticks that make a robot lost.
        pids = [st.node_pid('/robot_%d/robot' % robot) for robot in robots]
        if lockstep:
            at = self.hold_in_phase(mission_id, phase, timeout)
            killed_at = at - 1
        else:
            self.assertTrue(
                st.wait_for(lambda: status.first(mission_id, phase) is not None, timeout),
                'no %s; states so far %s' % (st.NAMES[phase], status.states(mission_id)))
        for pid in pids:
            os.kill(pid, signal.SIGKILL)
        if lockstep:
            self.assertEqual(self.hold(0).code, Hold._response_class.OK)
        else:
            killed_at = log.latest_tick()
        self.assertTrue(st.wait_for(lambda: status.final(mission_id), timeout),
                        'mission %d never ended after robot(s) %s died; states %s'
                        % (mission_id, robots, status.states(mission_id)))
        return status, log, killed_at

    def hold_in_phase(self, mission_id, phase, timeout, leader=0):
        """Moves a run held at tick 1 on a tick at a time until robot `leader` (the first
        leader) has mission `mission_id` in `phase` (its ~state: no status in flight to wait
        for); returns the tick it holds before."""
        self.hold = rospy.ServiceProxy('/simulator/hold', Hold)
        self.hold.wait_for_service(timeout)
        at = 1
        for _ in range(400):
            self.assertTrue(st.wait_for(lambda: self.hold(at).holding, timeout),
                            'the run never held at tick %d' % at)
            state = st.robot_state(leader, timeout)
            if dict(zip(state.mission_ids, bytearray(state.mission_phases))).get(mission_id,
                                                                                   0) >= phase:
                return at
            at += 1
            self.assertEqual(self.hold(at).code, Hold._response_class.OK)
        self.fail('mission %d never reached %s by tick %d' % (mission_id, st.NAMES[phase], at))

    def promoted(self, status, mission_id, killed_at, lost, leader, bound):
        """The mission ends DONE; one status names the robot promoted and the robots lost, within
        `bound` ticks of the kill, in TRANSPORT - or, in real time, in LOADING when the promoted
        robot had not heard the TRANSPORT of the first leader killed right after it (seen beside
        two busy loops: the takeover said LOADING at tick 107, TRANSPORT followed at 108)."""
        states = status.states(mission_id)
        self.assertEqual(states[-2:], ['UNLOADING', 'DONE'], states)
        takeovers = [m for m in status.of(mission_id) if ' leads: ' in m.reason]
        self.assertTrue(all(m.state in (2, 3) for m in takeovers),
                        [(m.tick, st.NAMES[m.state], m.reason) for m in takeovers])
        self.assertEqual(len(takeovers), 1, [(m.tick, m.reason) for m in status.of(mission_id)])
        want = 'robot %d leads: robot(s) %s lost' % (leader, ', '.join(str(r) for r in lost))
        self.assertIn(want, takeovers[0].reason)
        self.assertLessEqual(takeovers[0].tick - killed_at, bound,
                             'killed at tick %d, taken over at tick %d'
                             % (killed_at, takeovers[0].tick))

    def dropped(self, mission_id, lockstep, bound):
        """A passive robot killed in GATHERING: named lost on the progress topic within `bound`
        ticks of the kill, the mission DONE without it."""
        lost = g('lost_robot')
        status, _, killed_at = self.kill_in_phase(mission_id, 1, [lost], lockstep=lockstep)
        self.assertEqual(status.states(mission_id), ['QUEUED', 'GATHERING', 'LOADING',
                                                     'TRANSPORT', 'UNLOADING', 'DONE'])
        self.assertIn('without robot(s) %d (lost' % lost, status.first(mission_id, 2).reason)
        want = 'robot(s) %d lost (not heard for' % lost
        notices = [m for m in self.progress.of(mission_id) if want in m.reason]
        self.assertEqual(len(notices), 1, [(m.tick, st.NAMES[m.state], m.reason)
                                           for m in self.progress.of(mission_id)])
        self.assertEqual(st.NAMES[notices[0].state], 'GATHERING', notices[0].reason)
        self.assertIn('the mission goes on without them', notices[0].reason)
        self.assertLessEqual(notices[0].tick - killed_at, bound,
                             'killed at tick %d, named lost at tick %d'
                             % (killed_at, notices[0].tick))

    def test_a_passive_robot_lost_in_gathering_is_dropped(self):
        self.dropped(6, True, g('max_ticks_to_promote'))

    def test_a_passive_robot_lost_in_gathering_is_dropped_realtime(self):
        self.dropped(7, False, g('max_ticks_to_promote_realtime'))

    def test_a_lost_first_leader_is_replaced_lockstep(self):
        status, _, killed_at = self.kill_in_phase(5, 3, [0])
        self.promoted(status, 5, killed_at, [0], 1, g('max_ticks_to_promote'))

    def test_a_lost_first_leader_is_replaced_realtime(self):
        status, _, killed_at = self.kill_in_phase(4, 3, [0], lockstep=False)
        self.promoted(status, 4, killed_at, [0], 1, g('max_ticks_to_promote_realtime'))

    def test_all_lost_leaders_are_replaced(self):
        status, _, killed_at = self.kill_in_phase(3, 3, [0, 1], leaders=2)
        self.promoted(status, 3, killed_at, [0, 1], 2, g('max_ticks_to_promote'))

    def test_all_lost_leaders_are_replaced_realtime(self):
        status, _, killed_at = self.kill_in_phase(8, 3, [0, 1], leaders=2, lockstep=False)
        self.promoted(status, 8, killed_at, [0, 1], 2, g('max_ticks_to_promote_realtime'))

    def test_a_mission_naming_a_dead_first_leader_goes_on_without_it(self):
        """Its first leader's process died before the order: the order is taken (the robot is
        still in the world), the next robot is promoted once the dead one is not heard, and the
        mission ends DONE - it does not wait in QUEUED for good."""
        timeout = g('timeout_s')
        status = st.StatusLog()
        log = st.PositionLog()
        self.addCleanup(log.close)
        swarm = st.launch_swarm(robots=g('robots'), seed=g('seed'), lockstep=True, max_ticks=0)
        self.addCleanup(swarm.shutdown)
        self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
        os.kill(st.node_pid('/robot_0/robot'), signal.SIGKILL)
        killed_at = log.latest_tick()
        self.assertTrue(log.wait_tick(killed_at + 20, timeout), 'the swarm stopped ticking')
        submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
        submit.wait_for_service(timeout)
        answer = submit(st.mission(9, 0, g('group'), 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)))
        self.assertEqual(answer.code, 0, answer.message)
        self.assertTrue(st.wait_for(lambda: status.final(9), timeout),
                        'mission 9 never ended; states %s' % status.states(9))
        states = status.states(9)
        self.assertEqual(states[-1], 'DONE', [(m.state, m.reason) for m in status.of(9)])
        reasons = [m.reason for m in status.of(9) if m.reason]
        self.assertTrue(any('robot 1 leads: robot(s) 0 lost' in r for r in reasons), reasons)

    def test_too_few_robots_left_for_the_leaders_aborts(self):
        status, log, killed_at = self.kill_in_phase(2, 3, [1], group=2, leaders=2)
        end = [m for m in status.of(2) if m.state in (5, 6, 7)][0]
        self.assertEqual(st.NAMES[end.state], 'ABORTED', end.reason)
        self.assertIn('robot(s) 1 lost', end.reason)
        self.assertIn('fewer robots than leaders', end.reason)
        self.assertLessEqual(end.tick - killed_at, g('max_ticks_to_promote'),
                             'killed at tick %d, ABORTED at tick %d' % (killed_at, end.tick))
        # Its other robot dropped the mission (Delete_Object) and goes on ticking, unfrozen.
        self.assertTrue(log.wait_tick(end.tick + 20, g('timeout_s')))
        self.assertTrue(
            st.wait_for(lambda: not st.robot_state(0, g('timeout_s')).mission_ids, g('timeout_s')),
            st.robot_state(0, g('timeout_s')))
        self.assertFalse(st.robot_state(0, g('timeout_s')).frozen)


if __name__ == '__main__':
    rospy.init_node('robot_loss_test')
    rostest.rosrun('swarm_transport', 'robot_loss', RobotLoss, sys.argv)
