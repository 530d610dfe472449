"""The viewer page and pictures from Python and in notebooks: a Result displays as the viewer page
(_repr_html_: the page in an iframe's srcdoc), a System and a Model as the SVG drawing of their
initial configuration (_repr_svg_). The page in a browser: tests/view/browser_test.py."""
import html
import json
import re

import pytest

import mo2d


@pytest.fixture(scope="module")
def result():
    from conftest import MECHANISMS
    return mo2d.inverse(mo2d.load_scene(MECHANISMS / "fourbar.yaml", set={}))


def page_data(page):
    """The run's JSON object of a viewer page."""
    return json.loads(page.split("const MO2D = ", 1)[1].split(";</script>", 1)[0])


def test_a_result_displays_as_its_viewer_page_in_an_iframe(result):
    shown = result._repr_html_()
    m = re.fullmatch(r'<iframe [^>]*srcdoc="([^"]*)"></iframe>', shown, re.S)
    assert m, shown[:200]
    page = html.unescape(m.group(1))
    assert page == result.viewer_html()
    assert page.startswith("<!DOCTYPE html>") and "window.mo2dViewer = api" in page
    # self-contained: nothing loaded from elsewhere
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", page), "a reference off the page"
    assert "http://" not in page and "https://" not in page


def test_the_page_draws_the_joints_where_the_run_puts_them(result):
    """The page's pixels of crank_pin (node crank.A) are the run's crank.A through the frame's
    view: x right, y down, the view's centre at the image centre."""
    d = page_data(result.viewer_html())
    W, H, s, (cx, cy) = d["width"], d["height"], d["scale"], d["centre"]
    assert (W, H) == (800, 600)
    j = [x["name"] for x in d["joints"]].index("crank_pin")
    stride = d["stride"]
    for f in (0, 7, len(d["t"]) - 1):
        k = min(f * stride, len(result.t) - 1)
        assert d["t"][f] == pytest.approx(result.t[k], abs=1e-9)
        x, y = result["crank.A.x"][k], result["crank.A.y"][k]
        px, py = d["frames"][f]["J"][2 * j:2 * j + 2]
        assert px == pytest.approx(W / 2 + s * (x - cx), abs=0.006)
        assert py == pytest.approx(H / 2 - s * (y - cy), abs=0.006)
    # the values a click shows, and the plotted efforts
    assert d["plots"] == ["crank_pivot.torque"]
    assert d["values"]["crank_pivot.torque"][7] == pytest.approx(
        result["crank_pivot.torque"][7 * stride], rel=1e-5)


def test_the_page_holds_at_most_max_frames_and_says_so(result, tmp_path):
    n = len(result.t)
    d = page_data(result.viewer_html(max_frames=50, columns=["crank.angle", "crank_pin.Fx"]))
    assert len(d["t"]) <= 50 and d["t"][0] == result.t[0] and d["t"][-1] == result.t[-1]
    assert d["samples"] == n and d["stride"] == (n - 2) // 49 + 1
    assert any(f"{len(d['t'])} of {n} samples in the page" in note for note in d["notes"])
    assert d["plots"] == ["crank.angle", "crank_pin.Fx"]
    path = tmp_path / "run.html"
    result.write_viewer(str(path), max_frames=50, columns=["crank.angle", "crank_pin.Fx"])
    assert path.read_text() == result.viewer_html(max_frames=50,
                                                  columns=["crank.angle", "crank_pin.Fx"])
    assert not list(tmp_path.glob(".*tmp*")), "a temporary left"


def test_an_unknown_column_or_budget_is_an_error(result):
    with pytest.raises(mo2d.Error, match=r"unknown column 'crank_pivot\.torq'.*crank_pivot\.torque"):
        result.viewer_html(columns=["crank_pivot.torq"])
    with pytest.raises(mo2d.Error, match="max_frames is 1, must be >= 2"):
        result.viewer_html(max_frames=1)


def test_a_system_and_a_model_display_as_svg_drawings():
    s = mo2d.System("pendulum")
    s.add_ground_node("O", (0, 0))
    s.add_body("link", nodes={"O": (0, 0), "P": (0.5, 0)}, mass=2.0, com="P")
    s.add_revolute("pivot", "ground.O", "link.O", actuated=True)
    s.add_coordinate("link.angle", rate=[("link.w", 1.0)])
    for svg in (s._repr_svg_(), mo2d.build_model(s)._repr_svg_()):
        assert svg.startswith("<?xml") and "<svg" in svg and svg.rstrip().endswith("</svg>")
        assert 'width="360pt"' in svg or 'width="480' in svg, svg[:300]
    bad = mo2d.System("bad")
    bad.add_body("link", nodes={"O": (0, 0), "P": (0.5, 0)}, mass=2.0, com="P")
    bad.add_revolute("pivot", "ground.Q", "link.O")
    with pytest.raises(mo2d.Error, match="ground.Q"):
        bad._repr_svg_()


# Result.animate is `mo2d render --animate`: frame i at t0 + i / fps over the run, the file by
# its extension, nothing written for an unknown one.
def test_a_result_writes_its_animation(result, tmp_path):
    t = result.t
    info = result.animate(str(tmp_path / "run.gif"), fps=10, width=160, height=120)
    expected = int((t[-1] - t[0]) * 10 + 1e-9) + 1
    assert info["frames"] == expected and info["codec"] == "gif", info
    assert (info["width"], info["height"]) == (160, 120)
    assert (tmp_path / "run.gif").read_bytes()[:6] == b"GIF89a"
    with pytest.raises(mo2d.Error):
        result.animate(str(tmp_path / "run.xyz"), fps=10)
    assert not (tmp_path / "run.xyz").exists()


# Result.animate's loads, traces, labels and plot are `mo2d render --animate`'s --loads, --trace,
# --labels and --plot: the same bytes as the command's file, not those of the plain animation.
# The crank press: a pad force and a drag torque (loads), 0.5 s (6 frames at 10 frames/s).
ANIMATE_OPTIONS = [
    ({"loads": True}, ["--loads"]),
    ({"traces": ["slider.B", "crank.A"]}, ["--trace", "slider.B,crank.A"]),
    ({"labels": True}, ["--labels"]),
    ({"plot": "crank_pivot.torque"}, ["--plot", "crank_pivot.torque"]),
]
ANIMATE_SIZE = {"fps": 10, "width": 320, "height": 240}


@pytest.fixture(scope="module")
def press():
    from conftest import MECHANISMS
    return mo2d.inverse(mo2d.load_scene(MECHANISMS / "crank_press.yaml", set={}))


@pytest.mark.parametrize("kwargs, flags", ANIMATE_OPTIONS, ids=lambda x: str(x))
def test_animate_options_are_those_of_the_command_line(press, tmp_path, mo2d_cli, kwargs, flags):
    import subprocess

    from conftest import MECHANISMS
    plain, ours, theirs = tmp_path / "plain.gif", tmp_path / "ours.gif", tmp_path / "theirs.gif"
    press.animate(str(plain), **ANIMATE_SIZE)
    info = press.animate(str(ours), **ANIMATE_SIZE, **kwargs)
    assert info["frames"] == 6, info
    subprocess.run([mo2d_cli, "render", str(MECHANISMS / "crank_press.yaml"), "--out",
                    str(tmp_path), "--animate", str(theirs), "--fps", "10", "--width", "320",
                    "--height", "240", *flags], check=True, capture_output=True)
    assert ours.read_bytes() == theirs.read_bytes(), kwargs
    assert ours.read_bytes() != plain.read_bytes(), f"{kwargs} changed nothing"


def test_animate_plot_strip_is_below_the_frames(press, tmp_path):
    info = press.animate(str(tmp_path / "p.gif"), **ANIMATE_SIZE, plot="crank_pivot.torque")
    assert (info["width"], info["height"]) == (320, 240 + 240 // 3), info


def test_animate_unknown_trace_or_column_is_an_error_and_writes_nothing(press, tmp_path):
    with pytest.raises(mo2d.Error, match="no point 'slider.nowhere'"):
        press.animate(str(tmp_path / "t.gif"), **ANIMATE_SIZE, traces=["slider.nowhere"])
    with pytest.raises(mo2d.Error, match=r"no column 'crank.tork' \(columns: .*crank_pivot.torque"):
        press.animate(str(tmp_path / "c.gif"), **ANIMATE_SIZE, plot="crank.tork")
    assert list(tmp_path.iterdir()) == []
