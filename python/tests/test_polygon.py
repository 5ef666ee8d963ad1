"""fillPolygons, triangulatePolygons: input forms, rules, canvases, errors, exact triangulation."""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import need_cv2

SQUARE = [[2, 2], [16, 2], [16, 16], [2, 16]]
HOLE = [[6, 6], [12, 6], [12, 12], [6, 12]]


def blank(h=20, w=20, dtype=np.float32):
    return np.zeros((h, w, 3), dtype)


def mask(canvas):
    return canvas.any(axis=2)


def test_constants():
    assert sh.FILL_EVEN_ODD == 0 and sh.FILL_NONZERO == 1


def test_square_with_hole_by_rule():
    c = blank()
    out = sh.fillPolygons(c, [SQUARE, HOLE], (1, 0.5, 0.25))
    assert out is c
    # Top-left rule: columns and rows 2..15 of the square, 6..11 of the hole cut out.
    assert mask(c).sum() == 14 * 14 - 6 * 6
    np.testing.assert_array_equal(c[2, 2], [1, 0.5, 0.25])
    assert not c[8, 8].any() and not c[16, 16].any()
    # Nonzero: the same orientation fills the hole, the opposite one keeps it.
    c = blank()
    sh.fillPolygons(c, [SQUARE, HOLE], 1, sh.FILL_NONZERO)
    assert mask(c).sum() == 14 * 14
    c = blank()
    sh.fillPolygons(c, [SQUARE, HOLE[::-1]], 1, fillRule=sh.FILL_NONZERO)
    assert mask(c).sum() == 14 * 14 - 6 * 6


def test_input_forms_agree():
    ref = mask(sh.fillPolygons(blank(), [SQUARE, HOLE], 1))
    forms = [
        [np.array(SQUARE, np.int32), np.array(HOLE, np.float64)],
        (np.array(SQUARE, np.float32).reshape(-1, 1, 2), HOLE),
        np.array([SQUARE, HOLE], np.int64),             # K x N x 2
        [np.array(SQUARE, np.int64), np.array(HOLE, np.uint8)],
    ]
    for f in forms:
        np.testing.assert_array_equal(mask(sh.fillPolygons(blank(), f, 1)), ref)
    one = mask(sh.fillPolygons(blank(), np.array(SQUARE), 1))  # a single N x 2 contour
    assert one.sum() == 14 * 14


def test_uint8_canvas_and_view():
    img = np.zeros((30, 30, 3), np.uint8)
    sh.fillPolygons(img[5:, 5:], [SQUARE], (300, 128.4, -3))
    assert img[7, 7].tolist() == [255, 128, 0]
    assert not img[:5].any() and not img[:, :5].any()


def test_same_as_triangle():
    tri = [[1.3, 0.7], [17.9, 5.25], [6.5, 18.1]]
    a = sh.flats(blank(), tri, [[1, 1, 1]] * 3)
    b = sh.fillPolygons(blank(), [tri], 1)
    np.testing.assert_array_equal(a, b)


def test_within_a_pixel_of_cv2_fillpoly():
    cv2 = need_cv2()
    pts = np.array([[3, 4], [40, 8], [22, 20], [44, 41], [6, 36]], np.int32)
    ours = mask(sh.fillPolygons(blank(48, 48), [pts], 1))
    theirs = np.zeros((48, 48), np.uint8)
    cv2.fillPoly(theirs, [pts], 1)
    assert not (ours & ~theirs.astype(bool)).any()  # fillPoly also paints the boundary


def test_errors_leave_canvas_untouched():
    c = blank()
    with pytest.raises(sh.error, match="contour 1, point 2"):
        sh.fillPolygons(c, [SQUARE, [[0, 0], [1, 1], [np.nan, 2]]], 1)
    with pytest.raises(sh.error, match="fillRule"):
        sh.fillPolygons(c, [SQUARE], 1, 7)
    with pytest.raises(TypeError):
        sh.fillPolygons(c, 5, 1)
    with pytest.raises(ValueError):
        sh.fillPolygons(c, np.zeros((2, 2, 2, 2)), 1)
    assert not c.any()
    with pytest.raises(TypeError):
        sh.fillPolygons(np.zeros((4, 4, 3), np.float64), [SQUARE], 1)


def coverage_counts(points, faces, h=20, w=20):
    counts = np.zeros((h, w), int)
    for f in faces:
        counts += mask(sh.flats(blank(h, w), points[f], [[1, 1, 1]] * 3))
    return counts


def test_triangulation_covers_exactly_once():
    for rule in (sh.FILL_EVEN_ODD, sh.FILL_NONZERO):
        polys = [SQUARE, HOLE[::-1]]
        faces = sh.triangulatePolygons(polys, rule)
        assert faces.dtype == np.int32 and faces.shape[1] == 3
        points = np.concatenate([np.array(p, float) for p in polys])
        counts = coverage_counts(points, faces)
        assert counts.max() == 1
        np.testing.assert_array_equal(counts == 1, mask(sh.fillPolygons(blank(), polys, 1, rule)))
    assert sh.triangulatePolygons([[[0, 0], [5, 0], [0, 5]]]).tolist() in (
        [[2, 0, 1]], [[0, 1, 2]], [[1, 2, 0]])


def test_triangulation_of_a_bow_tie_adds_its_crossing():
    bowtie = [[[2, 2], [12, 12], [12, 2], [2, 12]]]
    for rule in (sh.FILL_EVEN_ODD, sh.FILL_NONZERO):
        faces, vertices = sh.triangulatePolygons(bowtie, rule, returnVertices=True)
        assert vertices.dtype == np.float64 and vertices.shape == (5, 2)
        np.testing.assert_array_equal(vertices[:4], bowtie[0])
        np.testing.assert_array_equal(vertices[4], [7, 7])  # on the grid: exact
        assert sorted(sorted(f) for f in faces.tolist()) == [[0, 3, 4], [1, 2, 4]]
        counts = coverage_counts(vertices, faces, 16, 16)
        assert counts.max() == 1
        np.testing.assert_array_equal(counts == 1,
                                      mask(sh.fillPolygons(blank(16, 16), bowtie, 1, rule)))
    # Without returnVertices: the faces alone, as before.
    assert sh.triangulatePolygons(bowtie).shape == (2, 3)


def test_triangulation_of_a_pentagram_by_rule():
    a = 0.1 - np.pi / 2 + 2 * np.pi * np.array([0, 2, 4, 1, 3]) / 5
    star = [np.stack([32 + 28 * np.cos(a), 32 + 28 * np.sin(a)], axis=1)]
    for rule, centre, nfaces in ((sh.FILL_EVEN_ODD, 0, 5), (sh.FILL_NONZERO, 1, 8)):
        faces, vertices = sh.triangulatePolygons(star, fillRule=rule, returnVertices=True)
        assert vertices.shape == (10, 2) and faces.shape == (nfaces, 3)
        np.testing.assert_array_equal(vertices[:5], np.round(star[0] * 256) / 256)
        np.testing.assert_array_equal(vertices * 256, np.round(vertices * 256))
        counts = coverage_counts(vertices, faces, 64, 64)
        assert counts.max() == 1 and counts[32, 32] == centre
        filled = mask(sh.fillPolygons(blank(64, 64), star, 1, rule))
        np.testing.assert_array_equal(counts == 1, filled)  # crossings off the grid: exact too
