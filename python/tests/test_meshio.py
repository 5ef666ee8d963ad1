"""loadMesh / saveMesh round trips."""
import os

import numpy as np
import pytest

import opencv_shading as sh
from conftest import sphere_mesh


def mesh():
    verts, faces, colors = sphere_mesh(rings=6, segments=8)
    normals, _ = sh.computeNormals(verts, faces)
    uv = np.stack([verts[:, 0] * 0.5 + 0.5, verts[:, 1] * 0.5 + 0.5], axis=1)
    return verts, faces, normals, colors, uv


@pytest.mark.parametrize("ext", [".ply", ".obj"])
def test_round_trip(tmp_path, ext):
    verts, faces, normals, colors, uv = mesh()
    path = str(tmp_path / ("m" + ext))
    if ext == ".ply":
        sh.saveMesh(path, verts, faces, normals, colors)
    else:
        sh.saveMesh(path, verts, faces, normals=normals, texCoords=uv)
    v, f, n, c, t = sh.loadMesh(path)
    assert v.dtype == np.float32 and v.shape == verts.shape
    assert f.dtype == np.int32 and f.shape == faces.shape
    # Same triangles (as position triples), whatever vertex order the file keeps.
    np.testing.assert_allclose(v[f], verts[faces].astype(np.float32), atol=1e-6)
    np.testing.assert_allclose(n[f], normals[faces], atol=1e-6)
    if ext == ".ply":
        np.testing.assert_allclose(c[f], colors[faces], atol=1 / 255 + 1e-6)  # 8-bit in PLY
        assert t is None
    else:
        assert c is None
        np.testing.assert_allclose(t[f][..., :2], uv[faces], atol=1e-6)


def test_positions_only_gives_none(tmp_path):
    verts, faces, _, _, _ = mesh()
    path = str(tmp_path / "m.off")
    sh.saveMesh(filename=path, vertices=verts.tolist(), faces=faces)
    v, f, n, c, t = sh.loadMesh(filename=tmp_path / "m.off")  # os.PathLike too
    assert v.shape == verts.shape and f.shape == faces.shape
    assert c is None and t is None


def test_errors(tmp_path):
    with pytest.raises(sh.error, match="nope.obj"):
        sh.loadMesh(str(tmp_path / "nope.obj"))
    verts, faces, _, _, _ = mesh()
    path = str(tmp_path / "bad.ply")
    with pytest.raises(sh.error, match="faces"):
        sh.saveMesh(path, verts, faces + 1000)
    assert not os.path.exists(path)
    with pytest.raises(ValueError, match="does not fit in int32"):
        sh.saveMesh(path, verts, faces + 2**40)
