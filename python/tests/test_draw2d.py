"""flats, gouraud, drawMesh, render: input forms, canvases (dtypes, views), errors."""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import course_mesh, need_cv2

TRI = [[0, 0], [8, 0], [0, 8]]
RGB = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]


def blank(h=16, w=16, dtype=np.float32):
    return np.zeros((h, w, 3), dtype)


# ---- hand-worked pixels ----------------------------------------------------------------------

def test_flats_hand_worked():
    c = blank()
    out = sh.flats(c, TRI, RGB)
    assert out is c
    third = np.float32(1) / 3
    np.testing.assert_allclose(c[1, 1], [third] * 3, rtol=1e-6)
    # Top-left rule: (0, 0) lies on the top and the left edge, covered; (4, 4) on the
    # hypotenuse, a right edge, not covered; (6, 6) outside.
    assert c[0, 0].any() and not c[4, 4].any() and not c[6, 6].any()


def test_gouraud_hand_worked():
    c = blank()
    assert sh.gouraud(c, TRI, RGB) is c
    # At (x, y) = (2, 2): weights red 1 - x/8 - y/8, green x/8, blue y/8.
    np.testing.assert_allclose(c[2, 2], [0.5, 0.25, 0.25], atol=1e-6)
    np.testing.assert_allclose(c[1, 3], [0.5, 0.375, 0.125], atol=1e-6)


def test_uint8_canvas():
    c = blank(dtype=np.uint8)
    sh.flats(c, TRI, [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    assert c.dtype == np.uint8 and c[1, 1].tolist() == [85, 85, 85]
    sh.gouraud(c, TRI, [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    assert c[2, 2].tolist() == [128, 64, 64]  # 127.5 rounds to 128; 63.75 to 64


# ---- input forms -----------------------------------------------------------------------------

def forms_of_mesh():
    v, f, col, d = course_mesh(n=8, size=64, seed=3)
    col = np.round(col * 8) / 8  # exactly representable in float32 too
    d = np.round(d)
    return v, f, col, d


FORMS = {
    "int64": lambda v, f, c, d: (v, f, c, d),
    "float64": lambda v, f, c, d: (v.astype(np.float64), f.astype(np.float64), c, d),
    "float32": lambda v, f, c, d: (v.astype(np.float32), f.astype(np.int32),
                                   c.astype(np.float32), d.astype(np.float32)),
    "int32": lambda v, f, c, d: (v.astype(np.int32), f.astype(np.int32), c, d.astype(np.int32)),
    "lists": lambda v, f, c, d: (v.tolist(), f.tolist(), c.tolist(), d.tolist()),
    "tuples": lambda v, f, c, d: (tuple(map(tuple, v.tolist())), tuple(map(tuple, f.tolist())),
                                  tuple(map(tuple, c.tolist())), tuple(d.tolist())),
    "depth_Nx1": lambda v, f, c, d: (v, f, c, d.reshape(-1, 1)),
    "depth_1xN": lambda v, f, c, d: (v, f, c, d.reshape(1, -1)),
    "Nx1x2_points": lambda v, f, c, d: (v.reshape(-1, 1, 2), f, c, d),
    "uint16_int16": lambda v, f, c, d: (v.astype(np.int16), f.astype(np.uint16), c, d),
    "uint64": lambda v, f, c, d: (v + 100, f.astype(np.uint64), c, d),
    "fortran_order": lambda v, f, c, d: (np.asfortranarray(v), np.asfortranarray(f), c, d),
    "strided_views": lambda v, f, c, d: (np.repeat(v, 2, axis=0)[::2], f,
                                         np.repeat(c, 2, axis=1)[:, ::2], d),
}


@pytest.mark.parametrize("form", sorted(FORMS))
@pytest.mark.parametrize("shade", [sh.SHADE_FLAT, sh.SHADE_GOURAUD])
def test_render_input_forms(form, shade):
    v, f, c, d = forms_of_mesh()
    shift = 100 if form == "uint64" else 0
    ref = sh.render(v.astype(np.float64) + shift, f.astype(np.int32), c, d, shadeType=shade,
                    size=(96, 80))
    got = sh.render(*FORMS[form](v, f, c, d), shadeType=shade, size=(96, 80))
    assert got.shape == (80, 96, 3) and got.dtype == np.float32
    assert got.flags.c_contiguous and got.flags.writeable
    np.testing.assert_array_equal(got, ref)


def test_render_defaults_and_keywords(course):
    v, f, c, d = course
    img = sh.render(v, f, c, d)
    assert img.shape == (512, 512, 3)
    assert np.array_equal(img, sh.render(v, f, c, d, shadeType=sh.SHADE_GOURAUD))
    img = sh.render(verts2d=v, faces=f, vcolors=c, depth=d, shadeType="FLAT", size=(300, 200),
                    background=(0.25, 0.5, 0.75))
    assert img.shape == (200, 300, 3)
    assert np.array_equal(img, sh.render(v, f, c, d, sh.SHADE_FLAT, (300, 200),
                                         (0.25, 0.5, 0.75)))
    empty = sh.render(np.zeros((0, 2)), np.zeros((0, 3), np.int64), np.zeros((0, 3)), None,
                      size=(4, 3), background=0.5)
    assert (empty == 0.5).all()


def test_drawmesh_depth_none_keeps_order():
    v = [[0, 0], [10, 0], [0, 10]]
    c = blank()
    # Two identical faces, no depth: the second one drawn wins; colours per vertex.
    sh.drawMesh(c, v + v, [[0, 1, 2], [3, 4, 5]], [[1, 0, 0]] * 3 + [[0, 1, 0]] * 3)
    assert c[1, 1].tolist() == [0, 1, 0]
    c2 = blank()
    sh.drawMesh(c2, v + v, [[0, 1, 2], [3, 4, 5]], [[1, 0, 0]] * 3 + [[0, 1, 0]] * 3,
                depth=[1, 1, 1, 5, 5, 5])  # the second is farther: drawn first
    assert c2[1, 1].tolist() == [1, 0, 0]


@pytest.mark.parametrize("name,shade", [("flat", 0), ("Gouraud", 1), ("PHONG", 2),
                                        ("flat", sh.SHADE_FLAT)])
def test_shade_strings(name, shade):
    assert sh.RenderSettings(shadeType=name).shadeType == shade


def test_shade_string_equivalent(course):
    v, f, c, d = course
    assert np.array_equal(sh.render(v, f, c, d, "flat", (64, 64)),
                          sh.render(v, f, c, d, sh.SHADE_FLAT, (64, 64)))
    c1, c2 = blank(64, 64), blank(64, 64)
    sh.drawMesh(c1, v, f, c, d, shadeType="gouraud")
    sh.drawMesh(c2, v, f, c, d, shadeType=np.int64(sh.SHADE_GOURAUD))
    assert np.array_equal(c1, c2)


def test_bad_shade_string():
    with pytest.raises(ValueError, match="'flat', 'gouraud', 'phong'"):
        sh.render(TRI, [[0, 1, 2]], RGB, None, shadeType="smooth")
    with pytest.raises(ValueError, match="'flat', 'gouraud', 'phong'"):
        sh.RenderSettings(shadeType="wire")
    with pytest.raises(TypeError):
        sh.render(TRI, [[0, 1, 2]], RGB, None, shadeType=1.0)


# ---- canvases --------------------------------------------------------------------------------

@pytest.mark.parametrize("dtype", [np.float32, np.uint8])
def test_draw_into_view(dtype):
    v, f, c, d = course_mesh(n=10, size=300, seed=1)
    if dtype == np.uint8:
        c = np.round(c * 255)
    img = np.full((300, 400, 3), 7, dtype)
    view = img[10:200, 30:300]
    assert not view.flags.c_contiguous
    out = sh.drawMesh(view, v, f, c, d)
    assert out is view
    # The view holds exactly what a fresh canvas of its size gets; the rest of img is untouched.
    fresh = np.full((190, 270, 3), 7, dtype)
    sh.drawMesh(fresh, v, f, c, d)
    assert np.array_equal(img[10:200, 30:300], fresh)
    assert (fresh != 7).any()
    mask = np.ones(img.shape[:2], bool)
    mask[10:200, 30:300] = False
    assert (img[mask] == 7).all()


def test_draw_into_row_strided_view():
    img = np.zeros((40, 20, 3), np.float32)
    view = img[::2]
    sh.flats(view, [[-5, -5], [100, -5], [-5, 100]], RGB)
    assert (img[::2] == np.float32(1) / 3).all() and (img[1::2] == 0).all()


def test_cv2_image_canvas(tmp_path):
    cv2 = need_cv2()
    path = str(tmp_path / "bg.png")
    cv2.imwrite(path, np.full((60, 80, 3), 200, np.uint8))
    img = cv2.imread(path)
    assert img.dtype == np.uint8 and img.shape == (60, 80, 3)
    sh.gouraud(img, [[0, 0], [79, 0], [0, 59]], [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    assert img[1, 1].tolist() != [200, 200, 200] and img[58, 78].tolist() == [200, 200, 200]
    sh.drawMesh(img[30:, 40:], [[0, 0], [39, 0], [0, 29]], [[0, 1, 2]], [[9, 9, 9]] * 3)
    assert img[31, 41].tolist() == [9, 9, 9]


def test_float64_canvas_raises():
    c = np.zeros((8, 8, 3), np.float64)
    with pytest.raises(TypeError, match="float32 or uint8"):
        sh.flats(c, TRI, RGB)
    assert not c.any()


def test_readonly_canvas_raises():
    c = blank()
    c.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        sh.gouraud(c, TRI, RGB)
    assert not c.any()


@pytest.mark.parametrize("make", [
    lambda: np.zeros((8, 8), np.float32),            # no channel axis
    lambda: np.zeros((8, 8, 4), np.float32),         # 4 channels
    lambda: np.zeros((8, 8, 3, 1), np.float32),      # 4-D
])
def test_bad_canvas_shape_raises(make):
    with pytest.raises(ValueError, match="H x W x 3"):
        sh.flats(make(), TRI, RGB)


@pytest.mark.parametrize("make", [
    lambda: np.zeros((8, 16, 3), np.float32)[:, ::2],         # pixels not contiguous
    lambda: np.zeros((8, 8, 3), np.uint8)[..., ::-1],         # BGR <-> RGB view
    lambda: np.zeros((8, 8, 3), np.float32)[::-1],            # negative row stride
    lambda: np.asfortranarray(np.zeros((8, 8, 3), np.float32)),
])
def test_non_contiguous_pixels_raise(make):
    c = make()
    with pytest.raises(ValueError, match="contiguous"):
        sh.flats(c, TRI, RGB)


@pytest.mark.parametrize("canvas", [[[[0.0] * 3] * 4] * 4, None, "img"])
def test_non_array_canvas_raises(canvas):
    with pytest.raises(TypeError, match="canvas"):
        sh.flats(canvas, TRI, RGB)


# ---- errors ----------------------------------------------------------------------------------

def test_cpp_error_message():
    c = blank()
    with pytest.raises(sh.error, match=r"faces: face 1 has index 5, outside \[0, 3\)") as e:
        sh.drawMesh(c, TRI, [[0, 1, 2], [0, 1, 5]], RGB)
    assert e.value.code < 0 and e.value.func and e.value.line > 0
    assert isinstance(e.value, RuntimeError)
    assert not c.any()  # nothing drawn when an argument is rejected


def test_cpp_error_vertex_count():
    with pytest.raises(sh.error, match="vertices"):
        sh.flats(blank(), [[0, 0], [1, 1]], RGB)


def test_face_index_overflow():
    with pytest.raises(ValueError, match="does not fit in int32"):
        sh.drawMesh(blank(), TRI, np.array([[0, 1, 2**31]], np.int64), RGB)
    with pytest.raises(ValueError, match="does not fit in int32"):
        sh.render(TRI, [[0, 1, -2**40]], RGB, None)


def test_bad_input_types():
    with pytest.raises(TypeError, match="verts2d"):
        sh.render(["a", "b", "c"], [[0, 1, 2]], RGB, None)
    with pytest.raises(TypeError, match="size"):
        sh.render(TRI, [[0, 1, 2]], RGB, None, size=(8.5, 8))
    with pytest.raises(sh.error):
        sh.render(TRI, [[0, 1, 2]], RGB, None, size=(0, 8))


def test_large_int64_vertices_kept_exact():
    # 2**35 does not fit in int32: int64 points go through float64, exactly.
    far = np.array([[0, 0], [2**35, 0], [0, 2**35]], np.int64)
    c1, c2 = blank(), blank()
    sh.flats(c1, far, RGB)
    sh.flats(c2, far.astype(np.float64), RGB)
    assert np.array_equal(c1, c2) and c1.all()
