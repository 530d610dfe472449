"""Contact scenes from Python (issue 35): mo2d.forward runs them through the event-driven contact
run, r.events lists the events (dicts), the columns are the CLI's."""
import json
import math
import subprocess

import pytest

import mo2d


def test_bouncing_ball_events_follow_the_closed_forms(mechanisms):
    r = mo2d.forward(mo2d.load_scene(mechanisms / "bouncing_ball.yaml"))
    h, rad, m, e, g = 1.0, 0.05, 0.2, 0.8, 9.81  # the scene's parameters
    impacts = [x for x in r.events if x["kind"] == "impact"]
    assert len(impacts) >= 10
    assert set(impacts[0]) == {"kind", "t", "contact", "speed", "speed_after", "impulse",
                               "energy_lost", "predicted_t"}
    t1 = math.sqrt(2 * (h - rad) / g)
    v1 = g * t1
    t = t1
    for k, x in enumerate(impacts[:10]):
        v = v1 * e**k
        assert x["contact"] == "floor"
        assert x["t"] == pytest.approx(t, abs=1e-9), k
        assert x["speed"] == pytest.approx(v, abs=1e-9 * v1), k
        assert x["speed_after"] == pytest.approx(e * v, abs=1e-9 * v1), k
        assert x["energy_lost"] == pytest.approx((1 - e * e) * m * v * v / 2, abs=1e-9), k
        t += 2 * e * v / g
    zeno = [x for x in r.events if x["kind"] == "zeno"]
    assert len(zeno) == 1
    assert zeno[0]["predicted_t"] == pytest.approx(t1 * (1 + e) / (1 - e), abs=1e-9)
    # the columns: the ball never below the floor by more than the gap tolerance
    y = r["ball.C.y"]
    assert len(y) == 401 and y[0] == 1.0
    assert y.min() > rad - 1e-9


def test_events_are_those_of_the_command_line(mechanisms, mo2d_cli, tmp_path):
    r = mo2d.forward(mo2d.load_scene(mechanisms / "bouncing_ball.yaml"))
    subprocess.run([mo2d_cli, "forward", str(mechanisms / "bouncing_ball.yaml"), "--out",
                    str(tmp_path)], check=True, capture_output=True)
    summary = json.loads((tmp_path / "bouncing_ball_forward.json").read_text())
    cli = summary["contacts"]["events"]
    assert summary["contacts"]["contacts"] == {"floor": {"law": "rigid", "restitution": 0.8}}
    assert len(cli) == len(r.events)
    for a, b in zip(cli, r.events):
        for key in a:  # the JSON leaves out what does not apply to the kind
            assert a[key] == b[key], (key, a, b)


def test_cam_follower_lifts_off_above_the_critical_speed(mechanisms):
    m, k, ecc, P0, g = 0.5, 2000.0, 0.01, 10.0, 9.81  # the scene's parameters
    wc = math.sqrt((P0 + k * ecc + m * g) / (m * ecc))
    below = mo2d.forward(mo2d.load_scene(mechanisms / "cam_follower.yaml",
                                         set={"omega": 0.99 * wc}))
    assert below.events == []
    w = 1.2 * wc
    above = mo2d.forward(mo2d.load_scene(mechanisms / "cam_follower.yaml", set={"omega": w}))
    off = [x for x in above.events if x["kind"] == "lift_off"]
    assert len(off) == 1 and off[0]["contact"] == "cam"
    assert off[0]["t"] == pytest.approx(math.asin((m * g + P0) / (ecc * (m * w * w - k))) / w,
                                        abs=1e-10)


def test_scene_without_contacts_has_no_events(mechanisms):
    r = mo2d.forward(mo2d.load_scene(mechanisms / "mass_spring_mass.yaml"), duration=0.1,
                     samples=3)
    assert r.events == []


def test_inverse_of_a_contact_scene_is_refused(mechanisms):
    with pytest.raises(mo2d.Error, match=r"bouncing_ball.yaml:29:3: contact 'floor': inverse "
                       r"dynamics does not take contacts into account yet"):
        mo2d.inverse(mo2d.load_scene(mechanisms / "bouncing_ball.yaml"))
