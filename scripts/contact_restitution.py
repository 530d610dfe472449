#!/usr/bin/env python3
"""The rebound ratio of the Lankarani-Nikravesh contact law (docs/contact.md, "Laws").

In units where the mass, the stiffness and the approach speed are 1 the law's impact is
x'' = -x^n (1 + 3 (1 - e^2) / 4 x') for the penetration x >= 0 (the force clipped at 0), so the
ratio of rebound to approach speed depends on e and n alone. Integrated here by RK4 with a step
of 1e-4, the exit interpolated linearly (the same integration as tests/contact/compliant_test.cpp).
Usage: python3 scripts/contact_restitution.py [n]
"""
import sys


def rebound(e, n=1.5, h=1e-4):
    D = 3 * (1 - e * e) / 4

    def f(x, v):
        return 0.0 if x <= 0 else -max(x ** n * (1 + D * v), 0.0)

    x, v = 0.0, 1.0
    for i in range(1000000):
        k1x, k1v = v, f(x, v)
        k2x, k2v = v + h / 2 * k1v, f(x + h / 2 * k1x, v + h / 2 * k1v)
        k3x, k3v = v + h / 2 * k2v, f(x + h / 2 * k2x, v + h / 2 * k2v)
        k4x, k4v = v + h * k3v, f(x + h * k3x, v + h * k3v)
        xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if i > 10 and xn < 0:
            return -(v + (vn - v) * x / (x - xn))
        x, v = xn, vn
    return float("nan")


if __name__ == "__main__":
    n = float(sys.argv[1]) if len(sys.argv) > 1 else 1.5
    print("e asked  rebound ratio  excess")
    for e in (0.99, 0.95, 0.9, 0.8, 0.7, 0.5, 0.3):
        r = rebound(e, n)
        print(f"{e:7.2f}  {r:13.5f}  {r - e:7.5f}")
