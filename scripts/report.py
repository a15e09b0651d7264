#!/usr/bin/python3
"""Writes docs/validation/REPORT.md and its plots from what mpm_sdem_validate measured.

usage: report.py DATA_DIR REPORT_DIR MODE MACHINE
DATA_DIR holds results.csv and the case series; MODE is 'fast' or 'report'.
"""
import csv
import glob
import math
import os
import re
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMES = ["imp", "imp_grid", "multi_velocity", "particle_surface", "partitioned"]

# The cases issues 7 and 15 list, and which of them this report reproduces so far.
CASES = [
    ("collision", "Seed 000 sec. 5.1: collision energy transfer (5.1.1)", True),
    ("drop", "Seed 000 sec. 5.1: drop and bounce energy", True),
    ("forces", "Seed 000 sec. 5.2: normal force at Table 2's grid sizes, friction force", True),
    ("silo", "Seed 000 sec. 5.3: silo discharge against Beverloo", True),
    ("silo_convergence", "Seed 000 sec. 5.3: silo flow rate under refinement per neck (7 to 2.5 mm"
                         " cells), Beverloo exponent over necks of at least 6 cells", True),
    ("silo_granular", "Issue 41: the silo in the mu(I) granular sand (mu_s = sin 35 deg, 2 mm "
                      "grains) over necks of at least 6 cells at 7, 5, 3.5 and 2.5 mm cells: "
                      "rates, Beverloo exponent, C and k with the exponent 1.5", True),
    ("silo_granular_asflip", "Issue 41: the granular silo with ASFLIP (relaxation 0.03 s) at 7, "
                             "5 and 3.5 mm cells", True),
    ("silo_granular_fit", "Issue 79: the granular silo of silo_granular_asflip with "
                          "volume-consistent points", True),
    ("contact_schemes", "Seed 000 sec. 5.4: contact-scheme comparison (1D rod)", True),
    ("debris", "Seed 000 sec. 6 / seed 003: granular flow hitting three wooden blocks", True),
    ("debris_sweep", "Seed 000 sec. 6 / seed 003: resolution sweep of the wooden-block scene (IMP)",
     True),
    ("debris_ensemble", "Seed 000 sec. 6 / seed 003: ensembles of the wooden-block scene at four "
                        "resolutions (IMP; 8 runs each, points perturbed by 1e-4 of a cell; springs"
                        " per point and per length of contact)", True),
    ("debris_seed003", "Seed 000 sec. 6 / seed 003: the wooden-block scene as seed 003 models it"
                       " (the material's base fixed, wood adhesion 30 Pa, 60 Pa with the floor)"
                       " under refinement (IMP)", True),
    ("debris_granular", "Issues 40 and 41: the wooden-block scene in the granular sand with the "
                        "flume's side walls, ASFLIP and subcycled springs, ensembles of 3 from 1 "
                        "cm to 1.67 mm: resting positions, landings, turns and rotation histories "
                        "against seed 003",
     True),
    ("debris_granular_fit", "Issue 79: debris_granular with volume-consistent points "
                            "(solver.volume_fit), the same ensembles", True),
    ("debris_timestep", "Seed 000 sec. 6 / seed 003: the wooden-block scene against the time step"
                        " (kappa_2 of eq. 51) at 5 mm cells", True),
    ("debris_flow", "Seed 000 sec. 6 / seed 003: the flow alone before it meets the blocks (0.2 s)"
                    " under refinement at two kappa_2, and against the step with APIC and with"
                    " FLIP without PIC fraction", True),
    ("rolling", "Rotation under friction: a disk thrown without spin on a floor block, every "
                "coupling and transfer scheme (rigid cylinder: spin-up 2 mu g / R, rolls at 2/3 v0"
                " from v0 / (3 mu g))", True),
    ("clusters", "Seed 003 sec. 2.2: rigid clusters of discs - a rock of 25 discs thrown into a "
                 "granular bed against the spheropolygon of the same outline (depth, velocity "
                 "after, cost), and the incline's disk on an incline made of discs", True),
    ("compression", "Seed 000 sec. 7: granular matrix compression", True),
    ("chute", "Issues 41 and 79: steady uniform chute flow of the mu(I) material (periodic, 4 mm "
              "glass beads 5 cm deep, from rest perturbed by 10 um) against Bagnold's profile, "
              "three angles and three cells, ASFLIP without and with volume-consistent points "
              "and APIC with them: the worst layer, the grid's L2 error and the nodes' largest "
              "over-fill", True),
    ("column_collapse", "Issue 41: granular column collapse on a rough floor (glass beads, "
                        "aspect 0.5 to 8, two cells) against the quasi-2D fits of Lube et al. "
                        "2005", True),
    ("column_sidewalls", "Issue 91: the column of `column_collapse` between the channel's side "
                         "walls (a = 1 and 3, 5 and 2.5 mm, walls 5, 10 and 20 cm apart with the beads' "
                         "wall friction angle of 24.8 deg) against Lajeunesse et al.'s beads",
     True),
    ("blade", "Issue 20: an excavator blade (vertical, kinematic, 5 cm/s) through a layer of sand "
              "against Reece's earth-moving equation with McKyes' N_gamma (smooth blade: exact; "
              "friction 0.3: planar wedge), three depths at three cell sizes", True),
    ("blade_granular", "Issue 41: the blade of `blade` in the granular (mu(I)) sand at the same "
                       "in-plane flowing angle, at the Drucker-Prager stiffness (E 1 MPa) and a "
                       "soft dense state (50 kPa): forces against Reece, exponent in d, steps and "
                       "wall time per simulated second", True),
    ("intrusion", "Issue 44: a 5 cm plate pushed and dragged through the blade's sand at six "
                  "angles, three depths and five speeds against resistive force theory (Li, "
                  "Zhang & Goldman 2013: one scale factor zeta) and dynamic RFT's v^2 term; "
                  "refinement 1 cm to 2.5 mm", True),
    ("intrusion_transfer", "Issue 44: the plate of `intrusion` pushed down with APIC and with "
                           "ASFLIP at 1 cm and 5 mm: its inertial force alone (no gravity; the "
                           "sand and a medium without shear strength) against rho L v^2, the "
                           "v^2 term under gravity, and the slow push and the drag", True),
    ("intrusion_refinement", "Issue 44: the flat plate of `intrusion` pushed down (0.1 m/s) and "
                             "its inertial force alone (no gravity, 1 and 2 m/s), APIC, from 1 cm "
                             "to 1.25 mm: alpha_z, the bearing-capacity slope and intercept, "
                             "lambda_0, their orders and limits", True),
    ("intrusion_drag", "Issue 44: the upright plate of `intrusion` dragged along x at 6 cm "
                       "(0.1 m/s), APIC, from 1 cm to 1.25 mm: alpha_x, its order and limit",
     True),
    ("intrusion_diagnosis", "Issue 90: what the cell does to a tool's force - the upright "
                            "plate's drag at 6 cm and the flat plate's k_z at 1 cm and 5 mm, one "
                            "numerical choice switched at a time against the report's, and the "
                            "drag's line F(z) through 4, 6 and 8 cm", True),
    ("intrusion_frontier", "Issue 78: speed against error for the robot scenes: the drag of "
                           "`intrusion_drag` at 1 cm, 5 mm and 2.5 mm, every point awake, sand at"
                           " rest asleep, and USL; the error from the drag's limit against wall"
                           " time per simulated second", True),
    ("fem_cantilever", "Seed 002 sec. 2.3: an FEM cantilever (plane-strain linear triangles, "
                       "corotational) under its own weight against Euler-Bernoulli, three meshes",
     True),
    ("fem_incline", "Seed 002 sec. 4.1 in 2D: the elastic disk on an FEM plate at R = element /"
                    " cell = 1, 2, 4, 8 (particle-to-surface), and the grid-based multi_velocity "
                    "on an incline cut into rigid segments R cells long", True),
    ("flexible_barrier", "Issue 18: the shipped flexible_barrier scene (seed 003 sand into a "
                         "clamped FEM barrier) under refinement, and its cost by stage", True),
    ("water_gate", "Seed 002 sec. 4.3: a water column collapsing through an elastic gate (Walhorn"
                   " et al. 2005's case; gate tip against five published histories read off their"
                   " figures; Tait water at c0 = 60 m/s, particle-to-surface contact)", True),
    ("incline", "Seed 002 sec. 4.1: disk rolling on an incline", True),
    ("bar", "Seed 001: 1D reversibility and bar under a stress boundary condition", True),
    ("sph", "Seed 001 (issue 19): the coupled MPM-SPH method on the seed's 1D bar, biaxial "
            "plate and plate with a hole, and the SPH particles' cost", True),
    ("wheel", "Issue 20: a driven rigid wheel on sand (single-wheel rig, config/scenes/wheel.yaml):"
              " drawbar pull, gross thrust and sinkage against slip at two loads and two cell"
              " sizes, against Coulomb's bound W tan(phi) and the trends of Bekker and of Wong and"
              " Reece", True),
    ("wheel_granular", "Issue 41: the wheel rig of `wheel` with the granular sand that flows where"
                       " its Drucker-Prager sand does (mu_s the cone's slope, cases::matchedGranular)",
     True),
    ("stability", "Stability on hard cases (a fixed step above the bound set by hand is refused "
                  "before the run: test_free_fall FixedStep.AboveTheCriticalStepIsRefused)", True),
]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fmt(x, digits=4):
    v = float(x)
    if math.isnan(v):
        return "-"
    if v == 0:
        return "0"
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return "%.3g" % v
    return "%.*g" % (digits, v)


def table(rows):
    out = ["| quantity | value | reference | unit | source | error | wall (s) | settings |",
           "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        out.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["quantity"], fmt(r["value"], 6), fmt(r["reference"], 6), r["unit"], r["source"],
            fmt(r["error"]), fmt(r["wall_s"]), r["settings"]))
    return "\n".join(out)


def finish(fig, out, name):
    """Lays the figure out, writes it to out/name and closes it; returns name."""
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=110)
    plt.close(fig)
    return name


def snapshot_panels(frames, height):
    """A figure of two panels a row, one per frame (panel height in inches); the unused panels
    hidden. Returns the figure and the (axes, (time, frame)) pairs."""
    cols = 2
    rows = (len(frames) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(10, height * rows), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    panels = list(zip(axes.flat, frames.items()))
    for ax, _ in panels:
        ax.axis("on")
    return fig, panels


def plot_collision(data, out):
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5), sharey=True)
    for ax, name in zip(axes, ["hard", "soft"]):
        path = os.path.join(data, "collision_%s.csv" % name)
        if not os.path.exists(path):
            return None
        rows = read_csv(path)
        t = [float(r["time"]) * 1e3 for r in rows]
        for key, label in [("disk_kinetic", "disk kinetic"), ("block_kinetic", "block kinetic"),
                           ("elastic", "disk elastic")]:
            ax.plot(t, [float(r[key]) for r in rows], label=label)
        ax.set_title("%s disk" % name)
        ax.set_xlabel("time (ms)")
        ax.set_xlim(0, 20)
    axes[0].set_ylabel("energy (J/m)")
    axes[0].legend()
    return finish(fig, out, "collision_energy.png")


def plot_contact_schemes(data, out):
    path = os.path.join(data, "contact_schemes.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for s in SCHEMES:
        rs = [r for r in rows if r["scheme"] == s]
        h = [100 * float(r["cell_size_m"]) for r in rs]
        axes[0].semilogy(h, [max(float(r["v2_error"]), 1e-16) for r in rs], "o-", label=s)
        axes[1].semilogx([float(r["us_per_step"]) for r in rs],
                         [max(float(r["v2_error"]), 1e-16) for r in rs], "o", label=s)
    axes[0].set_xlabel("grid size d_g (cm)")
    axes[0].set_ylabel("|change of sum m v^2| / initial")
    axes[0].legend(fontsize=8)
    axes[1].set_yscale("log")
    axes[1].set_xlabel("wall time per step (us)")
    return finish(fig, out, "contact_schemes.png")


def plot_debris(data, out):
    fig, ax = plt.subplots(figsize=(6, 3.5))
    found = False
    for s in SCHEMES:
        path = os.path.join(data, "debris_%s.csv" % s)
        if not os.path.exists(path):
            continue
        found = True
        rows = read_csv(path)
        ax.plot([float(r["time"]) for r in rows],
                [-float(r["block2_angle_deg"]) for r in rows], label=s)
    if not found:
        plt.close(fig)
        return None
    ax.set_xlabel("time (s)")
    ax.set_ylabel("block 2 rotation (deg, clockwise)")
    ax.legend(fontsize=8)
    return finish(fig, out, "debris_block2_angle.png")


def plot_debris_granular(data, out):
    """Issues 40 and 79: the blocks' rotation histories in the granular scene, the first member at
    each cell size (solid; dashed with volume-consistent points), against seed 003's description
    (sec. 4.3): block 2 turned 90 deg by 0.40 s and lands at 0.36-0.37 s; block 1 turned over,
    180 deg, by 0.45 s, and lands at 0.38-0.39 s."""
    def runs(prefix):
        found = (f for f in os.listdir(data) if f.startswith(prefix) and f.endswith("mm.csv"))
        return {float(f[len(prefix):-len("mm.csv")]): f for f in found}
    plain, fitted = runs("debris_granular_angles_"), runs("debris_granular_fit_angles_")
    if not plain and not fitted:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5), sharey=True)
    for i, mm in enumerate(sorted(set(plain) | set(fitted), reverse=True)):
        for files, style, suffix in ((plain, "-", ""), (fitted, "--", ", fit")):
            if mm not in files:
                continue
            rows = read_csv(os.path.join(data, files[mm]))
            t = [float(r["time"]) for r in rows]
            for ax, key in zip(axes, ("block2_angle_deg", "block1_angle_deg")):
                ax.plot(t, [abs(float(r[key])) for r in rows], style, color="C%d" % i,
                        label="%g mm%s" % (mm, suffix), lw=1)
    marks = (((0.365, 0.40), 90, "block 2"), ((0.385, 0.45), 180, "block 1"))
    for ax, ((lands, by), angle, name) in zip(axes, marks):
        ax.plot([by], [angle], "k*", ms=10, label="seed 003: %d deg by %.2f s" % (angle, by))
        ax.axvline(lands, color="k", ls=":", lw=0.8, label="seed 003: lands (%.3f s)" % lands)
        ax.set_xlabel("time (s)")
        ax.set_title(name, fontsize=9)
        ax.set_xlim(0.2, 0.7)
    axes[0].set_ylabel("|rotation| (deg)")
    handles, labels = axes[0].get_legend_handles_labels()
    marks = [(h, l) for h, l in zip(handles, labels) if l.startswith("seed 003")]
    axes[0].legend(*zip(*marks), fontsize=7, loc="lower right")
    axes[1].legend(fontsize=6, loc="lower right", ncol=2)
    return finish(fig, out, "debris_granular_angles.png")


def plot_debris_snapshots(data, out):
    """The material points and blocks at the seeds' snapshot times (IMP run)."""
    path = os.path.join(data, "debris_snapshots.csv")
    if not os.path.exists(path):
        return None
    frames = OrderedDict()
    for r in read_csv(path):
        frame = frames.setdefault(r["time"], {"points": ([], []), "blocks": OrderedDict()})
        if r["what"] == "point":
            frame["points"][0].append(100 * float(r["x"]))
            frame["points"][1].append(100 * float(r["y"]))
        else:
            block = frame["blocks"].setdefault(r["what"], (float(r["id"]), []))
            block[1].append((100 * float(r["x"]), 100 * float(r["y"])))
    if not frames:  # the fast run writes the header only
        return None
    fig, panels = snapshot_panels(frames, 2.2)
    for ax, (t, frame) in panels:
        ax.scatter(frame["points"][0], frame["points"][1], s=1.0, c="#c2a060", linewidths=0)
        for name, (rounding, verts) in frame["blocks"].items():
            # The core polygon stroked with the rounding's width: the spheropolygon's outline.
            xs = [v[0] for v in verts] + [verts[0][0]]
            ys = [v[1] for v in verts] + [verts[0][1]]
            ax.fill(xs, ys, color="#7a4a1e" if name != "floor" else "#555555",
                    lw=max(0.5, 200 * rounding), edgecolor="#7a4a1e" if name != "floor" else "#555555")
        ax.set_xlim(0, 50)
        ax.set_ylim(-1, 22)
        ax.set_aspect("equal")
        ax.set_title("t = %.2f s" % float(t), fontsize=9)
        ax.tick_params(labelsize=7)
    fig.supxlabel("x (cm)", fontsize=9)
    return finish(fig, out, "debris_snapshots.png")


def plot_silo(data, out):
    path = os.path.join(data, "silo.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, ax = plt.subplots(figsize=(6, 4))
    groups = OrderedDict()
    for r in rows:
        key = "h %.1f mm, %s x %s ppc, J_sep %s" % (1000 * float(r["cell_size_m"]),
                                                   r["points_per_cell"], r["points_per_cell"],
                                                   r["separation"])
        groups.setdefault(key, []).append(r)
    for key, rs in groups.items():
        ax.plot([100 * float(r["neck_m"]) for r in rs], [float(r["rate_kg_s_m"]) for r in rs],
                "o-" if len(rs) > 1 else "s", label=key)
    d = [1.5 + 0.1 * i for i in range(50)]
    ax.plot(d, [0.58 * 1500 * math.sqrt(10) * max(0, x / 100 - 0.0022) ** 1.5 for x in d], "k--",
            label="Beverloo, C = 0.58, k_c = 2.2")
    ax.set_xlabel("neck width D0 (cm)")
    ax.set_ylabel("mass flow rate (kg/(s m))")
    ax.legend(fontsize=7)
    return finish(fig, out, "silo_beverloo.png")


def plot_silo_convergence(data, out):
    """Flow rate against cell size per neck (log-log), and the rates against the neck width."""
    path = os.path.join(data, "silo_convergence.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    necks = OrderedDict()
    sizes = OrderedDict()
    for r in rows:
        necks.setdefault(r["neck_m"], []).append(r)
        sizes.setdefault(r["cell_size_m"], []).append(r)
    for neck, rs in necks.items():
        axes[0].plot([1000 * float(r["cell_size_m"]) for r in rs],
                     [float(r["rate_kg_s_m"]) for r in rs], "o-",
                     label="D0 %.0f cm" % (100 * float(neck)))
    axes[0].set_xlabel("cell size h (mm)")
    axes[0].set_ylabel("mass flow rate (kg/(s m))")
    axes[0].invert_xaxis()
    axes[0].legend(fontsize=8)
    for h, rs in sizes.items():
        axes[1].loglog([100 * float(r["neck_m"]) - 0.22 for r in rs],
                       [float(r["rate_kg_s_m"]) for r in rs], "o-",
                       label="h %.1f mm" % (1000 * float(h)))
    d = [1.5 + 0.1 * i for i in range(50)]
    axes[1].loglog(d, [0.58 * 1500 * math.sqrt(10) * (x / 100) ** 1.5 for x in d], "k--",
                   label="Beverloo (exponent 1.5, C 0.58)")
    axes[1].set_xlabel("D0 - k_c r_p (cm)")
    axes[1].set_ylabel("mass flow rate (kg/(s m))")
    for ax in axes:
        ax.legend(fontsize=7, loc="lower right")
    return finish(fig, out, "silo_convergence.png")


def plot_debris_flow(data, out):
    """Kinetic energy at 0.2 s against the cell size (two kappa_2) and against the step count."""
    path = os.path.join(data, "debris_flow.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    series = OrderedDict()
    for r in rows:
        series.setdefault((r["study"], r["transfer"], r["contact_factor"]), []).append(r)
    for (study, transfer, kappa2), rs in series.items():
        if study == "refinement":
            axes[0].plot([1000 * float(r["cell_size_m"]) for r in rs],
                         [float(r["kinetic_J_per_m"]) for r in rs], "o-",
                         label="%s, kappa_2 %s" % (transfer, kappa2))
    axes[0].set_xlabel("cell size h (mm)")
    axes[0].set_ylabel("kinetic energy at 0.2 s (J/m)")
    axes[0].invert_xaxis()
    axes[0].legend(fontsize=8)
    by_transfer = OrderedDict()
    for (study, transfer, kappa2), rs in series.items():
        if study == "time_step":
            by_transfer.setdefault(transfer, []).extend(rs)
    for transfer, rs in by_transfer.items():
        axes[1].semilogx([float(r["steps"]) for r in rs], [float(r["kinetic_J_per_m"]) for r in rs],
                         "o-", label=transfer)
    axes[1].set_xlabel("steps to 0.2 s (one cell size)")
    axes[1].set_ylabel("kinetic energy at 0.2 s (J/m)")
    axes[1].legend(fontsize=8)
    return finish(fig, out, "debris_flow.png")


def plot_water_gate(data, out):
    """The gate's upper-left corner against the published range, one line per resolution."""
    path = os.path.join(data, "water_gate_tip.csv")
    if not os.path.exists(path):
        return None
    runs = OrderedDict()
    for r in read_csv(path):
        key = "cells %.0f mm, elements %.0f mm, c0 %.0f m/s" % (
            1000 * float(r["cell_m"]), 1000 * float(r["element_m"]), float(r["sound_speed"]))
        runs.setdefault(key, ([], []))
        runs[key][0].append(float(r["time"]))
        runs[key][1].append(1000 * float(r["tip_m"]))
    fig, ax = plt.subplots(figsize=(6, 3.5))
    # The five published curves' range at the times the case compares (m -> mm), as bars.
    for r in read_csv(os.path.join(data, "water_gate_reference.csv")):
        ax.plot([float(r["time"])] * 2, [1000 * float(r["low_m"]), 1000 * float(r["high_m"])],
                color="k", lw=3, alpha=0.4)
    ax.plot([], [], color="k", lw=3, alpha=0.4, label="published range (5 methods)")
    for key, (t, u) in runs.items():
        ax.plot(t, u, label=key, lw=1)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("gate tip displacement (mm)")
    ax.legend(fontsize=7)
    return finish(fig, out, "water_gate_tip.png")


def plot_water_gate_snapshots(data, out):
    path = os.path.join(data, "water_gate_snapshots.csv")
    if not os.path.exists(path):
        return None
    frames = OrderedDict()
    for r in read_csv(path):
        frame = frames.setdefault(r["time"], {"water": ([], []), "gate": ([], [])})
        frame[r["what"]][0].append(100 * float(r["x"]))
        frame[r["what"]][1].append(100 * float(r["y"]))
    if not frames:  # the fast run writes the header only
        return None
    fig, panels = snapshot_panels(frames, 2.6)
    for ax, (t, frame) in panels:
        ax.scatter(*frame["water"], s=0.3, c="#3070c0", linewidths=0)
        ax.scatter(*frame["gate"], s=2.0, c="#b03020", linewidths=0)
        ax.set_xlim(0, 58.4)
        ax.set_ylim(0, 32)
        ax.set_aspect("equal")
        ax.set_title("t = %.2f s" % float(t), fontsize=9)
        ax.tick_params(labelsize=7)
    fig.supxlabel("x (cm)", fontsize=9)
    return finish(fig, out, "water_gate_snapshots.png")


def stage_table(data, name):
    """Per-stage milliseconds per step and share of the step, one column per run."""
    path = os.path.join(data, name + "_stages.csv")
    if not os.path.exists(path):
        return None
    runs, stages = OrderedDict(), OrderedDict()
    for r in read_csv(path):
        run = "%g mm / %g mm" % (round(1000 * float(r["cell_m"]), 3),
                                 round(1000 * float(r["element_m"]), 3))
        runs.setdefault(run, {})[r["stage"]] = (float(r["ms_per_step"]), float(r["share"]))
        stages[r["stage"]] = True
    head = "| stage | " + " | ".join("%s: ms/step (share)" % k for k in runs) + " |"
    lines = ["Cost by stage (cells / elements):", "", head,
             "|" + " --- |" * (len(runs) + 1)]
    for st in stages:
        cells = []
        for run in runs.values():
            ms, share = run.get(st, (0, 0))
            cells.append("%.3f (%.0f%%)" % (ms, 100 * share))
        lines.append("| %s | %s |" % (st, " | ".join(cells)))
    return "\n".join(lines)


def plot_compression(data, out):
    fig, ax = plt.subplots(figsize=(6, 4))
    found = False
    for pct in ("10", "20", "30"):
        path = os.path.join(data, "compression_%s.csv" % pct)
        if not os.path.exists(path):
            continue
        found = True
        rows = read_csv(path)
        ax.plot([100 * float(r["settlement_m"]) for r in rows],
                [float(r["force_n_m"]) / 1000 for r in rows], label="fines %s%%" % pct)
    if not found:
        plt.close(fig)
        return None
    ax.set_xlabel("settlement (cm)")
    ax.set_ylabel("plate force (kN/m)")
    ax.legend()
    return finish(fig, out, "compression_force_settlement.png")


def plot_wheel(data, out):
    path = os.path.join(data, "wheel_sweep.csv")
    if not os.path.exists(path):
        return None
    rows = read_csv(path)
    fig, (pull, sink) = plt.subplots(1, 2, figsize=(10, 4))
    for key in sorted({(r["load_n_m"], r["cell_m"]) for r in rows}):
        sel = sorted((r for r in rows if (r["load_n_m"], r["cell_m"]) == key),
                     key=lambda r: float(r["slip"]))
        label = "W = %s N/m, h = %g mm" % (key[0], 1e3 * float(key[1]))
        slip = [float(r["slip"]) for r in sel]
        pull.plot(slip, [float(r["pull_n_m"]) / float(r["load_n_m"]) for r in sel], "o-",
                  label=label)
        sink.plot(slip, [1e3 * float(r["sinkage_m"]) for r in sel], "o-", label=label)
    bound = [float(r["reference"]) for r in read_csv(os.path.join(data, "results.csv"))
             if r["case"] == "wheel" and r["quantity"].startswith("drawbar pull")]
    if bound:
        pull.axhline(bound[0], color="k", ls=":", label="tan(phi): Coulomb's bound")
    pull.set_xlabel("slip")
    pull.set_ylabel("drawbar pull / load")
    pull.legend(fontsize=7)
    sink.set_xlabel("slip")
    sink.set_ylabel("sinkage (mm)")
    return finish(fig, out, "wheel_pull_sinkage.png")
def plot_blade(data, out):
    """Force on the blade over Reece's (q = 0) against its advance over the depth, per blade
    friction: the three depths (colours) at each cell size (line styles); in black, the shipped
    scene file's start (unstressed layer, blade at full speed at once)."""
    path = os.path.join(data, "blade.csv")
    if not os.path.exists(path):
        return None
    # A run ends where the settings change or the displacement falls back; of runs with the
    # same settings (the deeper layer's), the first is drawn.
    series, last_x = [], None
    for r in read_csv(path):
        key = (float(r["friction"]), float(r["depth_m"]), float(r["cell_m"]),
               float(r["speed_m_s"]), r["start"])
        x = float(r["displacement_m"])
        if not series or series[-1][0] != key or x < last_x:
            series.append((key, []))
        series[-1][1].append(r)
        last_x = x
    runs = OrderedDict()
    for key, rows in series:
        runs.setdefault(key, rows)
    frictions = sorted({k[0] for k in runs})
    fig, axes = plt.subplots(1, len(frictions), figsize=(6 * len(frictions), 4.2), squeeze=False)
    colours = {0.04: "tab:red", 0.06: "tab:green", 0.08: "tab:blue"}
    styles = {0.01: ":", 0.005: "--", 0.0025: "-"}
    for ax, mu in zip(axes[0], frictions):
        for (f, d, h, v, start), rows in runs.items():
            if f != mu or v != 0.05 or d not in colours or h not in styles:
                continue
            reece = float(rows[0]["reece_n_m"])
            scene = start == "scene"
            ax.plot([float(r["displacement_m"]) / d for r in rows],
                    [float(r["horizontal_n_m"]) / reece for r in rows],
                    "-" if scene else styles[h], lw=0.6 if scene else 0.9,
                    color="k" if scene else colours[d],
                    label=("d %.0f cm, h %.1f mm" % (100 * d, 1000 * h)) +
                    (", the scene file's start" if scene else ""))
        ax.axhline(1, color="k", lw=0.8)
        ax.axvspan(0.05, 0.3, color="0.9", zorder=0)
        ax.set_xlabel("blade advance x / d")
        ax.set_ylabel("horizontal force / Reece's (q = 0)")
        ax.set_title("blade friction %.1f" % mu)
        ax.set_ylim(0, 2.6)
        ax.legend(fontsize=6, ncol=3)
    return finish(fig, out, "blade_force.png")


def plot_chute(data, out):
    """The chute's grid L2 error against Bagnold's profile and the nodes' largest over-fill over
    time (chute_series.<run>.csv), one row per angle, one line per variant and cell."""
    series = sorted(glob.glob(os.path.join(data, "chute_series.*.csv")))
    if not series:
        return None
    runs = OrderedDict()
    for path in series:
        for r in read_csv(path):
            key = (float(r["angle_deg"]), r["variant"], float(r["cell_m"]))
            runs.setdefault(key, []).append((float(r["t_s"]), float(r["l2"]),
                                             float(r["overfill"])))
    angles = sorted({k[0] for k in runs})
    variants = list(OrderedDict.fromkeys(k[1] for k in runs))
    cells = sorted({k[2] for k in runs}, reverse=True)
    fig, axes = plt.subplots(len(angles), 2, figsize=(9, 2.6 * len(angles)), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = ["-", "--", ":"]
    for row, angle in enumerate(angles):
        for (a, variant, cell), pts in runs.items():
            if a != angle:
                continue
            colour = colours[variants.index(variant) % len(colours)]
            style = styles[cells.index(cell) % len(styles)]
            label = "%s, %g mm" % (variant, 1000 * cell)
            t = [p[0] for p in pts]
            axes[row][0].semilogy(t, [max(p[1], 1e-4) for p in pts], style, color=colour, lw=1,
                                  label=label)
            axes[row][1].semilogy(t, [max(p[2], 1e-6) for p in pts], style, color=colour, lw=1,
                                  label=label)
        axes[row][0].axhline(0.02, color="0.6", lw=0.6)
        axes[row][0].set_ylabel("%g deg: L2 error" % angle)
        axes[row][1].set_ylabel("largest over-fill")
    for ax in axes[-1]:
        ax.set_xlabel("t (s)")
    axes[0][1].legend(fontsize=5, ncol=1)
    return finish(fig, out, "chute_l2_overfill.png")


def plot_cross_solver(data, out):
    """cross_chute and cross_column: our profiles at each cell and transfer beside Basilisk's."""
    def runs(case):  # the case's tables in the order of its runs (case.N.csv)
        found = [f for f in os.listdir(data) if f.startswith(case + ".") and f.endswith(".csv")]
        return sorted(found, key=lambda f: int(f[len(case) + 1:-len(".csv")]))
    chute, column = runs("cross_chute"), runs("cross_column")
    if not chute and not column:
        return None
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    left = axes[0]
    for name in chute:
        rows = read_csv(os.path.join(data, name))
        if not rows:
            continue
        label = "%s, %g mm" % (rows[0]["transfer"], 1e3 * float(rows[0]["cell_m"]))
        style = "-" if rows[0]["transfer"] == "ASFLIP" else "--"
        left.plot([float(r["u_m_s"]) for r in rows], [100 * float(r["z_m"]) for r in rows],
                  style, marker=".", label=label)
    if chute:
        rows = read_csv(os.path.join(data, chute[0]))
        left.plot([float(r["basilisk_m_s"]) for r in rows], [100 * float(r["z_m"]) for r in rows],
                  "k-", linewidth=2, label="Basilisk")
    left.set_xlabel("speed along the slope (m/s)")
    left.set_ylabel("height (cm)")
    left.set_title("chute at 24.64 deg after 6 s")
    left.legend(fontsize=7)
    reference = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation",
                             "basilisk", "column_deposit.csv")
    theirs = read_csv(reference) if os.path.exists(reference) else []
    for ax, aspect, reach in ((axes[1], "0.5", 50), (axes[2], "1.42", 45)):
        for name in column:
            rows = [r for r in read_csv(os.path.join(data, name)) if r["aspect"] == aspect]
            if not rows:
                continue
            label = "%s, %g mm" % (rows[0]["transfer"], 1e3 * float(rows[0]["cell_m"]))
            style = "-" if rows[0]["transfer"] == "ASFLIP" else "--"
            ax.plot([100 * float(r["x_m"]) for r in rows],
                    [100 * float(r["thickness_m"]) for r in rows], style, label=label)
        mine = [r for r in theirs if r["aspect"] == aspect]
        levels = sorted({int(r["level"]) for r in mine})
        for level in levels:  # H0 = 10 cm
            sel = [r for r in mine if int(r["level"]) == level]
            ax.plot([10 * float(r["x_over_h0"]) for r in sel],
                    [10 * float(r["thickness_over_h0"]) for r in sel], "k-",
                    linewidth=2 if level == levels[-1] else 0.8,
                    label="Basilisk, %d cells over 5 H0" % (1 << level))
        ax.set_xlim(0, reach)
        ax.set_xlabel("distance from the back wall (cm)")
        ax.set_ylabel("deposit thickness (cm)")
        ax.set_title("column a = %s, H0 = 10 cm" % aspect)
        ax.legend(fontsize=7)
    return finish(fig, out, "cross_solver.png")


def plot_intrusion_frontier(data, out):
    """The upright plate's drag: |error| from its limit against wall seconds per simulated second,
    one line per configuration through the cells (labelled), real time marked."""
    path = os.path.join(data, "results.csv")
    if not os.path.exists(path):
        return None
    lines = OrderedDict()
    for r in read_csv(path):
        if r["case"] != "intrusion_frontier":
            continue
        # "alpha_x's error from the limit, h 5 mm, asleep below 10 mm/s[, USL]"
        parts = r["quantity"].split(", ")
        cell, config = parts[1][2:], ", ".join(parts[2:])
        rate = re.search(r"about ([0-9.e+]+) s per simulated s", r["settings"])
        if rate:
            lines.setdefault(config, []).append((float(rate.group(1)),
                                                 100 * abs(float(r["value"])), cell))
    if not lines:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.6))
    for config, pts in lines.items():
        line, = ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, lw=0.9,
                          label=config)
        for x, y, cell in pts:
            ax.annotate(cell, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points",
                        color=line.get_color())
    ax.axvline(1, color="k", lw=0.8, ls=":")
    ax.text(1.05, ax.get_ylim()[0] * 1.1, "real time", fontsize=7)
    for tol in (5, 10, 30):
        ax.axhline(tol, color="0.7", lw=0.6)
    ax.set_yticks([5, 10, 20, 30, 50, 70])
    ax.yaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.set_xlabel("wall seconds per simulated second (two threads)")
    ax.set_ylabel("|alpha_x - limit| / limit (%)")
    ax.set_title("upright plate dragged at 6 cm, 0.1 m/s")
    ax.legend(fontsize=7)
    return finish(fig, out, "intrusion_frontier.png")


def plot_intrusion_diagnosis(data, out):
    """The upright plate's drag error against its converged limit, one bar per numerical choice
    and cell (issue 90's diagnosis)."""
    path = os.path.join(data, "results.csv")
    if not os.path.exists(path):
        return None
    bars = OrderedDict()  # choice -> {cell: error %}
    for r in read_csv(path):
        # "alpha_x of the upright plate dragged at 6 cm, <choice>, h <cell>"
        if r["case"] != "intrusion_diagnosis" or "dragged at 6 cm" not in r["quantity"]:
            continue
        parts = r["quantity"].split(", ")
        bars.setdefault(", ".join(parts[1:-1]), {})[parts[-1][2:]] = 100 * (
            float(r["value"]) / float(r["reference"]) - 1)
    if not bars:
        return None
    cells = sorted({c for v in bars.values() for c in v}, key=lambda c: -float(c.split()[0]))
    fig, ax = plt.subplots(figsize=(8, 4.2))
    width = 0.8 / len(cells)
    for k, cell in enumerate(cells):
        xs = [i + (k - (len(cells) - 1) / 2) * width for i in range(len(bars))]
        ax.bar(xs, [v.get(cell, float("nan")) for v in bars.values()], width, label="h " + cell)
    ax.set_xticks(range(len(bars)))
    ax.set_xticklabels(list(bars), rotation=35, ha="right", fontsize=7)
    for tol in (-10, 10):
        ax.axhline(tol, color="0.6", lw=0.6, ls=":")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_ylabel("drag - converged drag (%)")
    ax.set_title("upright plate dragged at 6 cm: one numerical choice at a time")
    ax.legend(fontsize=7)
    return finish(fig, out, "intrusion_diagnosis.png")


def family(quantity):
    """Rows of one quantity measured at different settings: the name up to its first comma."""
    return quantity.split(",")[0]


def particle_steps_per_second(r):
    points, steps = int(r.get("points") or 0), int(r.get("steps") or 0)
    wall = float(r["wall_s"])
    return points * steps / wall if points and steps and wall > 0 else None


def speed_vs_error(by_case, out):
    """Per case and quantity, the runs with a reference and a wall time: error against wall time
    (and particle-steps per second where counted), the Pareto front (no other run both cheaper
    and more accurate), and the cheapest run that reaches 10%, 5% and 1%."""
    lines = ["", "## Speed against error", "",
             "Every measured quantity with a reference, grouped by quantity (the name before its"
             " first comma) within a case, its error against the wall time of its run. Pareto"
             " front: the runs no other run of the group beats on both. 'Cheapest' names the"
             " fastest run within 10%, 5% and 1% (relative error; absolute for a zero reference)."
             " The stability cases and sample-preparation checks are left out: they have no"
             " resolution to trade; so are the convergence studies without a reference, and the"
             " wheel, whose reference is a bound, not a value to reach.", "",
             "| case: quantity | runs | Pareto front (error @ wall s: run) | cheapest <= 10% | <= 5% |"
             " <= 1% |",
             "| --- | --- | --- | --- | --- | --- |"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for case, rows in by_case.items():
        if case in ("stability", "wheel", "wheel_granular"):
            continue
        groups = OrderedDict()
        for r in rows:
            err, wall = float(r["error"]), float(r["wall_s"])
            if (math.isnan(err) or wall <= 0 or r["source"] == "sample preparation"
                    or r["source"].startswith("convergence (no measurement)")):
                continue
            groups.setdefault(family(r["quantity"]), []).append((wall, err, r))
        for name, pts in groups.items():
            if len(pts) < 2:
                continue
            pts.sort(key=lambda p: (p[0], p[1]))
            front, best = [], float("inf")
            for p in pts:
                if p[1] < best:
                    front.append(p)
                    best = p[1]
            label = "%s: %s" % (case, name)
            line, = axes[0].loglog([p[0] for p in pts], [max(p[1], 1e-9) for p in pts], "o", ms=3,
                                   label=label)
            axes[0].loglog([p[0] for p in front], [max(p[1], 1e-9) for p in front], "-", lw=0.8,
                           color=line.get_color())
            rate = [(particle_steps_per_second(p[2]), p[1]) for p in pts]
            rate = [q for q in rate if q[0]]
            if rate:
                axes[1].loglog([q[0] for q in rate], [max(q[1], 1e-9) for q in rate], "o", ms=3,
                               color=line.get_color())

            def describe(p):
                q = p[2]["quantity"]
                rest = q[len(name) + 2:] if len(q) > len(name) else ""
                return rest or p[2]["settings"]

            def cheapest(tol):
                for p in pts:
                    if p[1] <= tol:
                        return "%s (%s s)" % (describe(p), fmt(p[0], 3))
                return "not reached"
            lines.append("| %s | %d | %s | %s | %s | %s |" % (
                label, len(pts), "; ".join("%s @ %s: %s" % (fmt(p[1], 3), fmt(p[0], 3), describe(p))
                                           for p in front),
                cheapest(0.10), cheapest(0.05), cheapest(0.01)))
    axes[0].set_xlabel("wall time of the run (s)")
    axes[0].set_ylabel("error")
    axes[0].legend(fontsize=5, ncol=2)
    axes[1].set_xlabel("particle-steps per second")
    axes[1].set_ylabel("error")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "speed_vs_error.png"), dpi=110)
    plt.close(fig)
    lines += ["", "![speed against error](speed_vs_error.png)"]
    return lines


def main():
    data, out, mode, machine = sys.argv[1:5]
    rows = read_csv(os.path.join(data, "results.csv"))
    by_case = OrderedDict()
    for r in rows:
        by_case.setdefault(r["case"], []).append(r)
    plots = {"collision": plot_collision(data, out),
             "contact_schemes": plot_contact_schemes(data, out),
             "debris": plot_debris(data, out),
             "debris_snapshots": plot_debris_snapshots(data, out),
             "debris_granular": plot_debris_granular(data, out),
             "silo": plot_silo(data, out),
             "silo_convergence": plot_silo_convergence(data, out),
             "debris_flow": plot_debris_flow(data, out),
             "compression": plot_compression(data, out),
             "wheel": plot_wheel(data, out),
             "blade": plot_blade(data, out),
             "intrusion_diagnosis": plot_intrusion_diagnosis(data, out),
             "intrusion_frontier": plot_intrusion_frontier(data, out),
             "chute": plot_chute(data, out),
             "cross_chute": plot_cross_solver(data, out),
             "water_gate": plot_water_gate(data, out),
             "water_gate_snapshots": plot_water_gate_snapshots(data, out)}
    lines = ["# Validation report", "",
             "Generated by `scripts/validate` (%s resolution), last on %s. Every row: the quantity,"
             " our value, the reference and where it comes from, the error (relative to the"
             " reference; absolute when the reference is 0), the wall time of the run and its"
             " settings. Cases run with `--cases` are merged into the report's other cases: the"
             " list below gives the commit, date and machine of each case's run. Do not edit by"
             " hand: rerun `scripts/validate`." % (mode, machine), "",
             "## Cases", ""]
    runs = {}
    if os.path.exists(os.path.join(data, "runs.csv")):
        runs = {r["case"]: r for r in read_csv(os.path.join(data, "runs.csv"))}
    for key, title, done in CASES:
        where = "below" if key in by_case else ("not in this run" if done else "not reproduced yet")
        if key in by_case:
            run = runs.get(key)
            where += " (measured %s at %s on %s%s)" % (
                run["date"], run["commit"], run["machine"],
                "; " + run["note"] if run.get("note") else "") if run else \
                " (measured before runs were recorded)"
        lines.append("- %s: %s" % (title, where))
    for key, title, _ in CASES:
        if key not in by_case:
            continue
        lines += ["", "## " + title, "", table(by_case[key])]
        for plot in (key, key + "_snapshots"):
            if plots.get(plot):
                lines += ["", "![%s](%s)" % (plot, plots[plot])]
        stages = stage_table(data, key)
        if stages:
            lines += ["", stages]
    lines += speed_vs_error(by_case, out)
    with open(os.path.join(out, "REPORT.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
