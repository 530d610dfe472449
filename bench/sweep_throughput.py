#!/usr/bin/env python3
"""Throughput of mo2d.sweep (docs/sweeps.md): runs per second of the serial loop in one process
against a dask.distributed LocalCluster of N single-threaded worker processes, on the inverse
dynamics of mechanisms/fourbar.yaml (401 samples) over a grid of crank and coupler lengths.

    PYTHONPATH=build/python python3 bench/sweep_throughput.py [RUNS] [WORKERS]
"""
import math
import os
import pathlib
import sys
import time

import mo2d

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "mechanisms" / "fourbar.yaml"


def main(runs=200, workers=2):
    from dask.distributed import Client, LocalCluster

    side = int(math.ceil(math.sqrt(runs)))
    grid = {"a": [0.09 + 0.02 * k / (side - 1) for k in range(side)],
            "b": [0.33 + 0.04 * k / (side - 1) for k in range(side)]}
    runs = side * side

    start = time.perf_counter()
    serial = mo2d.sweep(SCENE, grid, serial=True)
    t_serial = time.perf_counter() - start
    assert serial["ok"].all(), serial[~serial["ok"]]["error"].iloc[0]
    cpu = serial["cpu_seconds"].sum()
    task = serial["task_cpu_seconds"].sum()
    print(f"load average before: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"serial loop:       {runs} runs in {t_serial:6.2f} s = {runs / t_serial:7.1f} runs/s "
          f"(CPU per run: solver {cpu / runs * 1e3:.2f} ms, whole task {task / runs * 1e3:.2f} ms)")

    start = time.perf_counter()
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        t_up = time.perf_counter() - start
        mo2d.sweep(SCENE, {"a": [0.1]}, client=client)  # workers import mo2d once
        start = time.perf_counter()
        table = mo2d.sweep(SCENE, grid, client=client)
        t_cluster = time.perf_counter() - start
        start = time.perf_counter()
        batched = mo2d.sweep(SCENE, grid, client=client, batch=20)
        t_batched = time.perf_counter() - start
    assert table["ok"].all()
    task_c = table["task_cpu_seconds"].sum()
    assert (table["peak.crank_pivot.torque"].to_numpy()
            == serial["peak.crank_pivot.torque"].to_numpy()).all()
    ideal = runs / t_serial * workers
    print(f"LocalCluster({workers}): {runs} runs in {t_cluster:6.2f} s = "
          f"{runs / t_cluster:7.1f} runs/s (cluster start {t_up:.2f} s not counted); "
          f"speed-up {t_serial / t_cluster:.2f}x, ideal {workers}x = {ideal:.1f} runs/s; "
          f"CPU per run in the workers {task_c / runs * 1e3:.2f} ms")
    assert batched["ok"].all()
    print(f"LocalCluster({workers}), 20 runs per task: {runs / t_batched:7.1f} runs/s, "
          f"speed-up {t_serial / t_batched:.2f}x")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main(*map(int, sys.argv[1:3]))
