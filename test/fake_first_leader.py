#!/usr/bin/env python3
"""A stand-in for a first leader in TRANSPORT whose answers to a restarted dispatcher's resend
requests were lost (restart_test.py, `test_a_restarted_dispatcher_asks_again`). Run it as
/robot_<id>/robot (`__ns:=/robot_<id> __name:=robot`), the name a robot's reports must come from.

It answers no request heard before the dispatcher's ~status service answers (that is, before
its rebuild wait has ended: those answers are "lost"), then reports its mission's progress twice
a second, as a first leader does. It answers the first request heard after its first progress
report with the mission's status and order (Mission_Resent), then enters UNLOADING, and enters
DONE when the dispatcher sends UNLOADED. Usage: fake_first_leader.py ROBOT_ID MISSION_ID."""

import sys
import threading

import rospy
from std_srvs.srv import Trigger
from swarm_transport.msg import (Mission_Event, Mission_Resend_Request, Mission_Resent,
                                 Mission_Status, New_Mission)

TRANSPORT, UNLOADING, DONE = 3, 4, 5


def main():
    argv = rospy.myargv(sys.argv)
    robot, mission_id = int(argv[1]), int(argv[2])
    rospy.init_node('robot')
    lock = threading.Lock()
    state = {'phase': TRANSPORT, 'reporting': False, 'answered': False}

    order = New_Mission()
    order.robot_index_from, order.robot_index_to = robot, robot + 1
    order.leader_number = 1
    order.mission_id = mission_id
    order.object_position_x, order.object_position_y = 7.0, 7.0
    order.object_size_x, order.object_size_y = 1.0, 1.0
    order.target_x, order.target_y = 3.0, 3.0

    def status(phase):
        s = Mission_Status()
        s.mission_id, s.state, s.stamp = mission_id, phase, rospy.Time.now()
        s.robots_assigned, s.robots_inside = 1, 1
        s.object_position_x, s.object_position_y = 5.0, 5.0
        s.distance_to_target = 2.83
        return s

    status_pub = rospy.Publisher('/flock/mission/status', Mission_Status, queue_size=10)
    progress_pub = rospy.Publisher('/flock/mission/progress', Mission_Status, queue_size=10)
    resent_pub = rospy.Publisher('/flock/mission/resent', Mission_Resent, queue_size=10)

    def on_request(request):
        with lock:
            if not state['reporting']:
                rospy.loginfo('fake first leader: request %d of %s not answered (lost)',
                              request.request, request.requester)
                return
            if state['answered']:
                return
            state['answered'] = True
        answer = Mission_Resent(status=status(TRANSPORT), has_order=True, order=order,
                                requester=request.requester, request=request.request)
        resent_pub.publish(answer)
        rospy.loginfo('fake first leader: answered request %d', request.request)
        rospy.sleep(0.5)
        with lock:
            state['phase'] = UNLOADING
        status_pub.publish(status(UNLOADING))

    def on_event(event):
        if event.mission_id != mission_id or event.event != Mission_Event.UNLOADED:
            return
        with lock:
            if state['phase'] != UNLOADING:
                return
            state['phase'] = DONE
        status_pub.publish(status(DONE))

    requests = rospy.Subscriber('/flock/mission/resend_request', Mission_Resend_Request,
                                on_request)
    rospy.Subscriber('/flock/mission/event', Mission_Event, on_event)
    rospy.wait_for_service('/mission_dispatcher/status')
    # Served only once the dispatcher spins, that is after its rebuild wait.
    rospy.ServiceProxy('/mission_dispatcher/status', Trigger)()
    # The request topic is latched: a connection made late would deliver the rebuild's last
    # request now. Connected, and a moment for that delivery, every rebuild request is lost.
    while requests.get_num_connections() < 1 and not rospy.is_shutdown():
        rospy.sleep(0.05)
    rospy.sleep(0.5)
    with lock:
        state['reporting'] = True
    rate = rospy.Rate(2)
    while not rospy.is_shutdown():
        with lock:
            phase = state['phase']
        if phase != DONE:
            progress_pub.publish(status(phase))
        rate.sleep()


if __name__ == '__main__':
    main()
