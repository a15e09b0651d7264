#!/usr/bin/env python3
"""rviz with a shipped config under Xvfb at 1280x960: its 3D view fills most of the window and
shows the particles, not tiny in a corner (issue 20), and, with ~robot_pixels, the robot's links
drawn by rviz's RobotModel display among them (issue 44).

Run by rviz_view.test, which starts the node on the default scene, paused, and by
rviz_excavator.test (the excavator demo, running slowly). This test starts its
own X server (Xvfb picks a free display) and rviz, polls screenshots until rviz has drawn the
particles or the time limit passes, checks the last one and saves it (~screenshot). An rviz that
dies while it sets up (Ogre under Mesa's software renderer, now and then: seen in one fresh-clone
CI run on 2026-11-27) is started again, twice at most, within the same limit. Xvfb and rviz are
stopped whatever happens: in `finally`, on SIGTERM from rostest, and by the kernel if this process
dies first (PR_SET_PDEATHSIG)."""

import ctypes
import os
import select
import signal
import subprocess
import sys
import time
import unittest

import numpy
import rospy
import rostest
from PIL import ImageGrab

WIDTH, HEIGHT = 1280, 960
BACKGROUND = (48, 48, 48)  # the config's Background Color
# The Particles display colours speed from Min Color (0 m/s) to Max Color (1.5 m/s); at rest all
# particles take Min Color.
PARTICLE_MIN, PARTICLE_MAX = (70, 110, 230), (230, 40, 20)
DRAW_TIMEOUT = 35.0  # s for rviz to start and draw; the .test file's limit is 50 s
# At t = 0 the 10 cm x 20 cm column covers about 170 x 340 px at the config's 1700 px/m, of
# which the 5 px points fill about a third: 20,000 px. A quarter of that proves they are drawn
# (~particle_pixels; ~particle_height: the least share of the view's height they span).
MIN_PARTICLE_PIXELS = 5000
MIN_PARTICLE_HEIGHT = 0.15


def die_with_parent():
    """In the child before exec: killed when this test process dies, even by SIGKILL."""
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def start(args, env=None, pass_fds=()):
    return subprocess.Popen(args, env=env, pass_fds=pass_fds, start_new_session=True,
                            preexec_fn=die_with_parent, stdout=subprocess.DEVNULL,
                            stderr=subprocess.STDOUT)


def stop(process):
    """SIGTERM to the process's group, SIGKILL after 3 s."""
    if process is None or process.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, 3), (signal.SIGKILL, 3)):
        try:
            os.killpg(process.pid, sig)
        except ProcessLookupError:
            return
        try:
            process.wait(wait)
            return
        except subprocess.TimeoutExpired:
            pass


def start_xvfb():
    """Xvfb on a display it chooses (-displayfd): no clash with another X server or test."""
    read_end, write_end = os.pipe()
    xvfb = start(["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                  "%dx%dx24" % (WIDTH, HEIGHT), "-nolisten", "tcp"], pass_fds=(write_end,))
    os.close(write_end)
    # Read up to the newline: Xvfb writes the number, then "\n", and dies if the pipe is closed
    # in between.
    text, deadline = b"", time.monotonic() + 10
    while not text.endswith(b"\n") and time.monotonic() < deadline:
        ready, _, _ = select.select([read_end], [], [], max(0.0, deadline - time.monotonic()))
        chunk = os.read(read_end, 16) if ready else b""
        if not chunk:
            break
        text += chunk
    os.close(read_end)
    number = text.decode().strip() if text.endswith(b"\n") else ""
    if not number:
        stop(xvfb)
        raise RuntimeError("Xvfb did not start within 10 s (is the xvfb package installed?)")
    return xvfb, ":" + number


class View:
    """What a screenshot shows: the 3D view (the box of the background colour) and, in it, the
    pixels not of the background and those of the particles' colours."""

    def __init__(self, image, robot_color=None):
        self.image = image.convert("RGB")
        rgb = numpy.asarray(self.image).astype(numpy.int32)
        # The view's rows and columns are mostly background; a panel's or the toolbar's are not
        # (a few of their dark pixels may be of that colour).
        background = (rgb == BACKGROUND).all(axis=2)
        rows = numpy.nonzero(background.mean(axis=1) > 0.3)[0]
        cols = numpy.nonzero(background.mean(axis=0) > 0.3)[0]
        self.box = ((int(cols.min()), int(rows.min()), int(cols.max()) + 1, int(rows.max()) + 1)
                    if len(rows) and len(cols) else (0, 0, 0, 0))
        self.area = int((self.box[2] - self.box[0]) * (self.box[3] - self.box[1]))
        view = rgb[self.box[1]:self.box[3], self.box[0]:self.box[2]]
        self.drawn = int((numpy.abs(view - BACKGROUND).max(axis=2) > 6).sum())
        # Within 30 of the segment from PARTICLE_MIN to PARTICLE_MAX (rviz interpolates in RGB).
        low, high = numpy.array(PARTICLE_MIN), numpy.array(PARTICLE_MAX)
        t = numpy.clip(((view - low) @ (high - low)) / float((high - low) @ (high - low)), 0, 1)
        nearest = low + t[..., None] * (high - low)
        on_scale = numpy.abs(view - nearest).max(axis=2) <= 30
        self.particles = int(on_scale.sum())
        rows = numpy.nonzero(on_scale.sum(axis=1) >= 3)[0]  # not a stray blended pixel
        self.particle_height = int(rows.max() - rows.min()) if len(rows) else 0
        self.robot = 0
        if robot_color is not None:
            # Within 25 of the robot's colour scaled by rviz's shading (from dark to that colour).
            c = numpy.array(robot_color)
            t = numpy.clip((view @ c) / float(c @ c), 0.5, 1.2)
            self.robot = int((numpy.abs(view - t[..., None] * c).max(axis=2) <= 25).sum())


class RvizView(unittest.TestCase):
    def test_view_shows_the_particles(self):
        config = rospy.get_param("~config")
        screenshot = rospy.get_param("~screenshot")
        min_particles = rospy.get_param("~particle_pixels", MIN_PARTICLE_PIXELS)
        min_height = rospy.get_param("~particle_height", MIN_PARTICLE_HEIGHT)
        # The robot's links: pixels of ~robot_color (its URDF colour as the config's RobotModel
        # alpha blends it over the background), at least ~robot_pixels of them (0: no robot).
        min_robot = rospy.get_param("~robot_pixels", 0)
        robot_color = rospy.get_param("~robot_color", None) if min_robot else None

        def complete(v):
            return v.particles >= min_particles and v.robot >= min_robot
        xvfb = rviz = None
        try:
            xvfb, display = start_xvfb()
            env = dict(os.environ, DISPLAY=display)
            # rviz finds its Ogre media through rospack; Debian's ROS packages are in /usr/share,
            # which the devel space's package path leaves out.
            path = env.get("ROS_PACKAGE_PATH", "")
            if "/usr/share" not in path.split(":"):
                env["ROS_PACKAGE_PATH"] = (path + ":" if path else "") + "/usr/share"
            rviz = start(["rviz", "-d", config], env=env)
            started = time.monotonic()
            view = None
            crashes = []
            while time.monotonic() - started < DRAW_TIMEOUT:
                if rviz.poll() is not None:
                    # rviz's Ogre under Mesa's software renderer sometimes dies while it sets
                    # up (SIGSEGV, status -11; ros-visualization/rviz#1680): a fault of the
                    # virtual display, not of the config under test. Start it again, twice
                    # at most, within the same time limit.
                    crashes.append(rviz.poll())
                    self.assertLess(len(crashes), 3, "rviz exited with status %s" % crashes)
                    rospy.logwarn("rviz exited with status %s; starting it again", crashes[-1])
                    rviz = start(["rviz", "-d", config], env=env)
                    continue
                view = View(ImageGrab.grab(xdisplay=display), robot_color)
                if complete(view):
                    break
                time.sleep(0.5)
            waited = time.monotonic() - started
            self.assertIsNotNone(view, "no screenshot taken")
            view.image.save(screenshot)
            rospy.loginfo("rviz drew after %.1f s: %d particle pixels, %d robot pixels; "
                          "screenshot %s", waited, view.particles, view.robot, screenshot)
            screen = WIDTH * HEIGHT
            self.assertGreater(view.area, 0.7 * screen,
                               "the 3D view %s covers %.0f%% of the window, not most of it"
                               % (view.box, 100.0 * view.area / screen))
            self.assertGreaterEqual(
                view.particles, min_particles,
                "after %.0f s the 3D view shows %d pixels of particle colours (%d drawn of %d; "
                "does the paused node latch ~particles?); screenshot %s"
                % (waited, view.particles, view.drawn, view.area, screenshot))
            self.assertGreater(view.drawn, 0.02 * view.area)
            # Not tiny in a corner: the 20 cm column stands 340 px tall at 1700 px/m.
            self.assertGreater(view.particle_height, min_height * (view.box[3] - view.box[1]),
                               "the particles span %d px of the view's height"
                               % view.particle_height)
            self.assertGreaterEqual(
                view.robot, min_robot,
                "after %.0f s the 3D view shows %d pixels of the robot's colour %s (does "
                "robot_state_publisher's tf reach rviz?); screenshot %s"
                % (waited, view.robot, robot_color, screenshot))
        finally:
            stop(rviz)
            stop(xvfb)


if __name__ == "__main__":
    rospy.init_node("rviz_view", anonymous=True)
    # rostest ends its test nodes with SIGTERM at its time limit: run the `finally` above.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))
    rostest.rosrun("mpm_sdem", "rviz_view", RvizView)
