#!/usr/bin/python3
"""A closed-loop controller through the simulated sand, the template for your own nodes.

It holds the horizontal force of the sand on a blade at a set point: the blade moves forward
at a set speed, and its depth follows a PI law on the force error, through the blade's cmd_vel
(geometry_msgs/Twist in the blade's own axes, which the node applies between steps). It reads
the blade's load from the node's ~obstacles/<blade>/wrench (geometry_msgs/WrenchStamped, N per
metre of width, in the blade's axes). Too little force: go deeper; too much: rise.

Everything runs on the simulated clock (/use_sim_time), so the loop behaves the same at any
real-time factor. Copy this file, change what is read and what is commanded.

Parameters (SI):
  ~node "mpm_sdem": the simulation node's name; ~blade "blade": the kinematic block;
  ~force 100.0 N/m: the set point (the sand's force against the blade's forward motion);
  ~speed 0.05 m/s: forward; ~max_depth_rate 0.03 m/s: the most it rises or sinks;
  ~kp 1.2e-3 (m/s)/(N/m) and ~ki 1.0e-3 (m/s)/(N s/m): the PI gains on the force error;
  ~filter 0.1 s: the time constant of the low-pass on the measured force (a step's contact load
  is noisy: each material point's spring is a share of it); ~rate 50 Hz of simulated time.
  Ranges: force (0, 1e5], speed [0, 10], max_depth_rate (0, 10], kp and ki [0, 1], filter
  (0, 100], rate (0, 1000]; anything else stops the node at its start, naming the parameter.
Publishes ~force (std_msgs/Float64, the filtered force) for plots: rostopic echo -p /blade_force_controller/force > force.csv (docs/node.md, Plotting a run).
"""
import math
import sys

import rospy
from geometry_msgs.msg import Twist, WrenchStamped
from std_msgs.msg import Float64


def number(name, default, low, high, low_open=False):
    """~name, a finite number in [low, high] ((low, high] when low_open), or the node exits
    before it commands anything, naming the parameter, its value and the range."""
    value = rospy.get_param(name, default)
    number_like = isinstance(value, (int, float)) and not isinstance(value, bool)
    if not (number_like and math.isfinite(value) and (value > low if low_open else value >= low)
            and value <= high):
        rospy.logfatal("%s = %r: must be a number in %s%g, %g] (%s's parameters are listed at "
                       "the top of the file)", name, value, "(" if low_open else "[", low, high,
                       rospy.get_name())
        sys.exit(1)
    return float(value)


class BladeForceController:
    def __init__(self):
        node = rospy.get_param("~node", "mpm_sdem")
        blade = rospy.get_param("~blade", "blade")
        self.set_point = number("~force", 100.0, 0, 1e5, low_open=True)
        self.speed = number("~speed", 0.05, 0, 10)
        self.max_rate = number("~max_depth_rate", 0.03, 0, 10, low_open=True)
        self.kp = number("~kp", 1.2e-3, 0, 1)
        self.ki = number("~ki", 1.0e-3, 0, 1)
        self.tau = number("~filter", 0.1, 0, 100, low_open=True)
        self.force = None  # filtered, N/m
        self.stamp = None
        self.integral = 0.0  # of the error, N s/m
        topic = "/%s/obstacles/%s/" % (node, blade)
        self.cmd = rospy.Publisher(topic + "cmd_vel", Twist, queue_size=1)
        self.filtered = rospy.Publisher("~force", Float64, queue_size=1)
        rospy.Subscriber(topic + "wrench", WrenchStamped, self.on_wrench, queue_size=10)

    def on_wrench(self, msg):
        """Low-pass the force against the forward motion (-x in the blade's axes)."""
        measured = -msg.wrench.force.x
        t = msg.header.stamp.to_sec()
        if self.force is None or t < self.stamp:  # the first, or the clock went back (reset)
            self.force = measured
        elif t == self.stamp:  # a repeat of the same step's load: nothing new
            return
        else:
            a = 1.0 - math.exp(-(t - self.stamp) / self.tau)
            self.force += a * (measured - self.force)
        self.stamp = t

    def command(self, dt):
        """The blade's velocity from the force error: down (negative y) when it is too small."""
        twist = Twist()
        twist.linear.x = self.speed
        if self.force is not None:
            error = self.set_point - self.force
            down = self.kp * error + self.ki * self.integral
            if abs(down) < self.max_rate:  # integrate only when not saturated (no wind-up)
                self.integral += error * dt
            twist.linear.y = -max(-self.max_rate, min(self.max_rate, down))
            self.filtered.publish(Float64(self.force))
        self.cmd.publish(twist)


def main():
    rospy.init_node("blade_force_controller")
    controller = BladeForceController()
    rate_hz = number("~rate", 50.0, 0, 1000, low_open=True)
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        controller.command(1.0 / rate_hz)
        try:
            rate.sleep()
        except rospy.ROSTimeMovedBackwardsException:  # the node's ~reset: start again
            controller.integral, controller.force = 0.0, None
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
