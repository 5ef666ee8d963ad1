#!/usr/bin/env bash
# Builds the benchmarks (Release, -DOPENCV_SHADING_BUILD_PERF=ON) in build-perf/, runs them
# (medians of 9 repetitions, interleaved at random, JSON into build-perf/results/), then prints
# the Markdown report and writes the plots to docs/perf/ (report.py). llvmpipe runs in the same
# program when OSMesa was found (libosmesa6-dev). The 2D scenes take about eight minutes on 2
# cores, the 3D ones (drawMesh3d, --benchmark_filter=3d) about as long again.
#
# usage: modules/shading/perf/run_benchmarks.sh [Google Benchmark flags, e.g.
#        --benchmark_filter=512 --benchmark_repetitions=3, or --benchmark_filter=3d: 3D only,
#        --benchmark_filter='Textured|machine': the textured 3D cells only]
# environment: BUILD_DIR (default build-perf), JOBS (build jobs, default nproc), PLOTS_DIR
#              (default docs/perf: a filtered run's plots replace the full ones there)
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
build="${BUILD_DIR:-$root/build-perf}"
results="$build/results"

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DOPENCV_SHADING_BUILD_PERF=ON \
  -DOPENCV_SHADING_BUILD_TESTS=OFF -DOPENCV_SHADING_BUILD_SAMPLES=OFF >/dev/null
cmake --build "$build" -j"${JOBS:-$(nproc)}"

mkdir -p "$results"
rm -f "$results"/*.json
# Repetitions interleaved at random: slow drifts of a shared machine hit every method alike.
"$build/modules/shading/perf/opencv_shading_perf" --benchmark_repetitions=9 \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
  --benchmark_out_format=json --benchmark_out="$results/opencv_shading_perf.json" "$@"

# Plots need matplotlib: Debian's python3-matplotlib is for /usr/bin/python3.
python=python3
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  python=/usr/bin/python3
fi
"$python" "$root/modules/shading/perf/report.py" "$results"/*.json --plots "${PLOTS_DIR:-$root/docs/perf}" \
  | tee "$results/report.md"
