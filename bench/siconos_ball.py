#!/usr/bin/env python3
"""Siconos 4.4 on the bouncing ball (issue 35, item 4; docs/contact.md, "Siconos"): a benchmark
peer beside mo2d's events, its compliant law and Box2D (`build/bench/mo2d_contact_study speed`),
against the same closed form over the same horizon (10 impacts, 3.54 s).

    /usr/bin/python3 bench/siconos_ball.py [table]      # the sweep and the table (~30 s)
    /usr/bin/python3 bench/siconos_ball.py check        # the short check of ctest (peers label)
    /usr/bin/python3 bench/siconos_ball.py once|twice KIND ... # for callgrind (once_run below)

Debian's interpreter (/usr/bin/python3): python3-siconos installs into its dist-packages. Siconos
is optional (a benchmark peer only; mo2d does not depend on it): without it the script prints
"Siconos not installed (python3-siconos): skipped" and exits 0.

The scene: mechanisms/bouncing_ball.yaml's parameters (h, r, m, e, g), the ball a disc of three
coordinates (x, y, angle; mass m, inertia m r^2 / 2) as a LagrangianLinearTIDS under its weight,
the floor a LagrangianLinearTIR y = [0 1 0] q - r with a NewtonImpactNSL(e). Closed form: impact
k (k = 0, 1, ...) at t1 + 2 v1 (e + ... + e^k) / g at the approach speed v1 e^k (t1 = sqrt(2 (h -
r) / g), v1 = g t1); the errors are the largest over the first 10 impacts, as in
bench/contact_study.cpp: |t - t_k| in s and |v - v_k| / v1 with v the approach speed.

Schemes:
- Moreau-Jean time-stepping (TimeStepping, MoreauJeanOSI(theta), an LCP at the velocity level) at
  steps h. An impact is read from the run's step ends as contact_study.cpp reads Box2D's, with one
  difference that Moreau-Jean needs: the contact is activated on a predicted gap (g + h g' / 2 <=
  0, MoreauJeanOSI::addInteractionInIndexSet), so the impulse often comes one step before the gap
  at a step end is <= 0, and then it never is (the ball rebounds above the floor); the gap's
  crossing, the rule for Box2D, misses those impacts. So an impact is the first step with a
  positive impulse after at least one step without; its time is where the straight line from the
  last open step end, along its gap rate, reaches g = 0 (t_k + g_k / -g'_k: Box2D's rule, the line
  between the gaps at two step ends, on the free flight's side only); its approach speed is -g' at
  that last open step end, as for Box2D. The gap-crossing count is printed beside it.
- Siconos's event-driven scheme (EventDriven + LsodarOSI, an impact LCP and an acceleration LCP):
  each non-smooth event is an impact, at the event's time, its approach speed from the
  pre-impact velocity Siconos keeps in the memory of the dynamical system.

Cost: CPU time (user + sys of this process, time.process_time) per run, building the Siconos
objects and running the loop, the median of repeated runs of at least 0.2 s in all (at least 3),
as contact_study.cpp. The loop is Python's (computeOneStep / advanceToEvent in a `while`, reading
the state through NumPy views): that is how Siconos is driven from Python and what reading the
impacts needs; the cost of Siconos's own C++ loop (Simulation.run(), nothing read) is printed
beside it.
"""
import math
import os
import pathlib
import statistics
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "mechanisms" / "bouncing_ball.yaml"
IMPACTS = 10

try:
    import siconos.kernel as sk
    import siconos.numerics as sn
    import numpy as np
except ImportError as error:  # optional peer: not a failure
    print(f"Siconos not installed (python3-siconos): skipped ({error})")
    sys.exit(0)


def scene_parameters():
    """h, r, m, e, g from the scene file (plain numbers there)."""
    import yaml

    p = yaml.safe_load(SCENE.read_text())["parameters"]
    return {k: float(p[k]) for k in ("h", "r", "m", "e", "g")}


class Exact:
    """The closed form of the bouncing ball's impacts."""

    def __init__(self, p):
        self.e, self.g = p["e"], p["g"]
        self.t1 = math.sqrt(2 * (p["h"] - p["r"]) / p["g"])
        self.v1 = p["g"] * self.t1

    def time(self, k):
        return self.t1 + 2 * self.v1 * sum(self.e**j for j in range(1, k + 1)) / self.g

    def speed(self, k):
        return self.v1 * self.e**k

    def errors(self, impacts):
        """(found, max |t - t_k|, max |v - v_k| / v1) over the first IMPACTS impacts."""
        first = impacts[:IMPACTS]
        dt = max((abs(t - self.time(k)) for k, (t, _) in enumerate(first)), default=math.nan)
        dv = max((abs(v - self.speed(k)) / self.v1 for k, (_, v) in enumerate(first)),
                 default=math.nan)
        return len(first), dt, dv


def ball_system(p, t_end):
    """The ball and its floor contact: (nsds, ball, interaction)."""
    m, r = p["m"], p["r"]
    ball = sk.LagrangianLinearTIDS(np.array([0.0, p["h"], 0.0]), np.zeros(3),
                                   np.diag([m, m, 0.5 * m * r * r]))
    ball.setFExtPtr(np.array([0.0, -m * p["g"], 0.0]))
    relation = sk.LagrangianLinearTIR(np.array([[0.0, 1.0, 0.0]]), np.array([-r]))
    inter = sk.Interaction(sk.NewtonImpactNSL(p["e"]), relation)
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(ball)
    nsds.link(inter, ball)
    return nsds, ball, inter


LCP_SOLVERS = {"Lemke": sn.SICONOS_LCP_LEMKE, "ENUM": sn.SICONOS_LCP_ENUM,
               "PGS": sn.SICONOS_LCP_PGS, "NSGS_SBM": sn.SICONOS_LCP_NSGS_SBM,
               "NewtonMin": sn.SICONOS_LCP_NEWTONMIN}


def moreau_jean(p, t_end, h, theta, solver="Lemke", tol=1e-12, record=True):
    """Moreau-Jean time-stepping; returns (impacts, crossings) read from the step ends (module
    docstring), or (None, None) with record=False (Siconos's own loop, nothing read)."""
    nsds, ball, inter = ball_system(p, t_end)
    lcp = sk.LCP(LCP_SOLVERS[solver])
    lcp.numericsSolverOptions().dparam[sn.SICONOS_DPARAM_TOL] = tol
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(theta), lcp)
    if not record:
        with QuietStdout():
            sim.run()
        return None, None
    r = p["r"]
    q, v, impulse = ball.q(), ball.velocity(), inter.lambda_(1)
    t_prev, g_prev, rate_prev, open_prev = 0.0, q[1] - r, v[1], True
    impacts, crossings = [], 0
    while sim.hasNextEvent():
        sim.computeOneStep()
        t, g, rate, is_open = sim.nextTime(), q[1] - r, v[1], impulse[0] == 0.0
        if open_prev and not is_open:  # the first impulse after an open step: an impact
            impacts.append((t_prev + g_prev / -rate_prev, -rate_prev))
        if g_prev > 0 >= g:  # Box2D's rule (contact_study.cpp): the gap at a step end closes
            crossings += 1
        t_prev, g_prev, rate_prev, open_prev = t, g, rate, is_open
        sim.nextStep()
    return impacts, crossings


def event_driven(p, t_end, h, rtol=None, record=True):
    """EventDriven + LsodarOSI; h is the time discretisation (the largest span between two
    events of the events manager); rtol None: Lsodar's defaults (rtol 10 eps, atol 100 eps)."""
    nsds, ball, _ = ball_system(p, t_end)
    osi = sk.LsodarOSI()
    if rtol is not None:
        osi.setTol(1, rtol, rtol)  # itol 1: scalar rtol and atol (4.4 sets atol = rtol anyway)
    sim = sk.EventDriven(nsds, sk.TimeDiscretisation(0.0, h))
    sim.insertIntegrator(osi)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_IMPACT)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_SMOOTH_ACC)
    if not record:
        with QuietStdout():
            sim.run()
        return None
    events = sim.eventsManager()
    impacts = []
    while sim.hasNextEvent():
        sim.advanceToEvent()
        nonsmooth = events.nextEvent().getType() == 2  # a NonSmoothEvent
        sim.processEvents()
        if nonsmooth:  # the pre-impact velocity is kept in the memory, index 1
            impacts.append((sim.startingTime(), -ball.velocityMemory().getSiconosVector(1)[1]))
    return impacts


class QuietStdout:
    """Siconos's Simulation.run() writes two lines to C++'s std::cout (unconditionally, 4.4's
    Simulation.cpp): file descriptor 1 goes to /dev/null while it runs."""

    def __enter__(self):
        sys.stdout.flush()
        self.saved = os.dup(1)
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 1)
        os.close(null)

    def __exit__(self, *exc):
        os.dup2(self.saved, 1)
        os.close(self.saved)


def median_cpu(f):
    """Median CPU seconds of f() over repeats (at least 0.2 s in all and 3 runs; at most 200)."""
    times = []
    while len(times) < 3 or (sum(times) < 0.2 and len(times) < 200):
        start = time.process_time()
        f()
        times.append(time.process_time() - start)
    return statistics.median(times)


def row(engine, setting, errors, cpu, note=""):
    found, dt, dv = errors
    print(f"| {engine} | {setting} | {found} | {dt:.2e} | {dv:.2e} | {1e3 * cpu:.3g} | {note} |",
          flush=True)


def table():
    p = scene_parameters()
    x = Exact(p)
    t_end = x.time(IMPACTS - 1) + 0.05  # just past the 10th impact, as contact_study.cpp
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; Siconos "
          f"{getattr(sk, '__version__', '4.4')}; horizon {t_end:.4f} s")
    print("\n| engine | setting | impacts found | time error max (s) | speed error max / v1 | "
          "CPU per run (ms) | note |\n|---|---|---|---|---|---|---|")
    # LCP solvers and tolerances at one step: a single contact's LCP is 1 x 1, which every
    # solver solves exactly (the same impulses, the same errors); their costs are printed, and
    # Siconos's default (Lemke) is kept unless one is cheaper by more than the noise (5 %)
    h = 1e-3
    costs = {}
    for solver in LCP_SOLVERS:
        for tol in (1e-6, 1e-12):
            impacts, _ = moreau_jean(p, t_end, h, 0.5, solver, tol)
            costs[solver, tol] = median_cpu(lambda: moreau_jean(p, t_end, h, 0.5, solver, tol))
            row("Siconos Moreau-Jean", f"theta 0.5, h = {h:g}, LCP {solver} tol {tol:g}",
                x.errors(impacts), costs[solver, tol])
    solver, tol = min(costs, key=costs.get)
    if costs[solver, tol] > 0.95 * costs["Lemke", 1e-6]:
        solver, tol = "Lemke", 1e-6
    for theta in (0.5, 1.0):
        for h in (4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4):
            impacts, crossings = moreau_jean(p, t_end, h, theta, solver, tol)
            cpu = median_cpu(lambda: moreau_jean(p, t_end, h, theta, solver, tol))
            own = median_cpu(lambda: moreau_jean(p, t_end, h, theta, solver, tol, False))
            row("Siconos Moreau-Jean", f"theta {theta:g}, h = {h:g}, LCP {solver}",
                x.errors(impacts), cpu,
                f"{crossings} gap crossings; Siconos's own loop {1e3 * own:.3g} ms")
    # the time discretisation of the event-driven scheme divides the horizon: Siconos 4.4 stops
    # at its last multiple of h (h = 1 s: at 3 s, 6 impacts), and with h = the horizon itself
    # it runs on to 2 h (through the accumulation at 3.961 s)
    for parts in (4, 35, 354):
        h = t_end / parts
        for rtol in (None, 1e-10, 1e-6):
            impacts = event_driven(p, t_end, h, rtol)
            cpu = median_cpu(lambda: event_driven(p, t_end, h, rtol))
            own = median_cpu(lambda: event_driven(p, t_end, h, rtol, False))
            label = "defaults (10 eps, 100 eps)" if rtol is None else f"rtol = atol = {rtol:g}"
            row("Siconos event-driven", f"Lsodar {label}, h = T/{parts} = {h:.3g}",
                x.errors(impacts), cpu, f"Siconos's own loop {1e3 * own:.3g} ms")
    print(f"\nload average {os.getloadavg()[0]:.1f}")


def check():
    """The ctest check (< 1 s): Moreau-Jean (theta 1/2) at h = 2e-3 and 1e-3 finds the 10 impacts;
    its first impact within g h^2 / v1 of the closed form (the free flight is exact with theta =
    1/2 and the impact is read from the last open step end, at most h/2 before it, along the gap
    rate: the straight line misses the parabola by g (h/2)^2 / (2 v1), 8 times less; a gap offset
    or a time read at the wrong step end exceeds it); its error first order over the 10 impacts
    (the largest time error halves with h, ratio 1.6 to 2.5: each flight adds an error of a
    fraction of a step)."""
    p = scene_parameters()
    x = Exact(p)
    t_end = x.time(IMPACTS - 1) + 0.05
    errors = {}
    for h in (2e-3, 1e-3):
        impacts, _ = moreau_jean(p, t_end, h, 0.5)
        found, dt, dv = x.errors(impacts)
        first = abs(impacts[0][0] - x.time(0)) if impacts else math.inf
        bound = p["g"] * h * h / x.v1
        print(f"Moreau-Jean theta 0.5 h = {h:g}: {found} impacts, the first's time error "
              f"{first:.2e} s (bound {bound:.2e}), time error max {dt:.3e} s, speed error max "
              f"{dv:.3e} v1")
        if found != IMPACTS or not first <= bound:
            print(f"FAIL: h = {h:g}: {found} impacts (want {IMPACTS}), the first impact's time "
                  f"error {first:.3e} s (want <= {bound:.3e})")
            return 1
        errors[h] = dt
    ratio = errors[2e-3] / errors[1e-3]
    print(f"time error ratio h = 2e-3 / h = 1e-3: {ratio:.3f} (first order: 2)")
    if not 1.6 <= ratio <= 2.5:
        print("FAIL: the time error does not halve with the step")
        return 1
    print("ok")
    return 0


def once_run(argv, runs=1):
    """One run (or `runs` runs) for callgrind: once none | once mj H THETA | once ed PARTS [RTOL]
    (h = the horizon / PARTS); mj-own, ed-own: Siconos's own loop, nothing read. Instructions per run: the count of `once none` (Python, NumPy,
    Siconos's import, the scene's parameters) subtracted; `twice` the same runs twice, whose
    difference from `once` is a run without the first run's one-time costs."""
    kind = argv[0] if argv else "none"
    p = scene_parameters()
    x = Exact(p)
    t_end = x.time(IMPACTS - 1) + 0.05
    for _ in range(runs):
        own = kind.endswith("-own")  # Siconos's own loop (Simulation.run()), nothing read
        if kind.startswith("mj"):
            impacts, _ = moreau_jean(p, t_end, float(argv[1]), float(argv[2]), record=not own)
        elif kind.startswith("ed"):
            impacts = event_driven(p, t_end, t_end / float(argv[1]),
                                   float(argv[2]) if len(argv) > 2 else None, record=not own)
        else:
            continue
        print(kind, "impacts:", "not read" if impacts is None else len(impacts))
    return 0


def main(argv):
    mode = argv[0] if argv else "table"
    if mode == "table":
        table()
        return 0
    if mode == "check":
        return check()
    if mode in ("once", "twice"):
        return once_run(argv[1:], 1 if mode == "once" else 2)
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
