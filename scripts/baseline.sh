#!/usr/bin/env bash
# The test suite again with the AVX2 builds (lighting kernels, band pass) switched off at run
# time (OpenCV's OPENCV_CPU_DISABLE makes cv::checkHardwareSupport report no AVX2), so the SSE2
# baseline build that CPUs without AVX2 run is tested on this one too. Reuses build/ from
# scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/CTestTestfile.cmake ]; then
  bash scripts/test.sh
fi
OPENCV_CPU_DISABLE=AVX2 ctest --test-dir build --output-on-failure -j"$(nproc)"
