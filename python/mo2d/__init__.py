"""mo2d: dynamics of planar mechanisms in Orsino's nodal formulation (docs/python.md).

Scene files::

    import mo2d
    scene = mo2d.load_scene("mechanisms/fourbar.yaml", set={"a": 0.12})
    r = mo2d.inverse(scene)
    r.t, r["crank_pivot.torque"], r.efforts, r.reactions, r.stats["cpu_seconds"]
    r.to_pandas()                       # when pandas is installed

Run settings as keywords, checked like the command line's: mo2d.forward(scene, duration=2,
integrator="rk4", step=1e-4), mo2d.inverse(scene, samples=1001), load_scene(path, run={...}).

Mechanisms built in Python: mo2d.System, mo2d.build_model, mo2d.inverse_dynamics,
mo2d.forward_dynamics, loads as numbers, expression strings, callables or mo2d.Law(labels, f);
gears, racks, user constraints (expressions), mo2d.pd_control, mo2d.Table / read_table_csv,
mo2d.efforts_from_inverse / efforts_from_samples, mo2d.inverse_dynamics_lagrange,
mo2d.lump_transmission, r.units. An exception raised by a Python law during a
run comes out as itself, with a note (and mo2d_element, mo2d_time) naming the load and the time.

Step by step: mo2d.ForwardWorkspace (accelerations, multipliers, projection, reactions at a
state), mo2d.InverseWorkspace (one sample at a time); mo2d.energy_balance(result).
Parameter sweeps on Dask: mo2d.sweep (mo2d/_sweep.py; command line: python3 -m mo2d sweep). Every error is a mo2d.Error;
an unknown column of a result, r["pivot.torq"], is a mo2d.ColumnError (also a KeyError) naming the
closest one. mo2d.__version__ is the project's version (`mo2d --version`).
"""

import numbers

from . import _mo2d
from . import _runs
from ._runs import forward, inverse  # noqa: F401  (run settings as keywords)
from ._mo2d import (  # noqa: F401  (the public API)
    Equilibrium,
    ColumnError,
    Error,
    Law,
    Mode,
    Model,
    Result,
    Scene,
    State,
    StateSpace,
    System,
    build_model,
    consistent_state,
    crosscheck,
    crosscheck_forward,
    crosscheck_inverse,
    forward_dynamics,
    four_bar,
    inverse_dynamics,
    linearize,
    modes,
    static_equilibrium,
    transmission_angle,
    write_filmstrip,
    write_frame,
    write_plot,
    write_series_plot,
)
from ._mo2d import __version__  # noqa: F401  (project(mo2d VERSION ...) of CMakeLists.txt)
from ._mo2d import (  # noqa: F401  (step by step, energies, tables, controllers, transmissions)
    ForwardWorkspace,
    InverseWorkspace,
    Table,
    efforts_from_inverse,
    efforts_from_samples,
    energy_balance,
    energy_balance_error,
    inverse_dynamics_lagrange,
    kinetic_energy,
    lump_transmission,
    pd_control,
    potential_energy,
    rate_label,
    read_table_csv,
)

__all__ = [
    "ColumnError", "Error", "Law", "Model", "Result", "Scene", "State", "System", "build_model",
    "consistent_state", "crosscheck", "crosscheck_forward", "crosscheck_inverse", "forward",
    "forward_dynamics", "inverse", "inverse_dynamics", "load_scene", "parse_scene", "sweep",
    "Equilibrium", "Mode", "StateSpace", "linearize", "modes", "static_equilibrium",
    "write_filmstrip", "write_frame", "write_plot", "write_series_plot",
    "four_bar", "transmission_angle",
]
if hasattr(_mo2d, "optimize"):  # built with NLopt (libnlopt-dev)
    from ._mo2d import optimize  # noqa: F401
    __all__ += ["optimize"]
__all__ += [
    "ForwardWorkspace", "InverseWorkspace", "Table", "efforts_from_inverse",
    "efforts_from_samples", "energy_balance", "energy_balance_error", "inverse_dynamics_lagrange",
    "kinetic_energy", "lump_transmission", "pd_control", "potential_energy", "rate_label",
    "read_table_csv",
]


def _run_overrides(run):
    """run={"duration": 2} -> [("duration", "2")] (any key of `mo2d inverse` or `forward`)."""
    return _runs.run_overrides(run, _runs.ALL_KEYS)


def _overrides(set):
    """{"m": 2.0, "L": "2*a"} -> [("m", "2.0"), ("L", "2*a")]: numbers in their shortest exact
    form (repr), strings as expressions of the other parameters."""
    if set is None:
        return []
    items = set.items() if hasattr(set, "items") else set
    out = []
    for name, value in items:
        if isinstance(value, str):
            out.append((str(name), value))
        elif isinstance(value, numbers.Real) and not isinstance(value, bool):
            out.append((str(name), repr(float(value))))
        else:
            raise TypeError(f"set: parameter '{name}': a number or a string (an expression of the "
                            f"other parameters), not {type(value).__name__}")
    return out


def load_scene(path, set=None, run=None):
    """Read and check a scene file (docs/scene-format.md); returns a mo2d.Scene.

    path: the file (str or path-like). set={"name": value} overrides its parameters like
    `mo2d inverse --set name=value`: a number, or a string, an expression of the other
    parameters. run={"duration": 2} overrides its run settings like `--duration 2` (any key of
    `mo2d inverse` or `mo2d forward`: t0, duration, samples, integrator, rtol, ...). Raises
    mo2d.Error naming file:line:column (or the flag: "--duration: ..."), TypeError for a
    value of set= that is neither a number nor a string.

    Example::

        scene = mo2d.load_scene("mechanisms/fourbar.yaml", set={"a": 0.12, "b": "3.5 * a"})
        r = mo2d.inverse(scene)
    """
    return _mo2d._load_scene(str(path), _overrides(set), _run_overrides(run))


def parse_scene(text, file_name="<scene>", set=None, run=None):
    """A mo2d.Scene from YAML text instead of a file (as load_scene reads one).

    text: a str, or bytes (UTF-8, or UTF-16/32 with a byte order mark); file_name: the name
    errors give (file_name:line:column); set=, run=: as in load_scene. Raises mo2d.Error, or
    TypeError for text that is neither str nor bytes.

    Example::

        scene = mo2d.parse_scene(open("mechanisms/pendulum.yaml").read(), "pendulum.yaml")
    """
    if isinstance(text, (bytes, bytearray, memoryview)):
        text = bytes(text)
    elif not isinstance(text, str):
        raise TypeError(f"parse_scene: the text of a scene (str), not {type(text).__name__}; "
                        "a file: mo2d.load_scene(path)")
    return _mo2d._parse_scene(text, file_name, _overrides(set), _run_overrides(run))


def _to_pandas(self):
    """The result as a pandas DataFrame, one column per label of r.columns (the CSV's), one
    row per sample; needs pandas (python3-pandas)."""
    import pandas

    return pandas.DataFrame({label: self[label] for label in self.columns})


Result.to_pandas = _to_pandas


def sweep(scene, grid_or_samples, solve=None, summary=None, client=None, **kwargs):
    """Run a scene file for many parameter sets on Dask, one model per task (docs/sweeps.md).

    scene: the scene file's path; grid_or_samples: {"m": [1, 2], "L": [0.5, 1]} (every
    combination) or a list of dicts (one run each); solve: "inverse" or "forward" (default:
    the scene's); client: a dask.distributed Client (default: a LocalCluster for the call).
    Returns a pandas DataFrame (a list of dicts without pandas), one row per run: its
    parameters, ok, error (the message of a failed run), the peaks of the efforts, the largest
    residuals, the CPU time; see mo2d._sweep.sweep for the other arguments (jobs, batch,
    on_row, max_runs, ...).

    Example::

        rows = mo2d.sweep("mechanisms/pendulum.yaml", {"m": [1, 2], "L": [0.5, 1]})
    """
    from ._sweep import sweep as _sweep  # imports dask only when a sweep runs

    return _sweep(scene, grid_or_samples, solve=solve, summary=summary, client=client, **kwargs)
