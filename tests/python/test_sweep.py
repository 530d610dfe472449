"""Sweeps on a local Dask cluster of 2 worker processes: one row per run, failures as rows."""
import math

import pytest

import mo2d
from mo2d import _sweep


def test_parse_values():
    assert _sweep.parse_values("1:2:3") == [1.0, 1.5, 2.0]
    assert _sweep.parse_values("0.5,1") == [0.5, 1.0]
    assert _sweep.parse_values("2*L") == ["2*L"]
    with pytest.raises(ValueError):
        _sweep.parse_values("1:2")


def test_grid_order():
    assert _sweep.grid({"a": [1, 2], "b": [3, 4]}) == [
        {"a": 1, "b": 3}, {"a": 1, "b": 4}, {"a": 2, "b": 3}, {"a": 2, "b": 4}]


# a lambda: cloudpickle sends it by value (the workers cannot import this test module)
peak_angle = lambda r: {"max_angle": float(max(abs(r["link.angle"])))}  # noqa: E731


def test_sweep_on_a_local_cluster_of_two_workers(mechanisms):
    pytest.importorskip("distributed")
    from dask.distributed import Client, LocalCluster

    # m = -1 is refused by build_model: a failed row, the sweep goes on
    grid = {"m": [1.0, 2.0, -1.0], "L": [0.5, 1.0]}
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        table = mo2d.sweep(mechanisms / "pendulum.yaml", grid, summary=peak_angle, client=client)
        assert len(client.scheduler_info()["workers"]) == 2
        batched = mo2d.sweep(mechanisms / "pendulum.yaml", grid, client=client, batch=4)
    serial = mo2d.sweep(mechanisms / "pendulum.yaml", grid, summary=peak_angle, serial=True)
    rows = table.to_dict("records") if hasattr(table, "to_dict") else table
    assert [(r["m"], r["L"]) for r in rows] == [(m, L) for m in grid["m"] for L in grid["L"]]
    for r, s in zip(rows, serial.to_dict("records")):
        if r["m"] < 0:
            assert not r["ok"] and "mass" in r["error"], r["error"]
            continue
        assert r["ok"], r["error"]
        # the closed form bounds the peak: |tau| <= m L^2 max|theta''| + m g L
        assert 0 < r["peak.pivot.torque"] <= r["m"] * r["L"] ** 2 * 6.5 + r["m"] * 9.81 * r["L"]
        assert r["peak.pivot.torque"] == s["peak.pivot.torque"]  # same numbers as in-process
        assert r["max.residual.position"] < 1e-9
        assert r["max_angle"] == pytest.approx(4 + 0.5 * math.sin(6), rel=1e-12)
        assert r["cpu_seconds"] > 0 and r["solve"] == "inverse"
    assert list(batched["peak.pivot.torque"].fillna(-1)) == list(
        table["peak.pivot.torque"].fillna(-1))  # batches of 4 runs per task: the same rows
    assert list(batched["ok"]) == list(table["ok"])
    # the torque scales with m at fixed L: rows (1, L) and (2, L)
    assert rows[2]["peak.pivot.torque"] == pytest.approx(2 * rows[0]["peak.pivot.torque"])


def test_samples_and_a_failing_expression(mechanisms):
    rows = mo2d.sweep(mechanisms / "pendulum.yaml", [{"m": 1.0}, {"m": "nope + 1"}],
                      serial=True).to_dict("records")
    assert rows[0]["ok"] and not rows[1]["ok"]
    assert "nope" in rows[1]["error"]
    assert math.isnan(rows[1]["peak.pivot.torque"])


def test_rows_are_reported_as_they_finish_and_big_grids_refused(mechanisms):
    seen = []
    table = mo2d.sweep(mechanisms / "pendulum.yaml", {"m": [1.0, 2.0, -1.0]}, serial=True,
                       on_row=lambda k, row: seen.append((k, row["m"], row["ok"])))
    assert seen == [(0, 1.0, True), (1, 2.0, True), (2, -1.0, False)]
    assert len(table) == 3
    with pytest.raises(ValueError, match="1e\\+09 runs, more than the limit"):
        mo2d.sweep(mechanisms / "pendulum.yaml", {"m": range(1000), "L": range(1000000)})
    with pytest.raises(ValueError, match="more than the limit of 2"):
        mo2d.sweep(mechanisms / "pendulum.yaml", [{"m": 1}] * 3, serial=True, max_runs=2)
