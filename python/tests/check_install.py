"""Checks an installed opencv_shading: python check_install.py PREFIX REL_DIR (run with -I).

The module must sit in a folder this interpreter searches when installed under PREFIX
(site.getsitepackages([PREFIX]), the list site.py builds from a prefix), import from there with
its stub beside it, and load libopencv_shading from PREFIX (its RPATH), not from elsewhere.
"""
import os
import site
import sys

prefix, rel = os.path.realpath(sys.argv[1]), sys.argv[2]
moddir = os.path.join(prefix, rel)
searched = [os.path.realpath(d) for d in site.getsitepackages([prefix])]
assert os.path.realpath(moddir) in searched, (moddir, searched)
# The same relative folder under /usr/local (or this interpreter's own prefix) is on sys.path.
own = [os.path.join(p, rel) for p in ("/usr/local", sys.prefix)]
assert any(d in sys.path for d in own), (own, sys.path)

sys.path[:0] = searched
import opencv_shading  # noqa: E402

modfile = os.path.realpath(opencv_shading.__file__)
assert os.path.dirname(modfile) == os.path.realpath(moddir), modfile
assert os.path.isfile(os.path.join(moddir, "opencv_shading.pyi"))
with open("/proc/self/maps") as maps:
    libs = {line.split()[-1] for line in maps if "libopencv_shading" in line}
assert libs and all(os.path.realpath(p).startswith(prefix + os.sep) for p in libs), libs
img = opencv_shading.render([[0, 0], [8, 0], [0, 8]], [[0, 1, 2]], [[0, 0, 0]] * 3, None,
                            size=(8, 8))
assert img.shape == (8, 8, 3) and img[1, 1].tolist() == [0, 0, 0]
print("installed module OK:", modfile, "library:", sorted(libs))
