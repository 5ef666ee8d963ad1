"""texturedTriangles: against cv2.remap, forms, errors."""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import need_cv2


def test_equals_remap_on_an_axis_aligned_quad():
    cv2 = need_cv2()
    rng = np.random.default_rng(3)
    tex = rng.integers(0, 256, (16, 16, 3), dtype=np.uint8)
    verts = [[0, 0], [40, 0], [0, 40], [40, 40]]
    uv = [[-2.3, 1.7], [17.9, 1.7], [-2.3, 21.7], [17.9, 21.7]]
    faces = [[0, 1, 2], [1, 3, 2]]
    for interp in (cv2.INTER_NEAREST, cv2.INTER_LINEAR):
        for border in (cv2.BORDER_CONSTANT, cv2.BORDER_REPLICATE, cv2.BORDER_REFLECT_101):
            c = np.zeros((40, 40, 3), np.uint8)
            assert sh.texturedTriangles(c, verts, faces, uv, tex, interp, border) is c
            x, y = np.meshgrid(np.arange(40), np.arange(40))
            mx = (-2.3 + x * (20.2 / 40)).astype(np.float32)
            my = (1.7 + y * (20.0 / 40)).astype(np.float32)
            ref = cv2.remap(tex, mx, my, interp, borderMode=border)
            # Coordinates computed two ways may round a hair apart: a few pixels at most.
            assert (c != ref).any(axis=2).sum() <= 8


def test_float_canvas_and_defaults():
    tex = np.full((4, 4, 3), 255, np.uint8)
    c = np.zeros((10, 10, 3), np.float32)
    sh.texturedTriangles(c, [[0, 0], [10, 0], [0, 10]], [[0, 1, 2]], [[0, 0], [3, 0], [0, 3]],
                         tex)
    assert c[1, 1].tolist() == [1, 1, 1] and c[9, 9].tolist() == [0, 0, 0]


def test_errors():
    c = np.zeros((10, 10, 3), np.uint8)
    tri, f, uv = [[0, 0], [9, 0], [0, 9]], [[0, 1, 2]], [[0, 0], [1, 0], [0, 1]]
    with pytest.raises(sh.error, match="interpolation"):
        sh.texturedTriangles(c, tri, f, uv, np.zeros((2, 2, 3), np.uint8), 2)
    with pytest.raises(sh.error, match="texCoords"):
        sh.texturedTriangles(c, tri, f, uv[:2], np.zeros((2, 2, 3), np.uint8))
    with pytest.raises(ValueError, match="texture"):
        sh.texturedTriangles(c, tri, f, uv, np.zeros((2, 2), np.uint8))
    assert not c.any()
