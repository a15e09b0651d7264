#!/usr/bin/python3
"""Obstacles at scale in the node (issue 39): the default scene in mpm_sdem_node (one thread, as
fast as it goes) with 0, 10, 100 and 1,000 static disks of 2 mm radius spawned through
~spawn_obstacle in a 6 mm lattice in the scene's empty upper right (bench/obstacles.cpp's).

For each count: ~reset, the disks spawned while paused (spawn calls per second over the last
tenth of them), then ~resume and the real-time factor from simulated t = 0.1 s to 0.5 s (wall
time between the ~stats messages that pass those times), then ~pause. Medians of --repeats,
after one run without disks that is not counted.
Starts its own master and node; needs a build (BUILD_DIR, default build/).

usage: bench/node_obstacles.py [--counts 0,10,100,1000] [--repeats 3]
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

import rospy
from mpm_sdem.msg import SimStats
from mpm_sdem.srv import SpawnObstacle, SpawnObstacleRequest
from std_srvs.srv import Trigger

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("BUILD_DIR", os.path.join(ROOT, "build"))
NODE = os.path.join(BUILD, "devel/lib/mpm_sdem/mpm_sdem_node")
NS = "/mpm_sdem/"


def disk(k):
    r = SpawnObstacleRequest()
    r.name = "disk%d" % k
    r.disk_radius = 0.002
    r.pose.x = 0.36 + 0.006 * (k % 39)
    r.pose.y = 0.07 + 0.006 * (k // 39)
    r.body_type = 0  # static
    r.density = 500
    r.friction = 0.5
    r.restitution = 0.5
    return r


class Stats:
    def __init__(self):
        self.samples = []  # (wall time, sim time)
        rospy.Subscriber(NS + "stats", SimStats, self.add, queue_size=100)

    def add(self, msg):
        self.samples.append((time.monotonic(), msg.sim_time, msg.paused))

    def wait(self, cond, timeout=120):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if self.samples and cond(self.samples[-1]):
                return self.samples[-1]
            time.sleep(0.01)
        raise RuntimeError("timed out waiting on ~stats")


def measure(count, stats, spawn, trigger):
    trigger["reset"]()
    stats.wait(lambda s: s[1] == 0 and s[2])
    timed = max(1, count // 10)
    start = time.monotonic()
    for k in range(count):
        if k == count - timed:
            start = time.monotonic()
        res = spawn(disk(k))
        if not res.success:
            raise RuntimeError(res.message)
    rate = timed / (time.monotonic() - start) if count else float("nan")
    stats.samples.clear()
    trigger["resume"]()
    a = stats.wait(lambda s: s[1] >= 0.1)
    b = stats.wait(lambda s: s[1] >= 0.5)
    trigger["pause"]()
    return rate, (b[1] - a[1]) / (b[0] - a[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--counts", default="0,10,100,1000")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    env = dict(os.environ, ROS_HOSTNAME="127.0.0.1",
               ROS_MASTER_URI="http://127.0.0.1:%d" % (20000 + os.getpid() % 20000))
    os.environ.update(env)
    port = env["ROS_MASTER_URI"].rsplit(":", 1)[1]
    core = subprocess.Popen(["roscore", "-p", port], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    node = None
    try:
        time.sleep(3)
        scene = os.path.join(ROOT, "config/scenes/debris_impact.yaml")
        node = subprocess.Popen([NODE, "__name:=mpm_sdem", "_scene:=" + scene, "_threads:=1",
                                 "_start_paused:=true", "_end_action:=continue"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rospy.init_node("bench_node_obstacles", anonymous=True)
        stats = Stats()
        rospy.wait_for_service(NS + "spawn_obstacle", timeout=30)
        spawn = rospy.ServiceProxy(NS + "spawn_obstacle", SpawnObstacle, persistent=True)
        trigger = {n: rospy.ServiceProxy(NS + n, Trigger) for n in ("reset", "resume", "pause")}
        measure(0, stats, spawn, trigger)  # warm-up, not counted
        print("%8s %12s %10s" % ("disks", "spawns/s", "x real"))
        for count in [int(c) for c in args.counts.split(",")]:
            rates, factors = [], []
            for _ in range(args.repeats):
                rate, factor = measure(count, stats, spawn, trigger)
                rates.append(rate)
                factors.append(factor)
            print("%8d %12.0f %10.3f" % (count, statistics.median(rates),
                                        statistics.median(factors)), flush=True)
    finally:
        if node:
            node.terminate()
            node.wait()
        core.terminate()
        core.wait()


if __name__ == "__main__":
    sys.exit(main())
