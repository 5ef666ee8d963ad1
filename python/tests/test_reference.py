"""The course's NumPy arrays through the bindings equal the C++ API on the same data.

The C++ side is opencv_shading_pyref (python/tests/pyref.cpp), which reads the scene from a
cv2.FileStorage YAML file and writes its result the same way (floats stored with enough digits
to round-trip exactly).
"""
import numpy as np
import pytest

import opencv_shading as sh
from conftest import course_mesh, sphere_mesh


@pytest.mark.parametrize("shade", [sh.SHADE_FLAT, sh.SHADE_GOURAUD])
def test_render_course_arrays(cpp_reference, course, shade):
    verts2d, faces, vcolors, depth = course
    assert verts2d.dtype == np.int64 and faces.dtype == np.int64 and depth.ndim == 1
    img = sh.render(verts2d, faces, vcolors, depth, shadeType=shade)
    ref = cpp_reference("render", verts2d=verts2d, faces=faces, vcolors=vcolors, depth=depth,
                        shadeType=shade)["img"]
    assert img.shape == ref.shape == (512, 512, 3) and ref.dtype == np.float32
    assert np.array_equal(img, ref)
    assert (img != 1).any(axis=2).mean() > 0.9  # the mesh covers the image


def test_render_size_background_no_depth(cpp_reference):
    verts2d, faces, vcolors, _ = course_mesh(n=12, size=200, seed=5)
    img = sh.render(verts2d, faces, vcolors, None, "flat", (240, 180), (0.2, 0.4, 0.6))
    ref = cpp_reference("render", verts2d=verts2d, faces=faces, vcolors=vcolors,
                        shadeType=sh.SHADE_FLAT, width=240, height=180,
                        background=np.array([0.2, 0.4, 0.6]))["img"]
    assert np.array_equal(img, ref)


def test_draw_mesh_uint8_canvas(cpp_reference):
    verts2d, faces, vcolors, depth = course_mesh(n=16, size=256, seed=2)
    vcolors = vcolors * 255
    canvas = np.random.default_rng(0).integers(0, 256, (256, 256, 3), dtype=np.uint8)
    ref = cpp_reference("drawMesh", canvas=canvas, verts2d=verts2d.astype(np.float64),
                        faces=faces, vcolors=vcolors, depth=depth)["img"]
    sh.drawMesh(canvas, verts2d, faces, vcolors, depth)
    assert ref.dtype == np.uint8 and np.array_equal(canvas, ref)


@pytest.mark.parametrize("shade", ["flat", "gouraud", "phong"])
def test_draw_mesh3d_lit(cpp_reference, shade):
    verts, faces, colors = sphere_mesh(rings=20, segments=30)
    K = np.array([[300.0, 0, 128], [0, 300, 96], [0, 0, 1]])
    rvec, tvec = sh.lookAt((2, 1.5, 5), (0, 0, 0), (0, 1, 0))
    lights = [sh.PointLight((4, 4, 6), (1, 0.9, 0.8)), sh.PointLight((-5, 0, 2), (0.2, 0.2, 0.4))]
    settings = sh.RenderSettings(shadeType=shade, lights=lights, cullMode=sh.CULL_BACK,
                                 shininess=24)
    canvas = np.full((192, 256, 3), 0.5, np.float32)
    _, depth, ids = sh.drawMesh3d(canvas, verts, faces, colors, K, rvec, tvec, settings)
    ref = cpp_reference("drawMesh3d", canvas=np.full((192, 256, 3), 0.5, np.float32),
                        verts3d=verts, faces=faces, vcolors=colors, cameraMatrix=K, rvec=rvec,
                        tvec=tvec, shadeType=settings.shadeType, cullMode=sh.CULL_BACK,
                        shininess=24.0,
                        lights=np.array([l.position + l.intensity for l in lights]))
    assert np.array_equal(canvas, ref["img"])
    assert np.array_equal(depth, ref["depth"])
    assert np.array_equal(ids, ref["faceIds"])
    assert (ids >= 0).mean() > 0.15
