"""Parameter sweeps of a scene file on Dask (docs/sweeps.md).

One task per run: the task loads the scene with its parameter overrides, builds the model and
solves it, and returns one row (parameters, peaks of the efforts, largest residuals, CPU time, and
the error message if the run failed). A failed run, even one that kills its worker process, is a
row with its message: it never stops the sweep.

Without a client the sweep starts a dask.distributed LocalCluster, one single-threaded worker
process per core, and closes it at the end; with client=Client("tcp://scheduler:8786") the same
call runs on that cluster (the workers must import mo2d and read the scene file at the same path).
"""

import itertools
import math
import os
import socket
import time
import urllib.parse

__all__ = ["sweep", "grid", "parse_values", "rows_to_csv", "check_scheduler", "MAX_RUNS"]

# The most runs one sweep may have (max_runs, `mo2d sweep --max-runs`): its rows come back to the
# client and a grid is a list of dicts, so a grid of 1e9 values would exhaust the memory after
# minutes; it is refused before anything runs.
MAX_RUNS = 1_000_000


def _too_many(count, what, max_runs):
    return ValueError(f"sweep: {what} {count:.6g} runs, more than the limit of {max_runs} "
                      f"(max_runs, mo2d sweep --max-runs): use fewer values, or split the sweep")


def grid(axes, max_runs=MAX_RUNS):
    """{"m": [1, 2], "L": [0.5, 1]} -> the Cartesian product as a list of dicts, the last axis
    varying fastest. More than max_runs combinations: ValueError, before any is made."""
    names = list(axes)
    for name in names:
        if len(axes[name]) == 0:
            raise ValueError(f"sweep: parameter '{name}' has no values")
    count = math.prod(len(axes[n]) for n in names)
    if max_runs and count > max_runs:
        sizes = " x ".join(f"{len(axes[n])} ({n})" for n in names)
        raise _too_many(count, f"the grid {sizes} has", max_runs)
    return [dict(zip(names, values)) for values in itertools.product(*(axes[n] for n in names))]


def parse_values(text, max_runs=MAX_RUNS):
    """The values of one --set of `mo2d sweep`: "a:b:n" (n values from a to b, ends included),
    "v1,v2,..." (a list) or one value. Numbers are floats; a value that is not a number is kept as
    an expression of the other parameters (as `mo2d inverse --set` takes it). A count above
    max_runs is refused before the values are made."""
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise ValueError(f"'{text}': a range is start:stop:count")
        a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
        if n < 1:
            raise ValueError(f"'{text}': the count must be at least 1")
        if max_runs and n > max_runs:
            raise _too_many(n, f"'{text}' alone has", max_runs)
        if n == 1:
            return [a]
        return [a + (b - a) * k / (n - 1) for k in range(n)]
    out = []
    for item in text.split(","):
        item = item.strip()
        if not item:
            raise ValueError(f"'{text}': empty value")
        try:
            out.append(float(item))
        except ValueError:
            out.append(item)  # an expression
    return out


def _samples(grid_or_samples, max_runs=MAX_RUNS):
    """A dict of value lists (a grid), a list of dicts (samples) or a pandas DataFrame (one run
    per row) -> list of dicts (at most max_runs: ValueError)."""
    if hasattr(grid_or_samples, "to_dict") and hasattr(grid_or_samples, "columns"):
        samples = grid_or_samples.to_dict("records")
    elif isinstance(grid_or_samples, dict):
        return grid({k: list(v) if _is_seq(v) else [v] for k, v in grid_or_samples.items()},
                    max_runs)
    else:
        samples = [dict(s) for s in grid_or_samples]
    if max_runs and len(samples) > max_runs:
        raise _too_many(len(samples), "the samples are", max_runs)
    return samples


def check_scheduler(address, timeout=3.0):
    """Refuse a Dask scheduler address that cannot be reached within `timeout` seconds (a TCP
    connection to its host and port), with a ValueError naming it and why: before any run, instead
    of dask's traceback after its 30 s connection timeout."""
    url = urllib.parse.urlparse(address if "://" in address else "tcp://" + address)
    try:
        host, port = url.hostname, url.port or 8786
    except ValueError as e:  # a port that is not a number
        raise ValueError(f"--scheduler {address}: not an address tcp://HOST:PORT ({e})") from None
    if url.scheme not in ("tcp", "tls") or not host:
        raise ValueError(f"--scheduler {address}: not an address tcp://HOST:PORT")
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except OSError as e:
        raise ValueError(f"--scheduler {address}: cannot reach the Dask scheduler at {host}:{port} "
                         f"within {timeout:g} s ({e.strerror or e}); is `dask scheduler` running "
                         f"there?") from None


def _is_seq(v):
    return not isinstance(v, str) and hasattr(v, "__len__")


def _peaks(matrix):
    """max |value| of every column (samples x columns), as floats."""
    import numpy

    if matrix.shape[0] == 0:
        return numpy.zeros(matrix.shape[1])
    return numpy.abs(matrix).max(axis=0)


def run_one(scene_path, params, solve=None, summary=None):
    """One run of the sweep (a Dask task; also the serial loop): a dict with the parameters,
    ok, error, element, cpu_seconds (the solver's), wall_seconds and task_cpu_seconds (the whole
    task: load, build, run, this row), peak.<effort label>, peak.reaction (largest
    |reaction component| and its label), max.<residual label>, warnings and the summary's
    entries."""
    import mo2d  # in the worker process

    row = dict(params)
    row.update(ok=False, error="", element="")
    start, cpu = time.perf_counter(), time.process_time()
    try:
        scene = mo2d.load_scene(scene_path, set=params)
        kind = solve or scene.solve
        if kind not in ("inverse", "forward"):
            raise ValueError(f"solve: 'inverse' or 'forward', not '{kind}'")
        r = mo2d.inverse(scene) if kind == "inverse" else mo2d.forward(scene)
        row["solve"] = kind
        row["cpu_seconds"] = r.cpu_seconds
        # each property is a copy of a matrix: read once, peaks with NumPy
        for label, peak in zip(r.effort_labels, _peaks(r.efforts)):
            row["peak." + label] = float(peak)
        reactions = _peaks(r.reactions)
        if len(reactions):
            k = int(reactions.argmax())
            row["peak.reaction"] = float(reactions[k])
            row["peak.reaction.label"] = r.reaction_labels[k]
        for label, peak in zip(r.residual_labels, _peaks(r.residuals)):
            row["max." + label] = float(peak)
        row["warnings"] = len(r.warnings)
        if summary is not None:
            row.update(summary(r))
        row["ok"] = True
    except mo2d.Error as e:
        row["error"] = str(e)
        row["element"] = e.element
    except Exception as e:  # a failed run is a row, never the end of the sweep
        row["error"] = f"{type(e).__name__}: {e}"
    row["wall_seconds"] = time.perf_counter() - start
    row["task_cpu_seconds"] = time.process_time() - cpu
    return row


def run_batch(scene_path, samples, solve=None, summary=None):
    """Several runs in one task (sweep's batch > 1): their rows, in order."""
    return [run_one(scene_path, s, solve, summary) for s in samples]


def _failed(params, message):
    row = dict(params)
    row.update(ok=False, error=message, element="")
    return row


def _column_order(rows, names):
    """Parameters first, then ok/error, then the rest in order of first appearance."""
    first = list(names) + ["ok", "error", "element", "solve", "cpu_seconds", "wall_seconds",
                           "task_cpu_seconds"]
    seen = list(first)
    for r in rows:
        for k in r:
            if k not in seen:
                seen.append(k)
    return seen


def _table(rows, names):
    columns = _column_order(rows, names)
    try:
        import pandas
    except ImportError:
        return [{c: r.get(c, None) for c in columns} for r in rows]
    return pandas.DataFrame([{c: r.get(c, math.nan) for c in columns} for r in rows],
                            columns=columns)


def sweep(scene, grid_or_samples, solve=None, summary=None, client=None, jobs=None,
          scheduler=None, serial=False, batch=1, on_row=None, max_runs=MAX_RUNS):
    """Solve the scene file `scene` for every parameter set and return one row per run.

    grid_or_samples: {"m": [1, 2], "L": [0.5, 1]} (every combination), a list of dicts
        ([{"m": 1.2, "L": 0.7}, ...], e.g. Monte Carlo samples) or a pandas DataFrame (one run per
        row). Values are numbers or expressions of the scene's other parameters.
    solve: "inverse", "forward" or None (the scene's run.solve).
    summary: None, or a function of the mo2d.Result returning a dict of extra columns (runs on
        the worker, so it must be picklable by cloudpickle: a lambda or a module function).
    client: a dask.distributed.Client; None: a LocalCluster of `jobs` single-threaded worker
        processes (default: one per core), or the scheduler at `scheduler` ("tcp://host:8786").
    serial: run in this process without Dask (the reference loop of docs/sweeps.md).
    batch: runs per task (default 1: one model per task). Runs of a few milliseconds are cheaper
        in batches (docs/sweeps.md: Dask's cost per task); a batch whose worker dies reports all
        its runs as failed.
    on_row: None, or a function on_row(index, row) called in this process as each run finishes
        (index: its position among the parameter sets), e.g. to save the rows as they come so
        that an interrupt (KeyboardInterrupt, which cancels the remaining runs) or a late error
        loses none.
    max_runs: more parameter sets than this is a ValueError before any run (0: no limit).

    Returns a pandas DataFrame (a list of dicts without pandas), rows in the order of the
    parameter sets: the parameters, ok, error (the mo2d.Error message of a failed run), element,
    solve, cpu_seconds (the solver's CPU time), wall_seconds and task_cpu_seconds (the whole task:
    load, build, run), peak.<effort label> (max |effort|), peak.reaction and
    peak.reaction.label (largest |reaction component|), max.<residual label>, warnings (count)
    and the summary's columns.
    """
    samples = _samples(grid_or_samples, max_runs)
    names = []
    for s in samples:
        for k in s:
            if k not in names:
                names.append(k)
    scene = os.path.abspath(str(scene))
    if batch < 1:
        raise ValueError("sweep: batch must be at least 1")
    if serial:
        rows = []
        for k, s in enumerate(samples):
            rows.append(run_one(scene, s, solve, summary))
            if on_row is not None:
                on_row(k, rows[-1])
        return _table(rows, names)

    from dask.distributed import Client, LocalCluster, as_completed

    own = []  # what this call started, closed at the end
    futures = []
    try:
        if client is None:
            if scheduler:
                check_scheduler(scheduler)
                client = Client(scheduler, timeout=10)
            else:
                n = jobs or os.cpu_count() or 1
                cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
                own.append(cluster)
                client = Client(cluster)
            own.insert(0, client)
        chunks = [samples[k:k + batch] for k in range(0, len(samples), batch)]
        # pure=False: a run is not cached by its arguments; retries=0: a killed worker's run is
        # reported, not retried on every other worker
        futures = [client.submit(run_batch, scene, c, solve, summary, pure=False, retries=0)
                   for c in chunks]
        first = {f.key: k * batch for k, f in enumerate(futures)}  # index of a chunk's first run
        done = [None] * len(chunks)
        for f in as_completed(futures):  # as they finish (waits 0.1 s at a time: interruptible)
            start = first[f.key]
            c = chunks[start // batch]
            try:
                batch_rows = f.result()
            except Exception as e:  # the worker died (KilledWorker) or the task could not run
                batch_rows = [_failed(s, f"{type(e).__name__}: {e}") for s in c]
            done[start // batch] = batch_rows
            if on_row is not None:
                for k, row in enumerate(batch_rows):
                    on_row(start + k, row)
        return _table([row for rows in done for row in rows], names)
    except BaseException:  # an interrupt or a late error: the runs not finished are cancelled
        if futures and client is not None:
            try:
                client.cancel(futures)
            except Exception:
                pass
        raise
    finally:
        for x in own:
            x.close()


def rows_to_csv(table, path, names=()):
    """Write a sweep's table as CSV, atomically (a temporary file renamed over `path`); a list of
    rows has the parameters `names` first (as sweep's table)."""
    import csv

    if hasattr(table, "to_dict"):
        columns = list(table.columns)
        rows = table.to_dict("records")
    else:
        rows = list(table)
        columns = _column_order(rows, names)
    tmp = f"{path}.tmp{os.getpid()}"
    try:
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(columns)
            for r in rows:
                w.writerow([_cell(r.get(c)) for c in columns])
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def _cell(v):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return ""
    if isinstance(v, float):
        return repr(v)
    return v
