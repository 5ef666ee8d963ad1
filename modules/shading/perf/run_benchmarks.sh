#!/usr/bin/env bash
# Builds the benchmarks (Release, -DOPENCV_SHADING_BUILD_PERF=ON) in build-perf/, runs them
# (medians of 5 repetitions, JSON into build-perf/results/), then prints the Markdown report and
# writes the plots to docs/perf/ (report.py). opencv_shading_perf_osmesa (llvmpipe) runs too when
# OSMesa was found. Takes a few minutes on 2 cores.
#
# usage: modules/shading/perf/run_benchmarks.sh [Google Benchmark flags, e.g.
#        --benchmark_filter=512 --benchmark_repetitions=3]
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
for program in opencv_shading_perf opencv_shading_perf_osmesa; do
  exe="$build/modules/shading/perf/$program"
  [[ -x $exe ]] || continue
  "$exe" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_out_format=json --benchmark_out="$results/$program.json" "$@"
done

# Plots need matplotlib: Debian's python3-matplotlib is for /usr/bin/python3.
python=python3
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  python=/usr/bin/python3
fi
"$python" "$root/modules/shading/perf/report.py" "$results"/*.json --plots "${PLOTS_DIR:-$root/docs/perf}" \
  | tee "$results/report.md"
