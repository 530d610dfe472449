#!/usr/bin/env python3
"""Writes mechanisms/engine_pressure.csv: the cylinder pressure of mechanisms/engine.yaml against
the crank angle over one four-stroke cycle (0..720 deg, 0 = TDC between exhaust and intake).

A textbook (Heywood ch. 9) single-zone shape, not a measured curve:
  V(theta) = Vc + Ap s(theta),  s = r + L - (r cos(theta) + sqrt(L^2 - r^2 sin(theta)^2))
             (piston distance from TDC), Vc = Vd / (CR - 1), Vd = 2 r Ap
  intake       0..180:  p = p0
  compression  180..540 (motored): p_mot = p0 (Vmax / V)^n   (polytropic p V^n = const)
  combustion   from theta_s over dtheta, Wiebe burn fraction xb = 1 - exp(-a u^(m+1)),
               u = (theta - theta_s) / dtheta:  p = p_mot (1 + (rp - 1) xb)
               (the constant-volume pressure ratio rp reached as the charge burns; after the
               burn the expansion is polytropic again, p = rp p_mot)
  blowdown     540..600: p = p0 + (p(540) - p0) (1 - (3 w^2 - 2 w^3)),  w = (theta - 540) / 60
  exhaust      600..720: p = p0
Every piece joins the next with the same value and slope (dV/dtheta = 0 at BDC, the Wiebe
function starts with zero slope, the smoothstep blowdown has zero end slopes), and the last row
(720 deg) equals the first: a periodic table. Values in bar (absolute), every 2 deg.

Usage: python3 scripts/engine_pressure.py [mechanisms/engine_pressure.csv]
"""
import math
import sys

# geometry of mechanisms/engine.yaml (keep in step with its parameters)
r, L, bore, CR = 0.04, 0.14, 0.08, 9.0
# gas: intake/exhaust pressure (bar), polytropic exponent, pressure ratio, Wiebe a, m, start, length
p0, n, rp = 1.0, 1.3, 4.0
a, m, theta_s, dtheta = 5.0, 2.0, 345.0, 50.0

Ap = math.pi * bore**2 / 4
Vd = 2 * r * Ap
Vc = Vd / (CR - 1)
Vmax = Vc + Vd


def volume(deg):
    th = math.radians(deg)
    s = r + L - (r * math.cos(th) + math.sqrt(L * L - (r * math.sin(th)) ** 2))
    return Vc + Ap * s


def pressure(deg):
    if deg <= 180:
        return p0
    if deg <= 540:
        p_mot = p0 * (Vmax / volume(deg)) ** n
        u = max(0.0, (deg - theta_s) / dtheta)
        xb = 1 - math.exp(-a * u ** (m + 1))
        return p_mot * (1 + (rp - 1) * xb)
    if deg <= 600:
        w = (deg - 540) / 60
        return p0 + (pressure(540) - p0) * (1 - (3 * w * w - 2 * w**3))
    return p0


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "mechanisms/engine_pressure.csv"
    with open(path, "w") as f:
        f.write("# Cylinder pressure of mechanisms/engine.yaml against crank angle (one cycle),\n")
        f.write("# written by scripts/engine_pressure.py (formula and parameters there).\n")
        f.write("# bore 80 mm, stroke 80 mm, rod 140 mm, compression ratio 9, n = 1.3,\n")
        f.write("# pressure ratio 4, Wiebe burn from 345 deg over 50 deg (a = 5, m = 2).\n")
        f.write("crank_deg,p_bar\n")
        for k in range(361):
            deg = 2.0 * k
            f.write(f"{deg:g},{pressure(deg):.6f}\n")
    # indicated work per cycle (trapezoid on a fine grid), for the record
    N = 72000
    w = 0.0
    for k in range(N):
        d0, d1 = 720.0 * k / N, 720.0 * (k + 1) / N
        w += 0.5 * (pressure(d0) + pressure(d1)) * 1e5 * (volume(d1) - volume(d0))
    print(f"wrote {path}; Vd = {Vd*1e6:.1f} cm^3, indicated work {w:.2f} J/cycle, "
          f"imep {w / Vd / 1e5:.2f} bar, peak {max(pressure(x / 10) for x in range(7201)):.2f} bar")


if __name__ == "__main__":
    main()
