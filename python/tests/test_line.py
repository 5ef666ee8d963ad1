"""lines: against cv2.line, colours, forms, errors."""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import need_cv2


def test_constants():
    assert sh.LINE_BRESENHAM == 0 and sh.LINE_DDA == 1


def test_equals_cv2_line():
    cv2 = need_cv2()
    rng = np.random.default_rng(1)
    for _ in range(300):
        p = rng.integers(0, [40, 30], size=(2, 2))
        ref = np.zeros((30, 40, 3), np.uint8)
        cv2.line(ref, tuple(int(v) for v in p[0]), tuple(int(v) for v in p[1]),
                 (255, 255, 255), 1, cv2.LINE_8)
        for algorithm in (sh.LINE_BRESENHAM, sh.LINE_DDA):
            mine = np.zeros((30, 40, 3), np.uint8)
            out = sh.lines(mine, p, [[255] * 3] * 2, algorithm)
            assert out is mine
            np.testing.assert_array_equal(mine, ref)


def test_colours_and_views():
    big = np.zeros((20, 30, 3), np.float32)
    view = big[5:15, 10:25]
    sh.lines(view, np.array([[0, 0], [10, 0]], np.int64), [[0, 0, 0], [1, 0.5, 0]])
    np.testing.assert_allclose(big[5, 10:21, 0], np.arange(11) / 10, atol=1e-7)
    assert not big[:5].any() and not big[5, 21:].any()
    c8 = np.zeros((4, 12, 3), np.uint8)
    sh.lines(c8, [[0, 1], [10, 1]], [[0, 0, 0], [255, 255, 255]])
    assert c8[1, 2].tolist() == [51, 51, 51]


def test_far_endpoints_and_nan():
    c = np.zeros((50, 50, 3), np.float32)
    sh.lines(c, [[-1e9, -1e9], [1e9, 1e9], [np.nan, 0], [10, 10]], np.ones((4, 3)))
    assert (c[np.arange(50), np.arange(50)] == 1).all()
    assert c.sum() == 150


def test_errors():
    c = np.zeros((10, 10, 3), np.uint8)
    with pytest.raises(sh.error, match="points: expected an even number"):
        sh.lines(c, [[0, 0], [1, 1], [2, 2]], np.ones((3, 3)))
    with pytest.raises(sh.error, match="colors"):
        sh.lines(c, [[0, 0], [1, 1]], np.ones((3, 3)))
    with pytest.raises(sh.error, match="algorithm"):
        sh.lines(c, [[0, 0], [1, 1]], np.ones((2, 3)), 5)
    with pytest.raises(TypeError):
        sh.lines(np.zeros((10, 10, 3), np.float64), [[0, 0], [1, 1]], np.ones((2, 3)))
    assert not c.any()


def test_for_each_span_matches_flats():
    tri = [[1.5, 2.25], [30.7, 9.1], [8.2, 27.9]]
    ref = np.zeros((32, 40, 3), np.float32)
    sh.flats(ref, tri, np.ones((3, 3)))
    mine = np.zeros((32, 40), bool)
    sums = []

    def fn(y, x0, x1, w, dwdx):
        mine[y, x0:x1] = True
        sums.append(sum(w))

    sh.forEachSpan((40, 32), tri, fn)
    np.testing.assert_array_equal(mine, ref[:, :, 0] == 1)
    np.testing.assert_allclose(sums, 1.0, atol=1e-12)
    with pytest.raises(ZeroDivisionError):
        sh.forEachSpan((40, 32), tri, lambda *a: 1 / 0)


def test_for_each_sample_covers_what_flats_covers_with_exact_weights():
    tri = np.array([[1.5, 2.25], [30.7, 9.1], [8.2, 27.9]])
    ref = np.zeros((32, 40, 3), np.float32)
    sh.flats(ref, tri, np.ones((3, 3)))
    mine = np.zeros((32, 40), bool)
    snapped = np.round(tri * 256) / 256  # weights belong to the 1/256 px snapped triangle

    def fn(x, y, w):
        mine[y, x] = True
        # The weights reproduce the sample point from the (snapped) vertices.
        np.testing.assert_allclose(np.dot(w, snapped), (x, y), atol=1e-9)

    sh.forEachSample((40, 32), tri, fn)
    np.testing.assert_array_equal(mine, ref[:, :, 0] == 1)
    with pytest.raises(ZeroDivisionError):
        sh.forEachSample((40, 32), tri, lambda *a: 1 / 0)


@pytest.mark.parametrize("name", ["lines", "texturedTriangles", "forEachSpan", "forEachSample"])
def test_docstrings(name):
    doc = getattr(sh, name).__doc__
    assert doc and name + "(" in doc and len(doc) > 150
