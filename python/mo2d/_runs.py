"""Runs of a scene with run settings given in Python (docs/python.md, "Run settings").

mo2d.forward(scene, duration=2, integrator="rk4") is `mo2d forward SCENE --duration 2
--integrator rk4`: each setting is a key of the scene's run: block that the command line may
override (mo2d/scene.hpp, RunOverride), passed as the text the command line would pass and applied
by the scene parser on top of the scene's own run: block, so every value goes through the same
checks and a refusal is the same mo2d.Error ("--duration: run.duration: must be > 0 s"). A
setting left at None keeps the scene's value.
"""

import numbers

from . import _mo2d

# The keys `mo2d inverse` and `mo2d forward` take (apps/scene_options.cpp, RunFlags).
BUDGET_KEYS = ("max_steps", "max_seconds", "max_memory")
INVERSE_KEYS = ("t0", "duration", "samples", "tolerance") + BUDGET_KEYS
FORWARD_KEYS = ("t0", "duration", "samples", "integrator", "formulation", "rtol", "atol",
                "step", "accuracy", "error_estimate") + BUDGET_KEYS
ALL_KEYS = tuple(dict.fromkeys(INVERSE_KEYS + FORWARD_KEYS))


def _text(key, value):
    """A run setting as the command line writes it: an int as is, a float in its shortest exact
    form, a string as it is (a name, or an expression of the parameters)."""
    if isinstance(value, bool):
        raise TypeError(f"run setting {key}: a number or a string, not a bool")
    if isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    raise TypeError(f"run setting {key}: a number or a string, not {type(value).__name__}")


def run_overrides(settings, keys=None):
    """{"duration": 2.0, "step": None} -> [("duration", "2.0")] (None: not given), in order;
    keys: the keys allowed (a ValueError names any other)."""
    if settings is None:
        return []
    items = settings.items() if hasattr(settings, "items") else settings
    out = []
    for key, value in items:
        if keys is not None and key not in keys:
            raise ValueError(f"'{key}' is not a run setting of this run (one of {', '.join(keys)})")
        if value is not None:
            out.append((str(key), _text(key, value)))
    return out


def _with(scene, settings, keys):
    run = run_overrides(settings, keys)
    return scene.with_run(run) if run else scene


def inverse(scene, *, t0=None, duration=None, samples=None, tolerance=None, max_steps=None,
            max_seconds=None, max_memory=None, measures=False, sensitivity=None):
    """Inverse dynamics of a scene, as `mo2d inverse` runs it (no files written).

    scene: a mo2d.Scene (mo2d.load_scene). The run settings given replace the scene's run:
    block for this run, as the command line's flags do (`mo2d inverse --duration ...`): t0
    (s), duration (s; the run ends at t0 + duration), samples, tolerance (the position
    tolerance, relative to the mechanism's size), max_steps, max_seconds (s), max_memory
    (bytes). A number is passed as the command line would pass it, a string as an expression
    of the parameters (duration="2 * T"); None keeps the scene's. Returns a mo2d.Result;
    raises mo2d.Error naming the flag for a bad setting ("--duration: run.duration: must be >
    0 s"), and naming the time and the element for a failed run. Releases the GIL.
    measures=True adds the designer's measures as `mo2d inverse --measures` does (the frame's
    shaking force and moment, every joint's bearing load; the scene's design: block adds its
    own either way): columns r["frame.shaking.Fx"], ..., and the summary r.design
    (docs/design.md).
    sensitivity: names of the scene's parameters (a list, or one string "m1,k"), as `mo2d inverse
    --sensitivity`: adds the exact derivative of every effort and reaction column to each,
    r["d(crank_pivot.torque)/d(m1)"] (docs/design.md, "Sensitivities"). Only parameters that set
    mass data and load coefficients; one that changes the geometry or the motion raises
    mo2d.Error naming it and what it changes.

    Example::

        r = mo2d.inverse(mo2d.load_scene("mechanisms/fourbar.yaml"), samples=1001)
        r["crank_pivot.torque"]
    """
    settings = dict(t0=t0, duration=duration, samples=samples, tolerance=tolerance,
                    max_steps=max_steps, max_seconds=max_seconds, max_memory=max_memory)
    if sensitivity is None:
        sensitivity = []
    elif isinstance(sensitivity, str):
        sensitivity = [n.strip() for n in sensitivity.split(",") if n.strip()]
    return _mo2d._inverse(_with(scene, settings, INVERSE_KEYS), measures, list(sensitivity))


def forward(scene, *, t0=None, duration=None, samples=None, integrator=None, formulation=None,
            rtol=None, atol=None, step=None, max_steps=None, max_seconds=None, max_memory=None,
            accuracy=None, error_estimate=None, measures=False):
    """Forward dynamics of a scene from its initial state, as `mo2d forward` runs it.

    scene: a mo2d.Scene. The run settings given replace the scene's for this run, as the
    command line's flags (`mo2d forward --integrator rk4 --step 1e-4 ...`): t0 (s), duration
    (s; the run ends at t0 + duration), samples, integrator ("cvode_bdf", "cvode_adams",
    "rk4", "dopri5", "erk6", "erk8", "baumgarte"), formulation, rtol, atol, step (s),
    accuracy=1e-6 (mo2d picks the integrator and its tolerances, `--accuracy`),
    error_estimate="on" | "off" | "automatic" (the a-posteriori estimate of the global error,
    r.stats["estimated_error"]), and the budgets max_steps, max_seconds (s), max_memory
    (bytes). None keeps the scene's. Returns a mo2d.Result with the energies; raises
    mo2d.Error naming the flag for a bad setting, the time and the variable for a failed
    run. Releases the GIL. measures=True: the designer's measures, as for mo2d.inverse.

    Example::

        f = mo2d.forward(mo2d.load_scene("mechanisms/double_fourbar.yaml"), duration=0.5,
                         integrator="rk4", step=1e-4)
        f["energy.kinetic"], f.stats["steps"]
    """
    settings = dict(t0=t0, duration=duration, samples=samples, integrator=integrator,
                    formulation=formulation, rtol=rtol, atol=atol, step=step, accuracy=accuracy,
                    error_estimate=error_estimate, max_steps=max_steps, max_seconds=max_seconds, max_memory=max_memory)
    return _mo2d._forward(_with(scene, settings, FORWARD_KEYS), measures)
