"""Rendering from Python: frames, filmstrips and plots as PNG and SVG files."""
import pytest

import mo2d


@pytest.fixture(scope="module")
def result():
    from conftest import MECHANISMS
    return mo2d.inverse(mo2d.load_scene(MECHANISMS / "fourbar.yaml", set={}))


@pytest.mark.parametrize("ext, magic", [(".png", b"\x89PNG\r\n\x1a\n"), (".svg", b"<?xml")])
def test_frame_filmstrip_and_plot(result, tmp_path, ext, magic):
    paths = [tmp_path / f"frame{ext}", tmp_path / f"strip{ext}", tmp_path / f"efforts{ext}",
             tmp_path / f"series{ext}"]
    mo2d.write_frame(result, str(paths[0]), sample=10, labels=True)
    mo2d.write_filmstrip(result, str(paths[1]), frames=4, columns=2, traces=["coupler.B"])
    mo2d.write_plot(result, str(paths[2]), "efforts")
    mo2d.write_series_plot(str(paths[3]), [("torque", list(result.t),
                                            list(result["crank_pivot.torque"]))],
                           title="crank torque", xlabel="time (s)", ylabel="torque (N m)")
    for p in paths:
        assert p.read_bytes().startswith(magic), p
        assert p.stat().st_size > 1000


def test_energies_plot_needs_a_forward_run(result, tmp_path):
    with pytest.raises(mo2d.Error, match="no energies"):
        mo2d.write_plot(result, str(tmp_path / "e.png"), "energies")
