"""Shared fixtures: course-like data, and the C++ reference renderer (opencv_shading_pyref)."""
import os
import subprocess

import numpy as np
import pytest

import opencv_shading  # noqa: F401  (fails the run early if the module does not import)

# Under ctest: the module must be the one just built, and the C++ helper must be there.
UNDER_CTEST = "OPENCV_SHADING_EXPECT_MODULE_DIR" in os.environ


def need_cv2():
    """cv2 (Debian python3-opencv): required under ctest, else the test is skipped."""
    try:
        import cv2
    except ImportError:
        if UNDER_CTEST:
            pytest.fail("cv2 not importable: apt-get install python3-opencv")
        pytest.skip("cv2 not importable")
    return cv2


def course_mesh(n=24, size=512, seed=0):
    """The course's arrays: verts2d int64 L x 2, faces int64 K x 3, vcolors float64 L x 3,
    depth float64 L, a jittered grid of triangles over a size x size image (some off-canvas)."""
    rng = np.random.default_rng(seed)
    g = np.linspace(-20, size + 20, n)
    x, y = np.meshgrid(g, g)
    verts = np.stack([x.ravel(), y.ravel()], axis=1) + rng.uniform(-6, 6, (n * n, 2))
    verts2d = np.rint(verts).astype(np.int64)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, :-1], idx[1:, 1:]
    faces = np.concatenate([np.stack([a, b, d], -1).reshape(-1, 3),
                            np.stack([a, d, c], -1).reshape(-1, 3)]).astype(np.int64)
    faces = faces[rng.permutation(len(faces))]
    vcolors = rng.uniform(0, 1, (n * n, 3))
    depth = rng.uniform(0, 100, n * n)
    return verts2d, faces, vcolors, depth


def sphere_mesh(rings=16, segments=24, radius=1.0):
    """A UV sphere: verts3d float64 L x 3, faces int64 K x 3 (outward, CCW seen from outside),
    vcolors float64 L x 3."""
    verts = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        th = np.pi * i / rings
        for j in range(segments):
            ph = 2 * np.pi * j / segments
            verts.append((radius * np.sin(th) * np.cos(ph), radius * np.sin(th) * np.sin(ph),
                          radius * np.cos(th)))
    verts.append((0.0, 0.0, -radius))
    verts = np.array(verts)
    faces = []
    ring = lambda i, j: 1 + (i - 1) * segments + j % segments  # noqa: E731
    for j in range(segments):
        faces.append((0, ring(1, j), ring(1, j + 1)))
        faces.append((len(verts) - 1, ring(rings - 1, j + 1), ring(rings - 1, j)))
    for i in range(1, rings - 1):
        for j in range(segments):
            faces.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)))
            faces.append((ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)))
    vcolors = 0.5 + 0.5 * verts / radius
    return verts, np.array(faces, np.int64), vcolors


@pytest.fixture
def course():
    return course_mesh()


@pytest.fixture
def cpp_reference(tmp_path):
    """cpp_reference(op, **args) -> dict of the C++ API's outputs for the same data."""
    exe = os.environ.get("OPENCV_SHADING_PYREF")
    if not exe:
        if UNDER_CTEST:
            pytest.fail("OPENCV_SHADING_PYREF not set")
        pytest.skip("OPENCV_SHADING_PYREF (the C++ helper) not set; run through ctest")
    cv2 = need_cv2()

    def run(op, **args):
        src, dst = str(tmp_path / "in.yml"), str(tmp_path / "out.yml")
        fs = cv2.FileStorage(src, cv2.FILE_STORAGE_WRITE)
        fs.write("op", op)
        for k, v in args.items():
            if v is None:
                continue
            if isinstance(v, (int, np.integer)):
                fs.write(k, int(v))
            elif isinstance(v, float):
                fs.write(k, v)
            else:
                v = np.asarray(v)
                # FileStorage stores int32/float32/float64/uint8 Mats; the values used are exact.
                if v.dtype == np.int64:
                    assert np.abs(v).max() < 2**31
                    v = v.astype(np.int32)
                fs.write(k, np.ascontiguousarray(v))
        fs.release()
        subprocess.run([exe, src, dst], check=True)
        fs = cv2.FileStorage(dst, cv2.FILE_STORAGE_READ)
        out = {}
        for k in ("img", "depth", "faceIds"):
            node = fs.getNode(k)
            if not node.empty():
                out[k] = node.mat()
        fs.release()
        return out

    return run
