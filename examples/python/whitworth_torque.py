#!/usr/bin/env python3
"""The README's second figure (docs/img/whitworth_torque.png) with matplotlib: the crank torque of
the Whitworth quick-return mechanism at omega = pi/2 rad/s over two crank revolutions, from the
scene file mechanisms/whitworth.yaml. docs/python.md walks through it.

    PYTHONPATH=build/python python3 examples/python/whitworth_torque.py [OUT.png]
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402

import mo2d  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main(out="whitworth_torque.png"):
    scene = mo2d.load_scene(ROOT / "mechanisms" / "whitworth.yaml")
    r = mo2d.inverse(scene)
    fig, ax = plt.subplots(figsize=(7.2, 3.3), dpi=110)
    ax.plot(r.t, r["crank_pivot.torque"], color="#E69F00", lw=1.4)
    ax.set_xlim(0, 8)
    ax.set_ylim(-1.25, 1.25)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("torque (N m)")
    ax.set_title("Whitworth mechanism: crank torque at \u03C9 = \u03C0/2 rad/s")
    ax.grid(True, lw=0.5, alpha=0.5)
    fig.tight_layout()
    fig.savefig(out)
    peak = abs(r["crank_pivot.torque"]).max()
    print(f"wrote {out}: peak |torque| {peak:.4g} N m over {r.t[-1]:g} s, "
          f"{r.cpu_seconds * 1e3:.3g} ms of CPU")
    return r


if __name__ == "__main__":
    main(*sys.argv[1:2])
