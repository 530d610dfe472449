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


def test_crosscheck_of_a_contact_scene_is_refused(mechanisms):
    """The command runs it (docs/contact.md, "Box2D"); the Python function not yet, and says so
    rather than comparing the scene without its contacts."""
    with pytest.raises(mo2d.Error, match=r"bouncing_ball.yaml:29:3: contact 'floor': Python's "
                       r"mo2d.crosscheck \(the command mo2d crosscheck .* does not take contacts"):
        mo2d.crosscheck(mo2d.load_scene(mechanisms / "bouncing_ball.yaml"))


def test_design_measures_of_a_contact_scene_are_refused(mechanisms):
    """The frame's shaking force and the bearing loads read the joints' reactions, not the
    contact forces: asked for on a contact scene, they are an error, not a result without them."""
    for name, run in (("bouncing_ball.yaml", mo2d.forward), ("cam_follower.yaml", mo2d.inverse)):
        with pytest.raises(mo2d.Error, match=r"contact '.*': the designer's measures"):
            run(mo2d.load_scene(mechanisms / name), measures=True)


def test_inverse_holds_the_cam_follower_on_its_cam(mechanisms):
    """Inverse dynamics with the contact held closed (docs/contact.md, "Inverse dynamics"): the
    contact force N = m g + P0 + ecc (k - m w^2) sin(w t) (the scene's header), positive below
    the critical speed (no warning), negative from the forward run's lift-off time above it."""
    m, k, ecc, P0, g = 0.5, 2000.0, 0.01, 10.0, 9.81  # the scene's parameters
    for w in (80.0, 100.0):
        r = mo2d.inverse(mo2d.load_scene(mechanisms / "cam_follower.yaml", set={"omega": w}))
        c = r.contacts["cam"]
        assert c["held"] and c["column"] == "cam.normal_force"
        t = r["t"]
        scale = m * g + P0 + ecc * abs(k - m * w * w)
        for x, n in zip(t, r["cam.normal_force"]):
            assert n == pytest.approx(m * g + P0 + ecc * (k - m * w * w) * math.sin(w * x),
                                      abs=1e-9 * scale), x
        assert c["min_force"] == pytest.approx(m * g + P0 - ecc * (m * w * w - k),
                                               abs=1e-9 * scale)
        warned = [x for x in r.warnings if "contact 'cam'" in x]
        if w == 80.0:
            assert c["min_force"] > 0 and c["t_negative"] is None and c["preload"] == 0 and not warned
        else:
            lift = math.asin((m * g + P0) / (ecc * (m * w * w - k))) / w
            assert c["t_negative"] == pytest.approx(lift, rel=1e-9)
            assert c["preload"] == pytest.approx(-c["min_force"], abs=0)
            assert len(warned) == 1 and "negative (pulling) contact force" in warned[0]


def test_rocking_block_pivots_with_housners_ratio(mechanisms):
    """mechanisms/rocking_block.yaml (friction: mu on both corners): each impact's landing speed
    is r = 1 - (3/2) sin^2(alpha) times the one before (Housner 1963), no corner slides, and the
    scene's friction is in the contact's summary."""
    r = mo2d.forward(mo2d.load_scene(mechanisms / "rocking_block.yaml"))
    b, h = 0.1, 0.3  # the scene's parameters
    ratio = 1 - 1.5 * math.sin(math.atan(b / h)) ** 2
    hits = [x for x in r.events if x["kind"] == "impact"]
    assert len(hits) == 10
    assert [x["contact"] for x in hits[:2]] == ["cornerA", "cornerB"]
    for a, c in zip(hits, hits[1:]):
        assert c["speed"] / a["speed"] == pytest.approx(ratio, abs=1e-9)
    assert not [x for x in r.events if x["kind"] in ("slip", "stick")]


def test_friction_key_in_the_json_summary(mechanisms, mo2d_cli, tmp_path):
    subprocess.run([mo2d_cli, "forward", str(mechanisms / "rocking_block.yaml"), "--out",
                    str(tmp_path)], check=True, capture_output=True)
    summary = json.loads((tmp_path / "rocking_block_forward.json").read_text())
    assert summary["contacts"]["contacts"]["cornerA"] == {"law": "rigid", "restitution": 0.0,
                                                         "friction": 1.0}
