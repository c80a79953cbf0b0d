#!/usr/bin/env python3
"""Virtual leaders (SPEC 9.2) in a launched run: robot 0 leads a leader-only mission with
leader_virtual_copies 3; the other robots' rounds carry its position with its 2 copies while it
leads (one position, Robot_Position.copies), never before, and not after it arrived; the
simulator's /flock/world_poses shows the same. ~lockstep false: in real time, where the
simulator takes the copies from the leader's /flock/position instead of its answers."""

import sys
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import Neighbors, Robot_Positions
from swarm_transport.srv import Submit_Mission

import swarm_testing as st

MISSION = 71


class VirtualCopies(unittest.TestCase):

    def test_the_robots_hear_the_copies_their_leader_announces_while_it_leads(self):
        g = rospy.get_param
        robots, copies, timeout = g('~robots'), g('~copies'), g('~timeout_s')
        lock = threading.Lock()
        heard = []  # (tick, hearer, copies of robot 0 in its round; None: not heard)
        poses = {}  # tick -> copies of robot 0 in /flock/world_poses
        typed = []  # positions of robot 0 of another type than physical

        def on_round(hearer):
            def cb(msg):
                got = [r.copies for r in list(msg.robots) + list(msg.relayed) +
                       list(msg.mission_peers) if r.robot_id == 0 and r.type == 0]
                loose = [r for r in msg.robots if r.robot_id == 0 and r.type != 0]
                with lock:
                    heard.append((msg.tick, hearer, got[0] if got else None))
                    typed.extend(loose)
            return cb

        def on_poses(msg):
            with lock:
                poses[msg.tick] = next((r.copies for r in msg.robots if r.robot_id == 0), None)

        status = st.StatusLog()
        subs = [rospy.Subscriber('/robot_%d/neighbors' % k, Neighbors, on_round(k),
                                 queue_size=1000) for k in range(1, robots)]
        subs.append(rospy.Subscriber('/flock/world_poses', Robot_Positions, on_poses,
                                     queue_size=1000))
        log = st.PositionLog()
        swarm = st.launch_swarm(robots=robots, seed=g('~seed'), lockstep=g('~lockstep', True),
                                max_ticks=0,
                                placement='corner', extra_config=g('~extra_config'))
        try:
            self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
            submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
            submit.wait_for_service(timeout)
            target = (g('~target_x'), g('~target_y'))
            submitted = log.latest_tick()
            answer = submit(st.mission(MISSION, 0, 1, 1, target + (0.0, 0.0), target))
            self.assertEqual(answer.code, 0, answer.message)
            self.assertTrue(st.wait_for(lambda: status.final(MISSION), timeout),
                            'the leader-only mission did not end: %s' % status.states(MISSION))
            done = status.first(MISSION, 5)
            self.assertIsNotNone(done, 'mission ended %s' % status.states(MISSION))
            end = log.latest_tick() + g('~after_ticks')
            self.assertTrue(log.wait_tick(end + 1, timeout))
            # Proof of delivery for "no copies after": a round after DONE in which a robot hears
            # robot 0 (the others may be out of its range for a while after it arrived: seen
            # once beside two busy loops, the rounds of the 10 ticks after DONE had none).
            self.assertTrue(st.wait_for(
                lambda: any(t >= end and c == 0 for t, _, c in heard), timeout),
                'no robot heard robot 0 within %.0f s after tick %d' % (timeout, end))
        finally:
            swarm.shutdown()
            for s in subs:
                s.unregister()
            log.close()
        with lock:
            rounds = list(heard)
            world = dict(poses)
        # The simulator's world: robot 0's position carries its copies over one stretch of
        # ticks after the order, none before and after.
        self.assertEqual(set(world.values()) - {None}, {0, copies}, 'counts in /flock/world_poses')
        led = sorted(t for t, c in world.items() if c == copies)
        self.assertGreater(led[0], submitted, 'copies before the mission')
        self.assertEqual(led, list(range(led[0], led[-1] + 1)), 'copies came and went')
        self.assertTrue(any(t > led[-1] and c == 0 for t, c in world.items()),
                        'no tick without copies after the leader arrived')
        # Every robot that heard robot 0 heard exactly that: its copies while it led, none else;
        # one position for the robot and its copies (no type 1 position on the wire).
        wrong = [r for r in rounds if r[2] is not None and
                 r[2] != (copies if led[0] <= r[0] <= led[-1] else 0)]
        self.assertEqual(wrong, [], '(tick, hearer, copies) against ticks %d-%d' % (led[0], led[-1]))
        self.assertEqual(typed, [], 'copies sent as positions of their own')
        self.assertTrue(any(c == copies for _, _, c in rounds),
                        'no robot heard robot 0 while it led: %s' % rounds[-5:])
        self.assertTrue(any(c == 0 and t > led[-1] for t, _, c in rounds),
                        'no robot heard robot 0 after it arrived')

if __name__ == '__main__':
    rospy.init_node('virtual_copies_test')
    rostest.rosrun('swarm_transport', 'virtual_copies', VirtualCopies, sys.argv)
