"""python3 -m mo2d sweep SCENE --set m=1:2:11 --set L=0.5,1 [--scheduler ADDRESS] [--jobs N]
[--solve inverse|forward] [-o OUT.csv]: the command line of mo2d.sweep (docs/sweeps.md).

`mo2d sweep ...` (the C++ tool) runs this with the python3 and the package path its build knows.
Exit status: 0 when every run succeeded, 3 when some failed (their rows carry the message), 2 for a
usage error, 130 when interrupted (Ctrl-C: the finished rows are written), 1 for any other error.
"""

import argparse
import json
import os
import sys
import time


def _parser():
    p = argparse.ArgumentParser(
        prog="mo2d sweep",
        description="Solve a scene file for every combination of parameter values on Dask and "
        "write one CSV row per run (parameters, peak efforts, residuals, CPU time, errors).")
    p.add_argument("scene", metavar="SCENE", help="scene file (docs/scene-format.md)")
    p.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUES",
                   help="values of a parameter: start:stop:count (count values, ends included), "
                   "v1,v2,... or one value (an expression of the other parameters allowed); "
                   "repeatable, the sweep is every combination")
    p.add_argument("--solve", choices=["inverse", "forward"], default=None,
                   help="default: the scene's run.solve")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="a running Dask scheduler (tcp://host:8786); default: a local cluster")
    p.add_argument("--jobs", type=int, default=None, metavar="N",
                   help="worker processes of the local cluster (default: one per core); with "
                   "--jobs 0 the runs are a serial loop in this process")
    p.add_argument("--batch", type=int, default=1, metavar="K",
                   help="runs per Dask task (default 1; runs of a few ms go faster in batches)")
    p.add_argument("-o", "--output", default=None, metavar="OUT.csv",
                   help="output CSV (default: NAME_sweep.csv, NAME the scene's name; a folder: "
                   "NAME_sweep.csv in it); each run's row is saved as it finishes, so an "
                   "interrupt (Ctrl-C) or a late error loses none")
    p.add_argument("--max-runs", type=int, default=None, metavar="N",
                   help="refuse a sweep of more runs, before any (default 1000000)")
    return p


class _RowSaver:
    """The rows of a sweep as they finish: kept in memory and appended, one JSON object per line
    ({"index": k, ...the row}), to OUT.partial, opened before the first run (an output path that
    cannot be written fails at once). At the end the CSV is written and OUT.partial removed; after
    an interrupt or an error the CSV of the finished rows is written instead, and OUT.partial is
    kept only if even that fails."""

    def __init__(self, output):
        self.output = output
        self.partial = output + ".partial"
        self.rows = {}
        self.file = open(self.partial, "w", encoding="utf-8")

    def __call__(self, index, row):
        self.rows[index] = row
        self.file.write(json.dumps({"index": index, **row}, default=str) + "\n")
        self.file.flush()

    def finish(self, table):
        from . import _sweep

        self.file.close()
        _sweep.rows_to_csv(table, self.output)
        os.remove(self.partial)

    def salvage(self, names, runs):
        """After an interrupt or an error: the CSV of the finished rows (in the order of the
        parameter sets); what was written, for the message."""
        from . import _sweep

        self.file.close()
        if not self.rows:
            os.remove(self.partial)
            return f"no run had finished, nothing written (of {runs} runs)"
        try:
            # the plain rows (no pandas to import: an interrupt should end at once)
            _sweep.rows_to_csv([self.rows[k] for k in sorted(self.rows)], self.output, names)
        except Exception as e:
            return f"could not write {self.output} ({e}); the finished rows are in {self.partial}"
        os.remove(self.partial)
        return (f"wrote the {len(self.rows)} finished of {runs} runs to "
                f"{os.path.abspath(self.output)}")


def _output_path(args, name):
    """-o as given (a folder: NAME_sweep.csv in it), or NAME_sweep.csv."""
    output = args.output or f"{name}_sweep.csv"
    if os.path.isdir(output):
        output = os.path.join(output, f"{name}_sweep.csv")
    return output


def sweep_main(argv):
    args = _parser().parse_args(argv)
    from . import _sweep, load_scene, Error

    max_runs = _sweep.MAX_RUNS if args.max_runs is None else args.max_runs
    if max_runs < 1:
        _parser().error("--max-runs must be >= 1")
    axes = {}
    for s in args.sets:
        name, eq, values = s.partition("=")
        if not eq or not name.strip():
            _parser().error(f"--set {s}: expected NAME=VALUES")
        try:
            axes[name.strip()] = _sweep.parse_values(values.strip(), max_runs)
        except ValueError as e:
            _parser().error(f"--set {s}: {e}")
    if args.jobs is not None and args.jobs < 0:
        _parser().error("--jobs must be >= 0")
    if args.batch < 1:
        _parser().error("--batch must be >= 1")
    try:
        samples = _sweep.grid(axes, max_runs)
    except ValueError as e:
        _parser().error(str(e))
    try:
        scene = load_scene(args.scene)  # a scene that cannot be read: one error, no sweep
    except Error as e:
        print(f"mo2d: error: {e}", file=sys.stderr)
        return 1
    for n in axes:  # a misspelt name would fail every run: a usage error instead
        if n not in scene.parameters:
            known = ", ".join(scene.parameters) or "none"
            _parser().error(f"--set {n}: not a parameter of {args.scene} (its parameters: "
                            f"{known})")
    name = scene.name
    output = _output_path(args, name)
    try:  # before the first run: an unreachable scheduler, an output path that cannot be written
        if args.scheduler:
            _sweep.check_scheduler(args.scheduler)
        saver = _RowSaver(output)
    except ValueError as e:
        print(f"mo2d: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:
        print(f"mo2d: error: -o {output}: cannot write there ({e.strerror or e})", file=sys.stderr)
        return 1
    start = time.perf_counter()
    try:
        table = _sweep.sweep(args.scene, samples, solve=args.solve, jobs=args.jobs or None,
                             scheduler=args.scheduler, serial=args.jobs == 0, batch=args.batch,
                             on_row=saver, max_runs=max_runs)
    except BaseException as e:  # an interrupt or an error: the finished rows are written
        kept = saver.salvage(list(axes), len(samples))
        if isinstance(e, KeyboardInterrupt):
            print(f"mo2d sweep: interrupted after {time.perf_counter() - start:.3g} s; {kept}",
                  file=sys.stderr)
            return 130
        print(f"mo2d sweep: {type(e).__name__}: {e}; {kept}", file=sys.stderr)
        raise
    seconds = time.perf_counter() - start
    saver.finish(table)
    rows = table.to_dict("records") if hasattr(table, "to_dict") else table
    failed = sum(1 for r in rows if not r["ok"])
    print(f"mo2d sweep: {name}: {len(rows)} runs, {failed} failed, {seconds:.3g} s "
          f"({len(rows) / seconds:.3g} runs/s)")
    for r in rows:
        if not r["ok"]:
            print(f"  failed: {r['error']}", file=sys.stderr)
            break
    print(f"  wrote {os.path.abspath(output)}")
    return 3 if failed else 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help"):
        print("usage: python3 -m mo2d sweep SCENE --set NAME=VALUES... (python3 -m mo2d sweep "
              "--help)")
        return 0 if argv else 2
    if argv[0] != "sweep":
        print(f"mo2d: error: unknown command '{argv[0]}' (the Python entry has: sweep)",
              file=sys.stderr)
        return 2
    return sweep_main(argv[1:])


if __name__ == "__main__":
    sys.exit(main())
