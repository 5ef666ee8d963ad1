#!/usr/bin/env bash
# Builds the libFuzzer target with clang (ASan + UBSan), replays the seed corpus in
# test/fuzz/corpus, then fuzzes for FUZZ_SECONDS (default 60). New inputs go to build-fuzz/corpus;
# a crash is written to build-fuzz/ and fails the script.
#   FUZZ_SECONDS=3600 bash scripts/fuzz.sh       # fuzz for an hour
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang libclang-rt-14-dev
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBUILD_SHARED_LIBS=OFF -DOPENCV_SHADING_BUILD_FUZZ=ON -DOPENCV_SHADING_BUILD_TESTS=OFF \
  -DOPENCV_SHADING_BUILD_SAMPLES=OFF -DOPENCV_SHADING_WARNINGS_AS_ERRORS=ON \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-fuzz -j"$(nproc)" --target fuzz_shading
fuzzer=build-fuzz/test/fuzz/fuzz_shading
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
echo "== replaying $(ls test/fuzz/corpus | wc -l) corpus inputs"
"$fuzzer" -runs=0 test/fuzz/corpus
echo "== fuzzing for ${FUZZ_SECONDS:-60} s"
mkdir -p build-fuzz/corpus
"$fuzzer" -max_total_time="${FUZZ_SECONDS:-60}" -timeout=10 -rss_limit_mb=4096 \
  -artifact_prefix=build-fuzz/ -print_final_stats=1 build-fuzz/corpus test/fuzz/corpus
