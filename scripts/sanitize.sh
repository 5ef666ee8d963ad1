#!/usr/bin/env bash
# The library and the whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer, any
# report fatal (-fno-sanitize-recover). Builds in build-asan/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# No Python module: an ASan-instrumented extension cannot load into Debian's uninstrumented
# python3 (the sanitizer runtime must come first); the Python tests run in the normal suite.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOPENCV_SHADING_BUILD_SAMPLES=OFF \
  -DOPENCV_SHADING_BUILD_PYTHON=OFF \
  -DOPENCV_SHADING_WARNINGS_AS_ERRORS=ON -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-asan -j"$(nproc)"
# The package test builds an uninstrumented consumer against the instrumented library: it runs
# in the normal suite, not here.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -E '^Package\.'
