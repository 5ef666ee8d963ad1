#!/usr/bin/env bash
# The library built with its scalar span paths instead of the SIMD ones (OPENCV_SHADING_SCALAR),
# and the whole test suite against it: both paths must give the reference's pixels. Builds in
# build-scalar/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build-scalar -DCMAKE_BUILD_TYPE=Release -DOPENCV_SHADING_SCALAR=ON \
  -DOPENCV_SHADING_BUILD_SAMPLES=OFF -DOPENCV_SHADING_WARNINGS_AS_ERRORS=ON
cmake --build build-scalar -j"$(nproc)"
ctest --test-dir build-scalar --output-on-failure -j"$(nproc)"
