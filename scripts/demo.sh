#!/usr/bin/env bash
# Quick start, part 1: install what is missing, build, render the built-in torus knot with the
# opencv_shading program, and run the samples. PNGs go to out/; windows open too when a display
# is available.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
mkdir -p out
# The one-step picture: any mesh file works in place of demo (OBJ, PLY, STL, glTF, OFF, ...).
./build/apps/opencv_shading demo -o out/opencv_shading_demo.png
./build/samples/demo_flat --out out/demo_flat.png "$@"
./build/samples/demo_gouraud --out out/demo_gouraud.png "$@"
./build/samples/fillpoly_coverage --out out/fillpoly_coverage.png "$@"
./build/samples/demo_lighting --out out/demo_lighting.png "$@"
./build/samples/pose_overlay --out out/pose_overlay.png "$@"
./build/samples/wireframe --out out/wireframe.png "$@"
./build/samples/texture_demo --out out/texture_demo.png "$@"
./build/samples/polygon_fill --out out/polygon_fill.png "$@"
./build/samples/textured_mesh3d --out out/textured_mesh3d.png "$@"
