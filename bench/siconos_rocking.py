#!/usr/bin/env python3
"""Siconos 4.4 on the rocking block (issue 35, item 4; docs/contact.md, "Siconos"): Moreau-Jean
time-stepping against Housner's closed form (scripts/rocking_block.py) and mo2d's events.

    /usr/bin/python3 bench/siconos_rocking.py [MO2D]   # MO2D: the mo2d command (build/mo2d)
    /usr/bin/python3 bench/siconos_rocking.py once none|H [THETA]   # one run, for callgrind

Debian's interpreter: python3-siconos installs into its dist-packages; without it the script says
"Siconos not installed (python3-siconos): skipped" and exits 0. It compiles
bench/siconos_rocking_plugin.c (the corners' gap functions and Jacobians, Siconos's plugin
convention) with `cc` into a temporary folder.

The scene: mechanisms/rocking_block.yaml (b = 0.1, h = 0.3 half sizes, m = 10, tilted by 0.15 rad
over its right corner B, released from rest; e = 0, mu = 1). In Siconos: a LagrangianLinearTIDS
of q = (x, y, theta) of the centre of mass (mass m, m, inertia m (b^2 + h^2) / 3) under its
weight; two LagrangianScleronomousR relations (corners A and B: the normal gap and the tangential
position, from the plugin) with NewtonImpactFrictionNSL(e_n = 0, e_t = 0, mu = 1, size 2); a
FrictionContact(2) problem per step; MoreauJeanOSI(theta); TimeStepping over 2 s, as mo2d's run.

Impacts are read from the step ends as in bench/siconos_ball.py: a corner's impact is its first
step with a normal impulse after at least 0.02 s without one (the pivot's resting contact has
steps without impulse: not impacts; the flights between impacts last 0.08 s and more); its time
is where the straight line from the last open step end along the corner's normal speed reaches
the ground, its landing speed the corner's normal speed there (mo2d's "before" speed, 2 b |omega|
in Housner's model). Errors over the first 10 impacts against Housner's: time (s), landing speed
(m/s), and the ratio of successive landing speeds against r = 1 - 3/2 sin^2(alpha) = 0.85.
CPU: time.process_time (user + sys) per run, building and running, median of repeats.

Siconos's event-driven scheme is not run here: EventDriven's impact and acceleration problems are
LCPs (NewtonImpactNSL), without Coulomb friction; frictionless corners slide and Housner's
pivoting (no sliding) does not hold.
"""
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "mechanisms" / "rocking_block.yaml"
PLUGIN = ROOT / "bench" / "siconos_rocking_plugin.c"
IMPACTS = 10
OPEN_BEFORE_IMPACT = 0.02  # s without impulse before a corner's impulse counts as an impact

try:
    import siconos.kernel as sk
    import siconos.numerics as sn
    import numpy as np
except ImportError as error:  # optional peer: not a failure
    print(f"Siconos not installed (python3-siconos): skipped ({error})")
    sys.exit(0)

sys.path.insert(0, str(ROOT / "scripts"))
import rocking_block as housner  # noqa: E402  (Housner's closed form, by quadrature)


def scene_parameters():
    import yaml

    p = {k: float(v) for k, v in yaml.safe_load(SCENE.read_text())["parameters"].items()}
    # scripts/rocking_block.py has the same numbers written in: they must agree
    for mine, theirs in (("b", housner.b), ("h", housner.h), ("theta0", housner.theta0),
                         ("g", housner.g)):
        if p[mine] != theirs:
            sys.exit(f"mechanisms/rocking_block.yaml's {mine} = {p[mine]} is not "
                     f"scripts/rocking_block.py's {theirs}")
    return p


def build_plugin(folder):
    """Compiles the corners' plugin; returns its path without the .so, as Siconos names it."""
    out = pathlib.Path(folder) / "siconos_rocking_plugin"
    subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-o", f"{out}.so", str(PLUGIN), "-lm"],
                   check=True)
    return str(out)


def corner_offsets(p):
    return {"A": (-p["b"], -p["h"]), "B": (p["b"], -p["h"])}


def rocking(p, plugin, h, theta, t_end=2.0, solver=None):
    """Moreau-Jean run; returns the impacts [(time, landing speed, corner)]."""
    m, b, hh, th0 = p["m"], p["b"], p["h"], -p["theta0"]  # leaning over B: clockwise
    s, c = math.sin(th0), math.cos(th0)
    # the centre of mass with B = (b, 0) on the ground: B = centre + R(th0) (b, -h)
    x0 = b - (b * c + hh * s)
    y0 = -(b * s - hh * c)
    block = sk.LagrangianLinearTIDS(np.array([x0, y0, th0]), np.zeros(3),
                                    np.diag([m, m, m * (b * b + hh * hh) / 3]))
    block.setFExtPtr(np.array([0.0, -m * p["g"], 0.0]))
    block.setzPtr(np.array([b, hh]))
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(block)
    inters = {}
    for name in "AB":
        relation = sk.LagrangianScleronomousR(f"{plugin}:h{name}", f"{plugin}:G{name}")
        inters[name] = sk.Interaction(sk.NewtonImpactFrictionNSL(0.0, 0.0, p["mu"], 2), relation)
        nsds.link(inters[name], block)
    problem = sk.FrictionContact(2) if solver is None else sk.FrictionContact(2, solver)
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(theta), problem)
    q, v = block.q(), block.velocity()
    offsets = corner_offsets(p)

    def gap(name):  # the corner's height and its rate (the reader's own, not Siconos's)
        dx, dy = offsets[name]
        s, c = math.sin(q[2]), math.cos(q[2])
        return q[1] + dx * s + dy * c, v[1] + (dx * c - dy * s) * v[2]

    last_impulse = {name: 0.0 for name in "AB"}  # the time of the corner's last impulse
    before = {name: (0.0, *gap(name)) for name in "AB"}  # (t, g, g') at the last step end
    impacts = []
    while sim.hasNextEvent():
        sim.computeOneStep()
        t = sim.nextTime()
        for name, inter in inters.items():
            if inter.lambda_(1)[0] != 0.0:
                t0, g0, rate0 = before[name]
                if t0 - last_impulse[name] >= OPEN_BEFORE_IMPACT and rate0 < 0:
                    impacts.append((t0 + g0 / -rate0, -rate0, name))
                last_impulse[name] = t
            before[name] = (t, *gap(name))
        sim.nextStep()
    return impacts


def errors(impacts, exact):
    """(found, max time error, max landing speed error, max ratio error) over IMPACTS."""
    first = impacts[:IMPACTS]
    dt = max(abs(t - te) for (t, _, _), (te, _) in zip(first, exact))
    dv = max(abs(v - ve) for (_, v, _), (_, ve) in zip(first, exact))
    dr = max((abs(first[k][1] / first[k - 1][1] - housner.r) for k in range(1, len(first))),
             default=math.nan)
    return len(first), dt, dv, dr


class SolverWarnings:
    """Counts Siconos's "Non smooth solver warning" lines (a step whose friction problem the
    solver did not solve to its tolerance; TimeStepping::DefaultCheckSolverOutput writes them to
    C++'s std::cout and goes on) by sending file descriptors 1 and 2 to a temporary file while it
    runs."""

    def __enter__(self):
        sys.stdout.flush()
        sys.stderr.flush()
        self.file = tempfile.TemporaryFile()
        self.saved = [os.dup(1), os.dup(2)]
        os.dup2(self.file.fileno(), 1)
        os.dup2(self.file.fileno(), 2)
        return self

    def __exit__(self, *exc):
        for fd, saved in zip((1, 2), self.saved):
            os.dup2(saved, fd)
            os.close(saved)
        self.file.seek(0)
        self.count = self.file.read().decode(errors="replace").count("Non smooth solver warning")
        self.file.close()


def median_cpu(f):
    times = []
    while len(times) < 3 or (sum(times) < 0.2 and len(times) < 50):
        start = time.process_time()
        f()
        times.append(time.process_time() - start)
    return statistics.median(times)


def mo2d_run(mo2d, rtol):
    """mo2d's impacts from `mo2d forward mechanisms/rocking_block.yaml --rtol RTOL --atol
    RTOL/100` and the run's CPU seconds (its JSON summary's cpu_seconds: the run, not the
    command's start-up and output)."""
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([mo2d, "forward", str(SCENE), "--rtol", f"{rtol:g}", "--atol",
                        f"{rtol / 100:g}", "--out", out], capture_output=True, check=True)
        summary = json.loads(next(pathlib.Path(out).glob("*.json")).read_text())
    hits = [(e["t"], e["speed"], e["contact"]) for e in summary["contacts"]["events"]
            if e["kind"] == "impact"]
    return hits, summary["cpu_seconds"]


def once(h, theta):
    """One run, for callgrind (`once none`: the imports, the plugin's compilation (cc is a child
    process: not counted without --trace-children) and the parameters, subtracted)."""
    p = scene_parameters()
    with tempfile.TemporaryDirectory() as folder:
        plugin = build_plugin(folder)
        if h != "none":
            print(len(rocking(p, plugin, float(h), float(theta))), "impacts")
    return 0


def main(argv):
    if argv and argv[0] == "once":
        return once(*(argv[1:] + ["0.5"])[:2]) if len(argv) > 1 else once("none", 0)
    p = scene_parameters()
    exact = housner.housner(IMPACTS)
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; Housner: first "
          f"impact {exact[0][0]:.10f} s at {exact[0][1]:.5f} m/s, r = {housner.r:.4f}")
    print("\n| engine | setting | impacts (2 s) | time error max (s) | landing speed error max "
          "(m/s) | ratio error max | CPU per run (ms) |\n|---|---|---|---|---|---|---|")
    mo2d = argv[0] if argv else str(ROOT / "build" / "mo2d")
    if os.access(mo2d, os.X_OK):
        for rtol in (1e-10, 1e-8, 1e-6):
            runs = [mo2d_run(mo2d, rtol) for _ in range(3)]
            hits = runs[0][0]
            found, dt, dv, dr = errors(hits, exact)
            cpu = statistics.median(cpu for _, cpu in runs)
            print(f"| mo2d (events) | dopri5 rtol {rtol:g}, atol {rtol / 100:g} | {len(hits)} | "
                  f"{dt:.2e} | {dv:.2e} | {dr:.2e} | {1e3 * cpu:.3g} (cpu_seconds, median of 3) |",
                  flush=True)
    with tempfile.TemporaryDirectory() as folder:
        plugin = build_plugin(folder)
        solvers = {"NSGS (default)": None, "Lemke": sn.SICONOS_FRICTION_2D_LEMKE,
                   "ENUM": sn.SICONOS_FRICTION_2D_ENUM}
        def row(setting, h, theta, solver=None):
            with SolverWarnings() as warnings:
                impacts = rocking(p, plugin, h, theta, solver=solver)
            with SolverWarnings():
                cpu = median_cpu(lambda: rocking(p, plugin, h, theta, solver=solver))
            found, dt, dv, dr = errors(impacts, exact)
            note = f" ({warnings.count} steps the solver failed)" if warnings.count else ""
            print(f"| Siconos Moreau-Jean | {setting}{note} | {len(impacts)} | {dt:.2e} | "
                  f"{dv:.2e} | {dr:.2e} | {1e3 * cpu:.3g} |", flush=True)

        for label, solver in solvers.items():
            row(f"theta 0.5, h = 0.001, FrictionContact(2) {label}", 1e-3, 0.5, solver)
        for theta in (0.5, 1.0):
            for h in (2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4):
                row(f"theta {theta:g}, h = {h:g}, FrictionContact(2) NSGS", h, theta)
    print(f"\nload average {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
