#!/usr/bin/env python3
"""The rocking block's impacts (mechanisms/rocking_block.yaml, docs/contact.md) against Housner's
closed forms (1963): the time T(theta_m) from rest at the tilt theta_m to the ground, by 20 panels of
20-point Gauss-Legendre quadrature after theta = theta_m (1 - s^2); the landing speed 2 b |omega|;
the ratio r = 1 - (3/2) sin^2(alpha) of successive landings.

    build/mo2d forward mechanisms/rocking_block.yaml --out OUT
    python3 scripts/rocking_block.py OUT/rocking_block_forward.json
"""
import json
import math
import sys

b, h, theta0, g = 0.1, 0.3, 0.15, 9.81  # the scene's parameters
R, alpha = math.hypot(b, h), math.atan(b / h)
p2, r = 3 * g / (4 * R), 1 - 1.5 * math.sin(alpha) ** 2


def legendre(n):
    nodes = []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            x -= p1 / dp
        nodes.append((x, 2 / ((1 - x * x) * dp * dp)))
    return nodes


NODES = legendre(20)


def quarter(tm):
    total = 0.0
    for panel in range(20):
        for x, w in NODES:
            s = (panel + (x + 1) / 2) / 20
            th = tm * (1 - s * s)
            total += w / 40 * 2 * tm * s / math.sqrt(
                2 * p2 * (math.cos(alpha - tm) - math.cos(alpha - th)))
    return total


def housner(count):
    """The first `count` impacts of Housner's closed form: (time, landing speed 2 b |omega|)."""
    t, w = quarter(theta0), math.sqrt(2 * p2 * (math.cos(alpha - theta0) - math.cos(alpha)))
    out = []
    for _ in range(count):
        out.append((t, 2 * b * w))
        w *= r
        t += 2 * quarter(alpha - math.acos(math.cos(alpha) + w * w / (2 * p2)))
    return out


def main(path):
    events = json.load(open(path))["contacts"]["events"]
    hits = [e for e in events if e["kind"] == "impact"]
    dt = dv = dr = 0.0
    for k, (e, (t, v)) in enumerate(zip(hits, housner(len(hits)))):
        dt, dv = max(dt, abs(e["t"] - t)), max(dv, abs(e["speed"] - v))
        if k:
            dr = max(dr, abs(e["speed"] / hits[k - 1]["speed"] - r))
    print(f"{len(hits)} impacts: times within {dt:.2g} s, landing speeds within {dv:.2g} m/s, "
          f"ratios within {dr:.2g} of r = {r}")


if __name__ == "__main__":
    main(sys.argv[1])
