"""`fishbot_urdf.drawing.picture`: the rasteriser's bounds (size, overlap, deadline) and the picture
it still makes of triangles piled on one another, checked by its pixels."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from fishbot_urdf.drawing.picture import MAX_PIXELS, PictureLimitError, render_png
from fishbot_urdf.drawing.scene import Part, Scene
from fishbot_urdf.errors import ArgumentError, LimitError
from fishbot_urdf.inputs import TimeLimitError, time_limit

RED, BLUE = (1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)


def _scene(*parts: tuple[list[list[list[float]]], tuple[float, float, float, float]]) -> Scene:
    made = []
    for triangles, color in parts:
        array = np.array(triangles, dtype=float)
        made.append(Part("a", array, color, array, np.eye(4)))
    return Scene(tuple(made), (), {"a": np.eye(4)})


def _pixels(data: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(data))).astype(int)


def _hue(pixels: np.ndarray) -> np.ndarray:
    """Per pixel: 0 background, 1 red (shaded, or blended with the background at an edge),
    2 blue, 3 anything else."""
    r, b = pixels[..., 0], pixels[..., 2]
    out = np.full(pixels.shape[:2], 3)
    out[r > b] = 1
    out[b > r] = 2
    out[(pixels == 255).all(axis=2)] = 0
    return out


def _square(x: float, half: float = 1.0) -> list[list[list[float]]]:
    """A square facing +x (the front view's camera), at depth ``x``: two triangles."""
    a, b, c, d = ((x, -half, -half), (x, half, -half), (x, half, half), (x, -half, half))
    return [[list(a), list(b), list(c)], [list(a), list(c), list(d)]]


def test_a_picture_too_big_is_refused_before_it_is_drawn() -> None:
    scene = _scene((_square(0.0), RED))
    with pytest.raises(PictureLimitError) as info:
        render_png(scene, "front", 30000, 30000)
    error = info.value
    assert isinstance(error, LimitError)
    assert error.rule == "limit"
    assert (error.what, error.needed, error.limit) == ("samples", 3_600_000_000, MAX_PIXELS)
    assert error.message == (
        "a 30000 x 30000 picture is drawn on 3,600,000,000 samples (about 40.2 GiB), more "
        "than the bound of 67,108,864 (a 4096 x 4096 picture)"
    )
    with pytest.raises(PictureLimitError):
        render_png(scene, "front", 8192, 8192)
    assert MAX_PIXELS == 4 * 4096 * 4096


@pytest.mark.parametrize(
    ("view", "width", "height"), [("nowhere", 10, 10), ("iso", 0, 10), ("iso", 10, -1)]
)
def test_a_wrong_view_or_size_is_an_argument_error(view: str, width: int, height: int) -> None:
    with pytest.raises(ArgumentError):
        render_png(_scene((_square(0.0), RED)), view, width, height)


def test_many_copies_of_a_big_triangle_are_drawn_once_in_the_first_ones_colour() -> None:
    # 500 copies of the same two screen-filling triangles (as an OBJ file of 4 KB repeating
    # one face would give), each copy in another colour: far more than MAX_COVER visits
    # per sample if each were drawn, and the first copy wins every pixel anyway.
    parts = [(_square(0.0), BLUE)] + [(_square(0.0), RED) for _ in range(499)]
    pixels = _pixels(render_png(_scene(*parts), "front", 200, 150))
    hues = _hue(pixels)
    assert set(np.unique(hues)) == {0, 2}  # blue and background: no red at all
    assert hues[75, 100] == 2
    assert (hues == 2).mean() > 0.5


def test_the_nearest_of_stacked_big_squares_is_seen_whatever_their_order() -> None:
    # 40 screen-filling squares, one behind the other, given in a shuffled order: the
    # nearest (red, at x = 1 towards the front camera) covers every other.
    depths = np.random.default_rng(7).permutation(np.linspace(-1.0, 1.0, 40))
    parts = [(_square(float(x)), RED if x == 1.0 else BLUE) for x in depths]
    hues = _hue(_pixels(render_png(_scene(*parts), "front", 160, 120)))
    assert set(np.unique(hues)) == {0, 1}
    assert (hues == 1).mean() > 0.5


def test_triangles_piled_past_the_visit_bound_are_refused(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Tilted squares stacked 0.001 apart: no copy of another, each one seen nowhere.
    parts = [([[[x, -1, -1], [x + 0.5, 1, -1], [x, 0, 1]]], BLUE) for x in np.arange(20) * 1e-3]
    scene = _scene(*parts)
    monkeypatch.setattr("fishbot_urdf.drawing.picture.MAX_COVER", 4)
    with pytest.raises(PictureLimitError) as info:
        render_png(scene, "front", 64, 48)
    error = info.value
    assert (error.what, error.limit) == ("visits", 4 * 128 * 96)
    assert error.needed > error.limit
    assert error.message.startswith("the picture's triangles overlap more than 4 times over")
    monkeypatch.setattr("fishbot_urdf.drawing.picture.MAX_COVER", 64)
    hues = _hue(_pixels(render_png(scene, "front", 64, 48)))
    assert set(np.unique(hues)) == {0, 2}


def test_rendering_stops_at_the_deadline() -> None:
    scene = _scene((_square(0.0), RED))
    with time_limit(1e-6), pytest.raises(TimeLimitError) as info:
        render_png(scene, "front", 64, 64)
    assert info.value.what == "rendering"
    assert info.value.rule == "limit"


def test_an_empty_scene_is_the_background() -> None:
    empty = Scene((), (), {"a": np.eye(4)})
    pixels = _pixels(render_png(empty, "iso", 32, 16))
    assert pixels.shape == (16, 32, 3)
    assert (pixels == 255).all()


# A square facing the front camera is lit at 0.35 + 0.65 |n . l|, l = (1, -0.4, 0.6) / |l|.
_LIT = 255 * (0.35 + 0.65 / float(np.linalg.norm([1.0, -0.4, 0.6])))


@pytest.mark.parametrize("given", ["near first", "far first"])
def test_a_transparent_square_blends_with_what_is_behind_it(given: str) -> None:
    glass = (_square(1.0), (0.0, 0.0, 1.0, 0.5))  # blue, half transparent, nearer
    wall = (_square(0.0), RED)
    parts = (glass, wall) if given == "near first" else (wall, glass)
    centre = _pixels(render_png(_scene(*parts), "front", 64, 48))[24, 32]
    # half the blue, half the red seen through it
    np.testing.assert_allclose(centre, [0.5 * _LIT, 0, 0.5 * _LIT], atol=1)


@pytest.mark.parametrize("front", ["blue", "red"])
def test_transparent_squares_are_blended_back_to_front_whatever_their_order(front: str) -> None:
    near, far = (1.0, 0.0) if front == "blue" else (0.0, 1.0)
    blue = (_square(near), (0.0, 0.0, 1.0, 0.5))
    red = (_square(far), (1.0, 0.0, 0.0, 0.5))
    for parts in ((blue, red), (red, blue)):
        centre = _pixels(render_png(_scene(*parts), "front", 64, 48))[24, 32]
        # over the white background: the far one first, then the near one over it
        behind = 0.5 * np.array([_LIT, 0, 0] if front == "blue" else [0, 0, _LIT]) + 127.5
        seen = 0.5 * np.array([0, 0, _LIT] if front == "blue" else [_LIT, 0, 0]) + 0.5 * behind
        np.testing.assert_allclose(centre, seen, atol=1)


def test_a_transparent_square_behind_an_opaque_one_is_hidden() -> None:
    parts = ((_square(0.0), (0.0, 0.0, 1.0, 0.5)), (_square(1.0), RED))
    centre = _pixels(render_png(_scene(*parts), "front", 64, 48))[24, 32]
    np.testing.assert_allclose(centre, [_LIT, 0, 0], atol=1)


def test_a_fully_transparent_shape_is_not_drawn() -> None:
    pixels = _pixels(render_png(_scene((_square(0.0), (1.0, 0.0, 0.0, 0.0))), "front", 32, 24))
    assert (pixels == 255).all()


def test_transparent_layers_count_towards_the_visit_bound(monkeypatch: pytest.MonkeyPatch) -> None:
    # Ten transparent squares, one behind the other: each sample is visited ten times.
    parts = [(_square(float(x)), (0.0, 0.0, 1.0, 0.3)) for x in range(10)]
    monkeypatch.setattr("fishbot_urdf.drawing.picture.MAX_COVER", 4)
    with pytest.raises(PictureLimitError) as info:
        render_png(_scene(*parts), "front", 64, 48)
    assert (info.value.what, info.value.limit) == ("visits", 4 * 128 * 96)
    monkeypatch.setattr("fishbot_urdf.drawing.picture.MAX_COVER", 64)
    centre = _pixels(render_png(_scene(*parts), "front", 64, 48))[24, 32]
    # 0.7 ** 10 of the white background is left, under ten layers of shaded blue
    blue = 0.3 * _LIT * sum(0.7**i for i in range(10))
    np.testing.assert_allclose(centre, [255 * 0.7**10, 255 * 0.7**10, blue + 255 * 0.7**10], atol=1)


def test_transparent_layers_piled_on_a_few_rows_are_refused(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The layers of 16 rows of samples at a time are held at once: 250 transparent strips
    # over the top rows pass MAX_COVER there, though not over the whole picture.
    def strip(x: float) -> list[list[list[float]]]:
        a, b, c, d = ((x, -0.5, 0.9), (x, 0.5, 0.9), (x, 0.5, 1.0), (x, -0.5, 1.0))
        return [[list(a), list(b), list(c)], [list(a), list(c), list(d)]]

    layers = [(strip(x * 1e-3), (0.0, 0.0, 1.0, 0.5)) for x in range(250)]
    below = ([[[0, -0.5, -1.0], [0, 0.5, -1.0], [0, 0, -0.9]]], RED)  # the picture's bottom
    monkeypatch.setattr("fishbot_urdf.drawing._raster._GLASS", 64 * 16)
    with pytest.raises(PictureLimitError) as info:
        render_png(_scene(*layers, below), "front", 32, 64)
    error = info.value
    assert (error.what, error.limit) == ("visits", 64 * 64 * 16)
    assert error.message.startswith(
        "the picture's transparent triangles overlap more than 64 times over 1,024 of its "
        "samples (rows 0 to 15 of 128)"
    )
