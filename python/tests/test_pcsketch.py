"""The Python module against the library and the CLI: arrays in, the same drawing and the same messages out."""

import json
import os
import subprocess

import numpy as np
import pytest

import pcsketch

BUNNY = os.path.join(os.environ.get("PCSKETCH_DATA", "data"), "bunny.ply")


def sphere(n=3000):
    """A Fibonacci sphere of radius 1: evenly spread points of a closed surface."""
    i = np.arange(n) + 0.5
    z = 1.0 - 2.0 * i / n
    r = np.sqrt(1.0 - z * z)
    phi = i * np.pi * (3.0 - np.sqrt(5.0))
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


@pytest.fixture(scope="module")
def prepared():
    return pcsketch.prepare(sphere(), neighbours=16)


def test_read_gives_world_points_and_normals_if_any():
    points, normals = pcsketch.read(BUNNY)
    assert points.dtype == np.float64 and points.ndim == 2 and points.shape[1] == 3
    assert normals is None or normals.shape == points.shape


def test_draw_returns_strokes_as_arrays(prepared):
    drawing = prepared.draw(view=(0, 0, 1), up=(0, 1, 0), size=(300, 200))
    assert (drawing.width, drawing.height) == (300, 200)
    contours = [s for s in drawing.strokes if s.kind == "contour" and s.visible]
    assert contours, "a sphere has an outline"
    for s in drawing.strokes:
        n = len(s.image_points)
        assert s.image_points.shape == (n, 2) and s.points.shape == (n, 3) and s.widths.shape == (n,)
    # The outline of a unit sphere seen along z: every point about 1 from the axis.
    radii = np.hypot(contours[0].points[:, 0], contours[0].points[:, 1])
    assert np.all(np.abs(radii - 1.0) < 0.05)
    for polygon, grey in drawing.regions:
        assert polygon.shape[1] == 2 and 0.0 <= grey <= 1.0


def test_svg_json_and_files(prepared, tmp_path):
    drawing = prepared.draw(size=(128, 128), azimuth=30, elevation=20)
    assert 'inkscape:label="1 contours"' in drawing.svg()
    parsed = json.loads(drawing.json())
    assert len(parsed["polylines"]) == len(drawing.strokes)
    for ext in ("svg", "png", "pdf", "json"):
        path = tmp_path / ("d." + ext)
        drawing.write(str(path))
        assert path.stat().st_size > 0


def test_options_are_the_cli_flags(prepared):
    plain = prepared.draw(size=(128, 128))
    plotter = prepared.draw(size=(128, 128), plotter=True, no_hatching=True, shadow_k=[0.25, 0.5])
    assert all(s.kind != "hatch" for s in plotter.strokes)
    assert json.loads(plotter.json())["parameters"]["render"]["plotter"] is True
    assert json.loads(plain.json())["parameters"]["render"]["plotter"] is False


def test_bad_values_raise_the_cli_messages(prepared):
    with pytest.raises(ValueError, match="--alpha"):
        pcsketch.prepare(sphere(), alpha=2)
    with pytest.raises(ValueError, match="--size"):
        prepared.draw(size="12 by 7")
    with pytest.raises(ValueError, match="--view"):
        prepared.draw(view=(0, 0, 0))
    with pytest.raises(TypeError, match="--no-such-flag"):
        prepared.draw(no_such_flag=1)
    with pytest.raises(ValueError, match="prepare"):
        prepared.draw(neighbours=24)
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        pcsketch.prepare(np.zeros((10, 2)))


def test_bad_input_raises_pcsketch_error(tmp_path):
    bad = tmp_path / "bad.ply"
    bad.write_text("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nend_header\n1\n")
    with pytest.raises(pcsketch.Error, match="bad.ply"):
        pcsketch.read(str(bad))


def test_arrays_give_the_drawing_the_cli_gives_for_the_file(tmp_path):
    points, normals = pcsketch.read(BUNNY)
    drawing = pcsketch.prepare(points, normals).draw(size=(200, 200), azimuth=-35, elevation=15)
    svg = tmp_path / "cli.svg"
    subprocess.run([os.environ["PCSKETCH_CLI"], "-q", "draw", BUNNY, "--size", "200x200", "--azimuth", "-35",
                    "--elevation", "15", "-o", str(svg)], check=True)
    assert drawing.svg() == svg.read_text()


def test_keep_freed_memory_leaves_drawings_unchanged(prepared):
    before = prepared.draw().svg()
    pcsketch.keep_freed_memory()
    assert prepared.draw().svg() == before
