"""Prints where, relative to an install prefix, this interpreter looks for modules.

Run by python/CMakeLists.txt at configure time with the interpreter the module is built for.
Debian's python3 searches <prefix>/lib/python3.X/dist-packages for the prefixes /usr/local and
/usr; other CPythons search <prefix>/lib/python3.X/site-packages.
"""
import os
import site
import sys
import sysconfig

PREFIX = os.path.abspath(os.sep + "opencv_shading_prefix")
version_dir = "python%d.%d" % sys.version_info[:2]
candidates = []
if hasattr(site, "getsitepackages"):
    for d in site.getsitepackages([PREFIX]):
        rel = os.path.relpath(d, PREFIX)
        # Debian also lists <prefix>/local/lib/...: meant for prefix /usr, not for a custom one.
        if not rel.startswith("local" + os.sep) and not rel.startswith(".."):
            candidates.append(rel)
# A compiled module is version-specific: prefer the versioned folder (lib/python3.11/...).
versioned = [rel for rel in candidates if version_dir in rel.split(os.sep)]
if versioned:
    print(versioned[0])
elif candidates:
    print(candidates[0])
else:
    scheme = "posix_prefix" if os.name == "posix" else "nt"
    path = sysconfig.get_path("platlib", scheme, vars={"base": PREFIX, "platbase": PREFIX})
    print(os.path.relpath(path, PREFIX))
