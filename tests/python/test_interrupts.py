"""Ctrl-C (SIGINT) stops every run and command at once (issue 31, item 3): a KeyboardInterrupt
within 0.5 s of the signal in Python (scene runs release the GIL, System runs keep it; both poll
the signal every 0.05 s), every CLI command ends by the signal, and an interrupted sweep writes the
rows it had finished. Each test starts a child process, waits until its run has begun, sends
SIGINT and measures the delay until the child reacts (CLOCK_MONOTONIC, shared by the processes)."""
import os
import signal
import subprocess
import sys
import time

import pytest

# The longest a run may take to notice the signal (the bound).
LIMIT = 0.5

CHILD = r"""
import sys, time, mo2d
kind, path = sys.argv[1], sys.argv[2]
scene = mo2d.load_scene(path)
if kind == "scene":
    run = lambda: mo2d.forward(scene, duration=1e5, max_seconds=60)
else:  # a System's run keeps the GIL
    model = scene.build_model()
    s0 = mo2d.consistent_state(model, velocities=[("crank0.w", -1.0)])
    run = lambda: mo2d.forward_dynamics(model, s0, 1e5, integrator="rk4", step=1e-4,
                                        max_seconds=60, max_steps=2**31 - 1)
print("running", flush=True)
try:
    run()
    print("finished", flush=True)
except KeyboardInterrupt:
    print(f"KeyboardInterrupt {time.monotonic()!r}", flush=True)
"""


def _interrupt(cmd, wait=0.7, first_line=False):
    """Start cmd, (first_line: wait for its first line on stdout,) wait `wait` s, send SIGINT;
    return the time it was sent, the time it ended, the process, its stdout and stderr."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    first = p.stdout.readline() if first_line else ""
    time.sleep(wait)
    assert p.poll() is None, f"ended before the signal: {first}{p.stdout.read()}{p.stderr.read()}"
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        pytest.fail(f"still running 30 s after SIGINT: {err}")
    ended = time.monotonic()
    return sent, ended, p, first + out, err


@pytest.mark.parametrize("kind", ["scene", "system"])
def test_keyboard_interrupt_during_a_run(mechanisms, kind):
    sent, _, p, out, err = _interrupt(
        [sys.executable, "-c", CHILD, kind, str(mechanisms / "double_fourbar.yaml")],
        first_line=True)
    lines = [x for x in out.splitlines() if x.startswith("KeyboardInterrupt")]
    assert lines, f"no KeyboardInterrupt: {out} {err}"
    delay = float(lines[0].split()[1]) - sent
    print(f"{kind}: KeyboardInterrupt {delay:.3f} s after SIGINT")
    assert delay < LIMIT, f"KeyboardInterrupt came {delay:.3f} s after SIGINT"


def _chain(tmp_path, n):
    text = "name: chain\nground: {O: [0, 0]}\nbodies:\n"
    joints = "joints:\n"
    for k in range(n):
        text += f"  l{k}: {{nodes: {{A: [0, {-k}], B: [0, {-k - 1}]}}, mass: 1, inertia: 0.1}}\n"
        a = "ground.O" if k == 0 else f"l{k - 1}.B"
        joints += f"  j{k}: {{type: revolute, node_a: {a}, node_b: l{k}.A}}\n"
    path = tmp_path / f"chain{n}.yaml"
    rest = ", ".join(f"l{k}.w: 0" for k in range(n))  # at rest
    path.write_text(text + joints + "loads: {gravity: [0, -9.81]}\n"
                    f"initial: {{velocities: {{{rest}}}}}\nrun: {{solve: forward}}\n")
    return path


def _cli_cases(mechanisms, tmp_path):
    # 300 links: 600 states, a dense linearization of several seconds (150 finished within the
    # second the test waits on a quiet machine)
    chain = _chain(tmp_path, 300)
    return {
        "forward": ["forward", str(mechanisms / "double_fourbar.yaml"), "--duration", "1e5"],
        "inverse": ["inverse", str(mechanisms / "slider_crank.yaml"), "--samples", "3000000",
                    "--duration", "1e4", "--max-memory", "1e11"],
        "crosscheck": ["crosscheck", str(mechanisms / "slider_crank.yaml"), "--step", "1e-6"],
        "modes": ["modes", str(chain), "--no-pictures"],
        "linearize": ["linearize", str(chain)],
    }


@pytest.mark.parametrize("command", ["forward", "inverse", "crosscheck", "modes", "linearize"])
def test_cli_command_ends_at_sigint(mechanisms, mo2d_cli, tmp_path, command):
    args = _cli_cases(mechanisms, tmp_path)[command]
    start = time.monotonic()
    sent, ended, p, out, err = _interrupt(
        [mo2d_cli] + args + ["--out", str(tmp_path / "out")], wait=1.0)
    print(f"{command}: ended {ended - sent:.3f} s after SIGINT (status {p.returncode})")
    assert p.returncode == -signal.SIGINT, (p.returncode, out, err)
    assert ended - sent < LIMIT
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
    assert sent - start > 0.9  # the command was working when it was interrupted


def test_interrupted_sweep_writes_its_finished_rows(mechanisms, mo2d_cli, tmp_path):
    out = tmp_path / "sweep.csv"
    # a serial sweep (--jobs 0) of runs of a few ms: many finish before the signal
    sent, ended, p, stdout, err = _interrupt(
        [mo2d_cli, "sweep", str(mechanisms / "pendulum.yaml"), "--set", "m=1:2:20000",
         "--jobs", "0", "-o", str(out)], wait=2.0)
    print(f"sweep: ended {ended - sent:.3f} s after SIGINT: {err.strip()}")
    assert p.returncode == 130, (stdout, err)
    assert ended - sent < LIMIT
    assert "interrupted" in err and "finished of 20000 runs" in err, err
    rows = out.read_text().splitlines()
    assert rows[0].startswith("m,ok,error") and len(rows) > 2
    assert not os.path.exists(str(out) + ".partial")
