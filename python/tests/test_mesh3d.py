"""RenderSettings, PointLight, lookAt, computeNormals, drawMesh3d."""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import need_cv2, sphere_mesh

K = np.array([[200.0, 0, 80], [0, 200, 60], [0, 0, 1]])


def scene():
    verts, faces, colors = sphere_mesh()
    rvec, tvec = sh.lookAt((0, 0, 6), (0, 0, 0), (0, 1, 0))
    return verts, faces, colors, rvec, tvec


# ---- settings --------------------------------------------------------------------------------

def test_point_light():
    light = sh.PointLight()
    assert light.position == (0.0, 0.0, 0.0) and light.intensity == (1.0, 1.0, 1.0)
    light = sh.PointLight(position=(0, 0, 5), intensity=np.array([1, 0.5, 0.25]))
    assert light.position == (0.0, 0.0, 5.0) and light.intensity == (1.0, 0.5, 0.25)
    assert sh.PointLight((1, 2, 3), (0, 0, 1)).position == (1.0, 2.0, 3.0)
    light.position = [1, 2, 3]
    assert light.position == (1.0, 2.0, 3.0)
    assert repr(light) == "PointLight(position=(1.0, 2.0, 3.0), intensity=(1.0, 0.5, 0.25))"
    assert light == sh.PointLight((1, 2, 3), (1, 0.5, 0.25)) and light != sh.PointLight()
    with pytest.raises(ValueError, match="position"):
        sh.PointLight(position=(1, 2))


def test_render_settings_defaults():
    s = sh.RenderSettings()
    assert (s.shadeType, s.visibility, s.cullMode) == (sh.SHADE_GOURAUD, sh.VISIBILITY_ZBUFFER,
                                                       sh.CULL_NONE)
    assert s.zNear == 1e-3 and s.lights == [] and s.ambient == (1.0, 1.0, 1.0)
    assert (s.ka, s.kd, s.ks, s.shininess) == (0.2, 0.7, 0.5, 16.0)
    assert repr(s) == ("RenderSettings(shadeType=SHADE_GOURAUD, visibility=VISIBILITY_ZBUFFER, "
                       "cullMode=CULL_NONE, zNear=0.001, lights=[], ambient=(1.0, 1.0, 1.0), "
                       "ka=0.2, kd=0.7, ks=0.5, shininess=16.0, textureInterpolation=1, "
                       "textureBorder=1, clear=False, background=(0.0, 0.0, 0.0))")


def test_render_settings_keywords_and_attributes():
    s = sh.RenderSettings(shadeType=sh.SHADE_PHONG, visibility=sh.VISIBILITY_PAINTER,
                          cullMode=sh.CULL_BACK, zNear=0.5,
                          lights=[sh.PointLight(position=(0, 0, 5), intensity=(1, 1, 1))],
                          ambient=(0.1, 0.2, 0.3), ka=0.1, kd=0.8, ks=0.3, shininess=32)
    assert s.shadeType == sh.SHADE_PHONG and s.visibility == sh.VISIBILITY_PAINTER
    assert s.cullMode == sh.CULL_BACK and s.zNear == 0.5 and s.shininess == 32.0
    assert s.lights == [sh.PointLight((0, 0, 5), (1, 1, 1))]
    assert s.ambient == (0.1, 0.2, 0.3) and (s.ka, s.kd, s.ks) == (0.1, 0.8, 0.3)
    assert "lights=[PointLight(position=(0.0, 0.0, 5.0)" in repr(s)
    assert "shadeType=SHADE_PHONG" in repr(s) and "cullMode=CULL_BACK" in repr(s)
    s.shadeType = "flat"
    s.lights = (sh.PointLight(), sh.PointLight((1, 1, 1)))
    s.ambient = [1, 1, 1]
    s.kd = 0.5
    assert s.shadeType == sh.SHADE_FLAT and len(s.lights) == 2 and s.kd == 0.5
    with pytest.raises(TypeError):
        sh.RenderSettings(sh.SHADE_FLAT)  # keyword-only
    with pytest.raises(TypeError, match="PointLight"):
        sh.RenderSettings(lights=[(0, 0, 5)])


# ---- lookAt, computeNormals ------------------------------------------------------------------

def test_look_at():
    rvec, tvec = sh.lookAt(eye=(0, 0, 10), target=(0, 0, 0), up=(0, 1, 0))
    assert rvec.shape == (3, 1) and tvec.shape == (3, 1)
    assert rvec.dtype == np.float64 and tvec.dtype == np.float64
    np.testing.assert_allclose(tvec.ravel(), [0, 0, 10], atol=1e-12)
    np.testing.assert_allclose(np.abs(rvec.ravel()), [np.pi, 0, 0], atol=1e-12)
    with pytest.raises(sh.error, match="target"):
        sh.lookAt((1, 2, 3), (1, 2, 3), (0, 1, 0))


def test_look_at_matches_cv2_project_points():
    cv2 = need_cv2()
    rvec, tvec = sh.lookAt(np.array([3.0, 2, 7]), [0, 0, 0], [0, 1, 0])
    uv, _ = cv2.projectPoints(np.array([[0.0, 0, 0]]), rvec, tvec, K, None)
    np.testing.assert_allclose(uv.ravel(), [80, 60], atol=1e-9)  # target at the centre


def test_compute_normals():
    verts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.int64)
    faces = np.array([[0, 1, 2], [0, 3, 1]], np.int64)
    vn, fn = sh.computeNormals(verts, faces)
    assert vn.shape == (4, 3) and fn.shape == (2, 3)
    assert vn.dtype == np.float32 and fn.dtype == np.float32
    np.testing.assert_allclose(fn, [[0, 0, 1], [0, 1, 0]], atol=1e-7)
    np.testing.assert_allclose(vn[0], np.array([0, 1, 1]) / np.sqrt(2), atol=1e-6)
    np.testing.assert_allclose(vn[2], [0, 0, 1], atol=1e-7)
    vn2, _ = sh.computeNormals(verts.astype(np.float32).tolist(), faces.tolist())
    assert np.array_equal(vn, vn2)


# ---- drawMesh3d ------------------------------------------------------------------------------

@pytest.mark.parametrize("dtype", [np.float32, np.uint8])
def test_draw_mesh3d_outputs(dtype):
    verts, faces, colors, rvec, tvec = scene()
    if dtype == np.uint8:
        colors = np.round(colors * 255)
    canvas = np.zeros((120, 160, 3), dtype)
    settings = sh.RenderSettings(shadeType="phong", lights=[sh.PointLight((3, 3, 6))])
    out, depth, ids = sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec, settings)
    assert out is canvas
    assert depth.shape == (120, 160) and depth.dtype == np.float32
    assert ids.shape == (120, 160) and ids.dtype == np.int32
    drawn = ids >= 0
    assert drawn[60, 80] and not drawn[0, 0] and ids.max() < len(faces)
    assert np.isinf(depth[~drawn]).all() and (depth[drawn] > 4.9).all()
    assert abs(depth[60, 80] - 5) < 0.02  # the sphere's front point, radius 1, eye at z=6
    assert canvas[drawn].any(axis=1).all() and not canvas[~drawn].any()


def test_draw_mesh3d_depth_buffer_in_place_composites():
    verts, faces, colors, rvec, tvec = scene()
    half = len(faces) // 2
    one = np.zeros((120, 160, 3), np.float32)
    _, d_one, id_one = sh.drawMesh3d(one, verts, faces, colors, K, rvec, tvec)
    two = np.zeros((120, 160, 3), np.float32)
    depth = np.full((120, 160), np.inf, np.float32)
    _, d1, _ = sh.drawMesh3d(two, verts, faces[half:], colors, K, rvec, tvec, depthBuffer=depth)
    assert d1 is depth
    _, d2, _ = sh.drawMesh3d(two, verts, faces[:half], colors, K, rvec, tvec,
                             sh.RenderSettings(), None, depth)
    assert d2 is depth
    assert np.array_equal(two, one) and np.array_equal(depth, d_one)


@pytest.mark.parametrize("visibility", ["VISIBILITY_ZBUFFER", "VISIBILITY_PAINTER"])
def test_draw_mesh3d_clear_equals_clearing_first(visibility):
    verts, faces, colors, rvec, tvec = scene()
    settings = sh.RenderSettings(shadeType="phong", lights=[sh.PointLight((3, 3, 6))],
                                 visibility=getattr(sh, visibility))
    expected = np.full((120, 160, 3), 0.25, np.float32)
    expected_depth = np.full((120, 160), np.inf, np.float32)
    sh.drawMesh3d(expected, verts, faces, colors, K, rvec, tvec, settings, None, expected_depth)
    settings.clear = True
    settings.background = 0.25
    assert settings.clear and settings.background == (0.25, 0.25, 0.25)
    canvas = np.full((120, 160, 3), -1, np.float32)  # stale content, all replaced
    depth = np.full((120, 160), 0.5, np.float32)     # a stale buffer that would hide everything
    _, d, ids = sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec, settings, None, depth)
    assert d is depth
    assert np.array_equal(canvas, expected) and np.array_equal(depth, expected_depth)
    assert (ids >= 0).any() and (canvas[ids < 0] == 0.25).all()
    with pytest.raises(sh.error, match="settings.background"):
        sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec,
                      sh.RenderSettings(clear=True, background=(0, np.nan, 0)))
    assert np.array_equal(canvas, expected)


def test_draw_mesh3d_view_and_normals():
    verts, faces, colors, rvec, tvec = scene()
    vn, _ = sh.computeNormals(verts, faces)
    settings = sh.RenderSettings(lights=[sh.PointLight((3, 3, 6))], cullMode=sh.CULL_BACK)
    big = np.zeros((300, 400, 3), np.float32)
    view = big[50:170, 100:260]
    sh.drawMesh3d(view, verts, faces, colors, K, rvec.ravel(), tvec.ravel().tolist(), settings,
                  normals=vn)
    fresh = np.zeros((120, 160, 3), np.float32)
    sh.drawMesh3d(fresh, verts, faces, colors, K, rvec, tvec, settings, vn)
    assert np.array_equal(view, fresh) and fresh.any()
    big[50:170, 100:260] = 0
    assert not big.any()


def test_draw_mesh3d_bad_depth_buffer():
    verts, faces, colors, rvec, tvec = scene()
    canvas = np.zeros((120, 160, 3), np.float32)
    with pytest.raises(TypeError, match="depthBuffer"):
        sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec,
                      depthBuffer=np.zeros((120, 160)))
    with pytest.raises(sh.error, match="depthBuffer"):
        sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec,
                      depthBuffer=np.zeros((10, 10), np.float32))
    with pytest.raises(sh.error, match="cameraMatrix"):
        sh.drawMesh3d(canvas, verts, faces, colors, np.eye(2), rvec, tvec)
    assert not canvas.any()
