#!/usr/bin/python3
"""One dig of the planar excavator (urdf/excavator.urdf): sensor_msgs/JointState on joint_states
for robot_state_publisher, whose tf the node's ~robot_links follow.

The dig is a path of the bucket's hinge (the wrist) and the bucket's angle in the plane, in
simulated time: wait above the sand, push the teeth about 7 cm into the bed, drag the bucket
towards the cab, curl it and lift it. Between waypoints the wrist moves along a straight line
with a smooth start and stop; the boom and stick angles follow from the two-link inverse
kinematics (elbow up), the bucket's from its angle less theirs.

Parameters (SI; defaults are the URDF's):
  ~pivot [0.1, 0.3] m: the boom's joint in the plane; ~boom 0.5 m, ~stick 0.35 m: lengths;
  ~rate 50 Hz of simulated time; ~waypoints: [[t s, wrist x m, wrist y m, bucket angle deg],
  ...], times increasing;
  ~wait_for_blocks [] (the launch file: its robot_links): the path holds its first waypoint
  until the node's ~blocks (~blocks_topic, /mpm_sdem/blocks) lists every one of these blocks,
  and its time zero is then that message's stamp. The links spawn only when this node's joint
  states, through robot_state_publisher's tf, reach the node: a few tenths of a second of wall
  time after launch, more on a loaded machine. A path on the clock alone could have the bucket
  appear already in the sand;
  ~start 0 s: the path's time zero, after that stamp (simulated time).
"""
import math

import rospy
from mpm_sdem.msg import BlockStates
from sensor_msgs.msg import JointState

# t (s), wrist x, y (m), bucket angle (deg, from +x, counter-clockwise): the bucket's teeth are
# 0.15 m from the wrist along its angle; the bed's surface is at y = 0.15 m.
DIG = [
    [0.0, 0.80, 0.36, -90],   # above the sand, teeth 6 cm clear
    [0.6, 0.80, 0.36, -90],
    [1.6, 0.80, 0.23, -100],  # in: teeth at y = 0.082, 6.8 cm deep
    [3.2, 0.52, 0.23, -70],   # drag towards the cab, teeth about 6 cm deep
    [4.0, 0.48, 0.25, 10],    # curl
    [4.8, 0.48, 0.42, 20],    # lift
]


def inverse_kinematics(pivot, boom, stick, wrist, bucket_angle):
    """Joint angles (rad) that put the wrist at `wrist` with the bucket at `bucket_angle`."""
    x, y = wrist[0] - pivot[0], wrist[1] - pivot[1]
    d2 = x * x + y * y
    cos_elbow = (d2 - boom * boom - stick * stick) / (2 * boom * stick)
    if abs(cos_elbow) > 1:
        raise ValueError("wrist (%.3f, %.3f) is out of the arm's reach" % tuple(wrist))
    elbow = -math.acos(cos_elbow)  # negative: the stick folds down, the elbow stays up
    shoulder = math.atan2(y, x) - math.atan2(stick * math.sin(elbow),
                                             boom + stick * math.cos(elbow))
    return shoulder, elbow, bucket_angle - shoulder - elbow


def wrist_at(waypoints, t):
    """The wrist's position and the bucket's angle (deg) at time t along the waypoints."""
    if t <= waypoints[0][0]:
        return waypoints[0][1:3], waypoints[0][3]
    for a, b in zip(waypoints, waypoints[1:]):
        if t <= b[0]:
            s = (t - a[0]) / (b[0] - a[0])
            s = s * s * (3 - 2 * s)  # smooth start and stop
            return [a[i] + s * (b[i] - a[i]) for i in (1, 2)], a[3] + s * (b[3] - a[3])
    return waypoints[-1][1:3], waypoints[-1][3]


def main():
    rospy.init_node("excavator_dig")
    pivot = rospy.get_param("~pivot", [0.1, 0.3])
    boom = rospy.get_param("~boom", 0.5)
    stick = rospy.get_param("~stick", 0.35)
    rate_hz = rospy.get_param("~rate", 50.0)
    start = rospy.get_param("~start", 0.0)
    wait_for = rospy.get_param("~wait_for_blocks", [])
    blocks_topic = rospy.get_param("~blocks_topic", "/mpm_sdem/blocks")
    waypoints = rospy.get_param("~waypoints", DIG)
    if not isinstance(waypoints, list) or len(waypoints) < 1 or not all(
            isinstance(w, list) and len(w) == 4 and
            all(isinstance(x, (int, float)) for x in w) for w in waypoints):
        rospy.logfatal("~waypoints: a list of [t s, wrist x m, wrist y m, bucket angle deg], "
                       "got %r", waypoints)
        return 1
    for (a, b) in zip(waypoints, waypoints[1:]):
        if not b[0] > a[0]:
            rospy.logfatal("~waypoints: times must increase (%g then %g)", a[0], b[0])
            return 1
    # Every waypoint's straight segment inside the reach, checked before moving.
    for w in waypoints:
        try:
            inverse_kinematics(pivot, boom, stick, w[1:3], math.radians(w[3]))
        except ValueError as e:
            rospy.logfatal("~waypoints at t = %g s: %s", w[0], e)
            return 1
    if not isinstance(wait_for, list) or not all(isinstance(b, str) for b in wait_for):
        rospy.logfatal("~wait_for_blocks: a list of block names, got %r", wait_for)
        return 1
    # The path's time zero (simulated s): when the node first lists every block waited for.
    origin = [None if wait_for else 0.0]

    def on_blocks(m):
        # A message stamped well after the clock as this node last heard it (a little behind the
        # node's) is from before a ~reset.
        if origin[0] is None and m.header.stamp.to_sec() <= rospy.get_time() + 0.1 and \
                set(wait_for) <= {b.name for b in m.blocks}:
            origin[0] = m.header.stamp.to_sec()
            rospy.loginfo("blocks %s in the simulation at t = %.3f s; the dig starts",
                          ", ".join(wait_for), origin[0])

    if wait_for:
        rospy.Subscriber(blocks_topic, BlockStates, on_blocks, queue_size=10)
    pub = rospy.Publisher("joint_states", JointState, queue_size=10)
    msg = JointState(name=["boom_joint", "stick_joint", "bucket_joint"])
    rate = rospy.Rate(rate_hz)
    last = None
    waiting = None  # when the wait for the blocks began (simulated time)
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        if now != last and not now.is_zero():  # one message per tick of the simulated clock
            if origin[0] is None:
                t = waypoints[0][0]  # hold the first waypoint: tf from it spawns the links
                waiting = now if waiting is None else waiting
                if (now - waiting).to_sec() > 2:  # seconds of simulated time: something is wrong
                    rospy.logwarn_throttle(10, "still waiting for blocks %s on %s, t = %.1f s" %
                                           (", ".join(wait_for), blocks_topic, now.to_sec()))
            else:
                t = now.to_sec() - origin[0] - start
            wrist, angle = wrist_at(waypoints, t)
            msg.header.stamp = now
            msg.position = list(inverse_kinematics(pivot, boom, stick, wrist, math.radians(angle)))
            pub.publish(msg)
            last = now
        try:
            rate.sleep()
        except rospy.ROSTimeMovedBackwardsException:  # the node's ~reset: start again
            last = None
            waiting = None
            if wait_for:
                origin[0] = None  # the links spawn anew
        except rospy.ROSInterruptException:  # shut down
            break
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
