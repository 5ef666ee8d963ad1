"""drawTexturedMesh3d and the perspective-correct interpolator (forEachSample/forEachSpan with
depths): hand-worked values, equality with drawMesh3d for a uniform texture, errors."""
import numpy as np
import pytest

import opencv_shading as sh

K = np.array([[100, 0, 100], [0, 100, 100], [0, 0, 1]], np.float64)
ZERO = np.zeros(3)
# The floor y = 1 (below the camera) from z = 1 to z = 3; u = 50 (x + 1), v = 50 (z - 1).
FLOOR = np.array([[-1, 1, 1], [1, 1, 1], [-1, 1, 3], [1, 1, 3]], np.float64)
FLOOR_FACES = [[0, 1, 2], [1, 3, 2]]
FLOOR_UV = np.stack([50 * (FLOOR[:, 0] + 1), 50 * (FLOOR[:, 2] - 1)], axis=1)


def ramp_texture():
    """texel (col, row) = (col / 100, row / 100, 0.5): a bilinear sample is its coordinate."""
    rows, cols = np.mgrid[0:101, 0:101].astype(np.float32)
    return np.dstack([cols / 100, rows / 100, np.full_like(rows, 0.5)]).astype(np.float32)


def test_perspective_correct_floor():
    canvas = np.full((200, 200, 3), -1, np.float32)
    out, depth, ids = sh.drawTexturedMesh3d(canvas, FLOOR, FLOOR_FACES, FLOOR_UV, ramp_texture(),
                                            K, ZERO, ZERO)
    assert out is canvas
    # Pixel (100, 150) sees the floor at Z = 2, X = 0: u = v = 50 (affine would give v = 75).
    np.testing.assert_allclose(canvas[150, 100], [0.5, 0.5, 0.5], atol=2e-4)
    assert abs(depth[150, 100] - 2) < 1e-4 and ids[150, 100] in (0, 1)
    # Pixel (110, 160): Z = 5/3, X = 1/6: u = 175/3, v = 100/3.
    np.testing.assert_allclose(canvas[160, 110, :2], [175 / 300, 100 / 300], atol=2e-4)
    assert (canvas[120] == -1).all() and ids[120, 100] == -1


def test_uniform_texture_equals_vertex_colours():
    colour = np.array([40, 200, 90], np.uint8)
    tex = np.tile(colour, (3, 5, 1))
    for settings in (sh.RenderSettings(),
                     sh.RenderSettings(shadeType="phong", lights=[sh.PointLight((0, -1, 2))]),
                     sh.RenderSettings(shadeType="flat", lights=[sh.PointLight((0, -1, 2))],
                                       textureInterpolation=0, textureBorder=3)):
        a = np.zeros((200, 200, 3), np.uint8)
        b = a.copy()
        _, _, ids_a = sh.drawMesh3d(a, FLOOR, FLOOR_FACES, np.tile(colour, (4, 1)), K, ZERO, ZERO,
                                    settings)
        _, _, ids_b = sh.drawTexturedMesh3d(b, FLOOR, FLOOR_FACES, FLOOR_UV, tex, K, ZERO, ZERO,
                                            settings)
        np.testing.assert_array_equal(ids_a, ids_b)
        assert np.abs(a.astype(int) - b.astype(int)).max() <= 1


def test_textured_errors_leave_the_canvas_untouched():
    canvas = np.zeros((20, 20, 3), np.uint8)
    tex = np.zeros((4, 4, 3), np.uint8)
    with pytest.raises(sh.error, match="textureInterpolation"):
        sh.drawTexturedMesh3d(canvas, FLOOR, FLOOR_FACES, FLOOR_UV, tex, K, ZERO, ZERO,
                              sh.RenderSettings(textureInterpolation=3))
    with pytest.raises(sh.error, match="textureBorder"):
        sh.drawTexturedMesh3d(canvas, FLOOR, FLOOR_FACES, FLOOR_UV, tex, K, ZERO, ZERO,
                              sh.RenderSettings(textureBorder=7))
    with pytest.raises(sh.error, match="texCoords"):
        sh.drawTexturedMesh3d(canvas, FLOOR, FLOOR_FACES, FLOOR_UV[:3], tex, K, ZERO, ZERO)
    with pytest.raises(ValueError, match="texture"):
        sh.drawTexturedMesh3d(canvas, FLOOR, FLOOR_FACES, FLOOR_UV, tex[:, :, 0], K, ZERO, ZERO)
    assert not canvas.any()


def test_for_each_sample_with_depths_by_hand():
    tri = [[0, 0], [100, 0], [0, 100]]
    seen = {}
    sh.forEachSample((128, 128), tri, lambda x, y, w: seen.__setitem__((x, y), w),
                     depths=[1, 2, 2])
    # At (20, 20) the screen weights are (0.6, 0.2, 0.2); divided by the depths (0.6, 0.1, 0.1)
    # and normalized: (0.75, 0.125, 0.125). The depth is 1 / 0.8 = 1.25.
    np.testing.assert_allclose(seen[(20, 20)], [0.75, 0.125, 0.125], atol=1e-12)
    flat = {}
    sh.forEachSample((128, 128), tri, lambda x, y, w: flat.__setitem__((x, y), w))
    assert seen.keys() == flat.keys()  # coverage does not depend on the depths

    def span(y, x0, x1, h, dh):
        for k in range(x1 - x0):
            hk = np.add(h, np.multiply(dh, k))
            np.testing.assert_allclose(hk / hk.sum(), seen[(x0 + k, y)], atol=1e-12)
            seen.pop((x0 + k, y))

    sh.forEachSpan((128, 128), tri, span, depths=np.array([1.0, 2.0, 2.0]))
    assert not seen  # every sample visited once by the spans too
    with pytest.raises(sh.error, match="depths"):
        sh.forEachSample((128, 128), tri, lambda *a: None, depths=[1, 0, 2])
    with pytest.raises(sh.error, match="depths"):
        sh.forEachSpan((128, 128), tri, lambda *a: None, depths=[1, 2])


def test_docstring():
    doc = sh.drawTexturedMesh3d.__doc__
    assert doc and "drawTexturedMesh3d(" in doc and "texCoords" in doc
