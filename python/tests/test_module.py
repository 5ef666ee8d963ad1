"""The module itself: where it was imported from, its stub, constants, exception, docstrings."""
import ast
import os

import pytest

import opencv_shading as sh


def test_module_is_the_build():
    expected = os.environ.get("OPENCV_SHADING_EXPECT_MODULE_DIR")
    if expected is None:
        pytest.skip("not run by ctest")
    assert os.path.dirname(os.path.realpath(sh.__file__)) == os.path.realpath(expected)


def test_stub_next_to_module():
    stub = os.path.join(os.path.dirname(sh.__file__), "opencv_shading.pyi")
    assert os.path.isfile(stub)
    text = open(stub).read()
    for name in ("def render", "def drawMesh3d", "class RenderSettings", "class PointLight",
                 "SHADE_PHONG", "class error", "def lookAt", "def computeNormals"):
        assert name in text


def test_stub_names_match_module():
    stub = os.path.join(os.path.dirname(sh.__file__), "opencv_shading.pyi")
    tree = ast.parse(open(stub).read())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    # Type aliases (plain assignments) are stub-only and not collected.
    public = {n for n in dir(sh) if not n.startswith("_")} | {"__version__"}
    assert names == public


def test_constants():
    assert (sh.SHADE_FLAT, sh.SHADE_GOURAUD, sh.SHADE_PHONG) == (0, 1, 2)
    assert (sh.VISIBILITY_ZBUFFER, sh.VISIBILITY_PAINTER) == (0, 1)
    assert (sh.CULL_NONE, sh.CULL_BACK, sh.CULL_FRONT) == (0, 1, 2)
    assert isinstance(sh.__version__, str)


def test_error_type():
    assert issubclass(sh.error, RuntimeError)


@pytest.mark.parametrize("name", ["flats", "gouraud", "drawMesh", "render", "drawMesh3d",
                                  "computeNormals", "lookAt", "loadMesh", "saveMesh"])
def test_docstrings(name):
    doc = getattr(sh, name).__doc__
    assert doc and name + "(" in doc and len(doc) > 150
