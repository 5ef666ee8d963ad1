#!/usr/bin/env python3
# This file is part of opencv_shading. License: Apache-2.0.
"""Turns Google Benchmark JSON from opencv_shading_perf into a
Markdown report on stdout: the machine, a table of median times per scene and a table of ratios,
then the 3D section (drawMesh3d and llvmpipe per scene, shading and visibility, the ratios and
the 3D targets) and the textured 3D section (drawTexturedMesh3d and llvmpipeTextured). With
--plots DIR and matplotlib (Debian: python3-matplotlib, for /usr/bin/python3) it also writes
DIR/perf_vs_triangles.png and DIR/perf_vs_canvas.png (2D scenes).

usage: report.py RESULTS.json [MORE.json ...] [--plots DIR]

Benchmark names are METHOD/SCENE[/SHADE]/threads:N[/real_time], SHADE being SHADING/VISIBILITY
for the 3D scenes (whose names contain "3d"). With repetitions the "median" aggregates are used;
without, the median of the runs of each benchmark.
"""
import argparse
import json
import os
import re
import statistics
import sys

UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
# Table order within a canvas size.
KINDS = ["grid", "sphere", "random", "demo", "biggrid", "bigsphere"]
# perf_polygon.hpp: fillPolygons against cv::fillPoly, scenes polyN (N vertices).
POLYGON_METHODS = ("fillPolygons", "fillPoly", "triangulatePolygons", "gluTess")
SHADES_3D = [("flat", "flat"), ("gouraud", "Gouraud"), ("phong", "Phong")]
VISIBILITIES_3D = [("zbuffer", "z-buffer"), ("painter", "painter's")]
TARGET_3D_RATIO = 3.0  # llvmpipe / drawMesh3d at all threads, every 3D cell: at least this
TARGET_3D_DEMO_MS = 2.0  # the demo knot in Phong with three lights, all threads: under this


def load(paths):
    """Returns (contexts, times, counts): times[(method, scene, shade, threads)] = median ms,
    counts[scene] = (triangles, pixels)."""
    contexts, runs, counts = [], {}, {}
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        contexts.append(data.get("context", {}))
        for b in data.get("benchmarks", []):
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
                continue
            parts = [p for p in b["run_name"].split("/") if p != "real_time"]
            threads = next((int(p.split(":")[1]) for p in parts if p.startswith("threads:")), 1)
            parts = [p for p in parts if not p.startswith("threads:")]
            method, scene = parts[0], parts[1]
            shade = "/".join(parts[2:]) or None  # 3D: "phong/zbuffer"
            ms = b["real_time"] * UNIT_MS[b.get("time_unit", "ns")]
            runs.setdefault((method, scene, shade, threads), []).append(ms)
            if "triangles" in b:
                counts[scene] = (int(b["triangles"]), int(b["pixels"]))
    times = {key: statistics.median(v) for key, v in runs.items()}
    return contexts, times, counts


def is_3d(scene):
    return "3d" in scene


def scene_order(scenes):
    """Scenes by canvas size, then grid, sphere, random, demo (3D ones by size, then name)."""
    def key(name):
        m = re.match(r"([a-z]+(?:3d)?)(\d+)$", name)
        kind, side = (m.group(1), int(m.group(2))) if m else (name, 0)
        return (side, KINDS.index(kind) if kind in KINDS else len(KINDS), name)
    return sorted(scenes, key=key)


def fmt_ms(ms):
    if ms is None:
        return "–"
    return f"{ms:.3g}" if ms < 100 else f"{ms:.0f}"


def fmt_ratio(num, den):
    return "–" if num is None or den is None else f"{num / den:.2f}x"


class Results:
    def __init__(self, contexts, times, counts):
        self.contexts, self.times, self.counts = contexts, times, counts
        scenes = {k[1] for k in times if k[0] != "machine" and k[0] not in POLYGON_METHODS}
        self.poly_scenes = sorted({k[1] for k in times if k[0] in POLYGON_METHODS},
                                  key=lambda s: (s.startswith("cross"),
                                                 int(re.sub(r"\D", "", s) or 0)))
        # 2D triangle scenes: those render drew (the lines/texture cells have scenes of their own).
        rendered = {k[1] for k in times if k[0] == "render"}
        self.scenes = scene_order(s for s in scenes if not is_3d(s) and s in rendered)
        self.scenes3d = scene_order(s for s in scenes if is_3d(s))
        self.all_threads = max((k[3] for k in times
                                if k[0] in ("render", "drawMesh3d", "drawTexturedMesh3d")),
                               default=1)

    def get(self, method, scene, shade=None, threads=None):
        """Median ms; threads None means the largest thread count measured for the method."""
        found = [(k[3], t) for k, t in self.times.items()
                 if k[0] == method and k[1] == scene and k[2] == shade
                 and (threads is None or k[3] == threads)]
        return max(found)[1] if found else None

    def has(self, method):
        return any(k[0] == method for k in self.times)

    def llvmpipe_threads(self, method="llvmpipe"):
        return max((k[3] for k in self.times if k[0] == method), default=None)


def machine_lines(res):
    ctx = {}
    for c in res.contexts:  # the first file's values win
        for k, v in c.items():
            ctx.setdefault(k, v)
    lines = [f"- Machine: {ctx.get('cpu_model', '?')}, {ctx.get('num_cpus', '?')} CPUs at "
             f"{ctx.get('mhz_per_cpu', '?')} MHz (host {ctx.get('host_name', '?')}, "
             f"load average {', '.join(f'{x:.2f}' for x in ctx.get('load_avg', []))} at start), "
             f"{ctx.get('date', '?')}",
             f"- OpenCV {ctx.get('opencv_version', '?')}, parallel framework "
             f"{ctx.get('opencv_parallel_framework', '?')}; render \"all threads\" = "
             f"{res.all_threads} threads"]
    if ctx.get("llvmpipe_threads"):
        lines.append(f"- llvmpipe (OSMesa) with {ctx['llvmpipe_threads']} threads")
    one, n = res.get("machine", "arithmetic", threads=1), res.get("machine", "arithmetic")
    n_threads = max((k[3] for k in res.times if k[0] == "machine"), default=1)
    if one and n and n_threads > 1:
        lines.append(f"- Cores available during the run: pure arithmetic ran {one / n:.2f}x "
                     f"faster on {n_threads} threads than on 1 (medians; {n_threads:.2f}x when "
                     "every core is free)")
    checks = sorted((k, v) for k, v in ctx.items() if k.startswith("check_"))
    for k, v in checks:
        lines.append(f"- {k}: {v}")
    lines.append("- Times are medians of the repetitions, in milliseconds, wall clock; every "
                 "method clears a float RGB canvas to white and draws all triangles in "
                 "painter's order (3D: with a z-buffer, cleared too, or in painter's order)")
    return lines


def time_table(res):
    n = res.all_threads
    cols = [("render flat 1 thr", "render", "flat", 1),
            (f"render flat {n} thr", "render", "flat", n),
            ("render Gouraud 1 thr", "render", "gouraud", 1),
            (f"render Gouraud {n} thr", "render", "gouraud", n),
            ("plain flat", "plain", "flat", 1),
            ("plain Gouraud", "plain", "gouraud", 1),
            ("fillConvexPoly", "fillConvexPoly", "flat", 1)]
    if res.has("llvmpipe"):
        lt = res.llvmpipe_threads()
        cols += [(f"llvmpipe flat {lt} thr", "llvmpipe", "flat", lt),
                 (f"llvmpipe Gouraud {lt} thr", "llvmpipe", "gouraud", lt)]
    cols.append(("clear", "clear", None, 1))
    if res.has("clearRead"):
        cols.append(("clear + read", "clearRead", None, 1))
    rows = [["scene", "triangles"] + [c[0] for c in cols]]
    for s in res.scenes:
        tri = res.counts.get(s, (None, None))[0]
        rows.append([s, f"{tri:,}" if tri else "?"] +
                    [fmt_ms(res.get(m, s, sh, t)) for _, m, sh, t in cols])
    return rows


def ratio_table(res):
    """Baseline time / render (all threads) time: above 1 means render is faster."""
    rows = [["scene", "plain / render flat", "plain / render Gouraud",
             "fillConvexPoly / render flat"]]
    llvm = res.has("llvmpipe")
    if llvm:
        rows[0] += ["llvmpipe / render flat", "llvmpipe / render Gouraud"]
    rows[0] += ["render flat / clear", "render Gouraud / clear"]
    floor = res.has("clearRead")
    if floor:
        rows[0] += ["render flat / (clear + read)", "render Gouraud / (clear + read)"]
    for s in res.scenes:
        flat, gour = res.get("render", s, "flat"), res.get("render", s, "gouraud")
        row = [s, fmt_ratio(res.get("plain", s, "flat"), flat),
               fmt_ratio(res.get("plain", s, "gouraud"), gour),
               fmt_ratio(res.get("fillConvexPoly", s, "flat"), flat)]
        if llvm:
            row += [fmt_ratio(res.get("llvmpipe", s, "flat"), flat),
                    fmt_ratio(res.get("llvmpipe", s, "gouraud"), gour)]
        row += [fmt_ratio(flat, res.get("clear", s)), fmt_ratio(gour, res.get("clear", s))]
        if floor:
            row += [fmt_ratio(flat, res.get("clearRead", s)),
                    fmt_ratio(gour, res.get("clearRead", s))]
        rows.append(row)
    return rows


def time_table_3d(res):
    """One row per 3D scene, shading and visibility: drawMesh3d at 1 and all threads, llvmpipe,
    their ratio, and the clears alone."""
    n, lt = res.all_threads, res.llvmpipe_threads()
    head = ["scene", "triangles", "shading", "visibility", "drawMesh3d 1 thr",
            f"drawMesh3d {n} thr"]
    if lt:
        head += [f"llvmpipe {lt} thr", f"llvmpipe / drawMesh3d ({n} thr)"]
    head.append("clear")
    rows = [head]
    for s in res.scenes3d:
        tri = res.counts.get(s, (None, None))[0]
        for shade, shade_label in SHADES_3D:
            for vis, vis_label in VISIBILITIES_3D:
                cell = f"{shade}/{vis}"
                mine = res.get("drawMesh3d", s, cell, n)
                row = [s, f"{tri:,}" if tri else "?", shade_label, vis_label,
                       fmt_ms(res.get("drawMesh3d", s, cell, 1)), fmt_ms(mine)]
                if lt:
                    gl = res.get("llvmpipe", s, cell, lt)
                    row += [fmt_ms(gl), fmt_ratio(gl, mine)]
                row.append(fmt_ms(res.get("clear", s)))
                if any(c != "–" for c in row[4:-1]):  # a filtered run: measured cells only
                    rows.append(row)
    return rows


def time_table_textured_3d(res):
    """One row per 3D scene, shading and visibility: drawTexturedMesh3d at 1 and all threads,
    llvmpipe drawing the same textured mesh, their ratio, and drawMesh3d (vertex colours) at all
    threads when the run measured it (what the texture costs)."""
    n, lt = res.all_threads, res.llvmpipe_threads("llvmpipeTextured")
    head = ["scene", "triangles", "shading", "visibility", "drawTexturedMesh3d 1 thr",
            f"drawTexturedMesh3d {n} thr"]
    if lt:
        head += [f"llvmpipe textured {lt} thr", f"llvmpipe / drawTexturedMesh3d ({n} thr)"]
    plain = res.has("drawMesh3d")  # measured in this run
    if plain:
        head.append(f"drawMesh3d {n} thr (untextured)")
    rows = [head]
    for s in res.scenes3d:
        tri = res.counts.get(s, (None, None))[0]
        for shade, shade_label in SHADES_3D:
            for vis, vis_label in VISIBILITIES_3D:
                cell = f"{shade}/{vis}"
                mine = res.get("drawTexturedMesh3d", s, cell, n)
                row = [s, f"{tri:,}" if tri else "?", shade_label, vis_label,
                       fmt_ms(res.get("drawTexturedMesh3d", s, cell, 1)), fmt_ms(mine)]
                if lt:
                    gl = res.get("llvmpipeTextured", s, cell, lt)
                    row += [fmt_ms(gl), fmt_ratio(gl, mine)]
                measured = any(c != "–" for c in row[4:])  # a filtered run: measured cells only
                if plain:
                    row.append(fmt_ms(res.get("drawMesh3d", s, cell, n)))
                if measured:
                    rows.append(row)
    return rows


def targets_3d(res):
    """Lines on the 3D targets: llvmpipe / drawMesh3d at least 3x on every cell, the demo knot
    in Phong under 2 ms (all threads). Says met or missed; cells not measured are named."""
    n, lt = res.all_threads, res.llvmpipe_threads()
    lines = []
    ratios = []
    for s in res.scenes3d:
        for shade, _ in SHADES_3D:
            for vis, _ in VISIBILITIES_3D:
                mine = res.get("drawMesh3d", s, f"{shade}/{vis}", n)
                gl = res.get("llvmpipe", s, f"{shade}/{vis}", lt) if lt else None
                if mine is not None and gl is not None:
                    ratios.append((gl / mine, f"{s} {shade} {vis}"))
    if ratios:
        below = [f"{name} {r:.2f}x" for r, name in sorted(ratios) if r < TARGET_3D_RATIO]
        low, low_name = min(ratios)
        lines.append(f"- Target llvmpipe / drawMesh3d at least {TARGET_3D_RATIO:g}x at {n} threads "
                     f"on every 3D cell: lowest {low:.2f}x ({low_name}); "
                     + ("met" if not below else
                        f"missed on {len(below)} of {len(ratios)} cells: " + ", ".join(below)))
    else:
        lines.append("- Target llvmpipe / drawMesh3d: no llvmpipe 3D cells measured")
    for s in res.scenes3d:
        if not s.startswith("knot3d"):
            continue
        for vis, vis_label in VISIBILITIES_3D:
            ms = res.get("drawMesh3d", s, f"phong/{vis}", n)
            if ms is not None:
                verdict = "met" if ms < TARGET_3D_DEMO_MS else "missed"
                lines.append(f"- Target demo knot ({s}) in Phong, three lights, under "
                             f"{TARGET_3D_DEMO_MS:g} ms at {n} threads, {vis_label}: "
                             f"{fmt_ms(ms)} ms, {verdict}")
    return lines


def polygon_name(scene):
    """poly1000 -> "1,000 vertices", cross1000 -> "1,000 vertices, self-crossing"."""
    name = f"{int(re.sub(r'[^0-9]', '', scene)):,} vertices"
    return name + ", self-crossing" if scene.startswith("cross") else name


def polygon_table(res):
    """fillPolygons at 1 and all threads against cv::fillPoly, per polygon size."""
    n = max((k[3] for k in res.times if k[0] == "fillPolygons"), default=1)
    rows = [["polygon", "fillPolygons 1 thr", f"fillPolygons {n} thr", "cv::fillPoly",
             f"fillPoly / fillPolygons {n} thr", "triangulatePolygons", "gluTess"]]
    for s in res.poly_scenes:
        ours1, oursn = res.get("fillPolygons", s, None, 1), res.get("fillPolygons", s, None, n)
        theirs = res.get("fillPoly", s, None, 1)
        rows.append([polygon_name(s), fmt_ms(ours1), fmt_ms(oursn),
                     fmt_ms(theirs), fmt_ratio(theirs, oursn),
                     fmt_ms(res.get("triangulatePolygons", s, None, 1)),
                     fmt_ms(res.get("gluTess", s, None, 1))])
    return rows


def polygon_coverage_table(res):
    """From the context's polygon_coverage/SCENE ("covered C; METHOD D T; ..."): per
    tessellation, the samples whose coverage differs from fillPolygons' and those covered
    twice."""
    found = {}
    for c in res.contexts:
        for k, v in c.items():
            if k.startswith("polygon_coverage/"):
                parts = [p.split() for p in v.split(";")]
                found[k.split("/", 1)[1]] = (int(parts[0][1]),
                                             {p[0]: (int(p[1]), int(p[2])) for p in parts[1:]})
    if not found:
        return None
    methods = [m for m in ("triangulatePolygons", "gluTess")
               if any(m in f[1] for f in found.values())]
    rows = [["polygon", "samples covered"] + [f"{m}: differ / covered twice" for m in methods]]
    for s in sorted(found, key=lambda s: (s.startswith("cross"), int(re.sub(r"\D", "", s)))):
        covered, per = found[s]
        rows.append([polygon_name(s), f"{covered:,}"] +
                    [("{:,} / {:,}".format(*per[m]) if m in per else "–") for m in methods])
    return rows


def markdown(rows):
    out = ["| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
    out += ["| " + " | ".join(r) + " |" for r in rows[1:]]
    return "\n".join(out)


def series(res):
    """(label, method, shade, threads, style) of the plotted lines."""
    n = res.all_threads
    out = [(f"render flat ({n} thr)", "render", "flat", n, dict(color="C0", ls="-", marker="o")),
           (f"render Gouraud ({n} thr)", "render", "gouraud", n,
            dict(color="C0", ls="--", marker="o")),
           ("plain flat", "plain", "flat", 1, dict(color="C1", ls="-", marker="s")),
           ("plain Gouraud", "plain", "gouraud", 1, dict(color="C1", ls="--", marker="s")),
           ("fillConvexPoly", "fillConvexPoly", "flat", 1, dict(color="C2", ls="-", marker="^"))]
    if res.has("llvmpipe"):
        lt = res.llvmpipe_threads()
        out += [(f"llvmpipe flat ({lt} thr)", "llvmpipe", "flat", lt,
                 dict(color="C3", ls="-", marker="D")),
                (f"llvmpipe Gouraud ({lt} thr)", "llvmpipe", "gouraud", lt,
                 dict(color="C3", ls="--", marker="D"))]
    out.append(("clear (floor)", "clear", None, 1, dict(color="0.5", ls=":", marker=".")))
    return out


def plot(res, outdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"(no plots: matplotlib is not available to {sys.executable})", file=sys.stderr)
        return []
    os.makedirs(outdir, exist_ok=True)
    written = []

    # Time against triangle count: the scenes of the smallest canvas.
    side = min(int(re.sub(r"\D", "", s) or 0) for s in res.scenes)
    scenes = sorted((s for s in res.scenes if s.endswith(str(side)) and s in res.counts),
                    key=lambda s: res.counts[s][0])
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for label, m, sh, t, style in series(res):
        pts = [(res.counts[s][0], res.get(m, s, sh, t)) for s in scenes]
        pts = [p for p in pts if p[1] is not None]
        if pts:
            ax.plot(*zip(*pts), label=label, **style)
    ax.set(xscale="log", yscale="log", xlabel="triangles", ylabel="median time (ms)",
           title=f"Time against triangle count, {side}x{side} canvas")
    ax.set_xticks([res.counts[s][0] for s in scenes],
                  [f"{res.counts[s][0]:,}\n{re.sub(r'[0-9]+$', '', s)}" for s in scenes])
    ax.minorticks_off()
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    written.append(os.path.join(outdir, "perf_vs_triangles.png"))
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)

    # Time against canvas size: one panel per scene kind measured at several sizes.
    kinds = {}
    for s in res.scenes:
        m = re.match(r"([a-z]+)(\d+)$", s)
        if m:
            kinds.setdefault(m.group(1), []).append((int(m.group(2)), s))
    kinds = {k: v for k, v in kinds.items() if len(v) > 1}
    if kinds:
        fig, axes = plt.subplots(1, len(kinds), figsize=(4.5 * len(kinds), 4.5), sharey=True,
                                 squeeze=False)
        for ax, (kind, sizes) in zip(axes[0], kinds.items()):
            for label, m, sh, t, style in series(res):
                pts = [(side_, res.get(m, s, sh, t)) for side_, s in sorted(sizes)]
                pts = [p for p in pts if p[1] is not None]
                if pts:
                    ax.plot(*zip(*pts), label=label, **style)
            ax.set(xscale="log", yscale="log", xlabel="canvas side (pixels)", title=kind)
            ax.set_xticks([s for s, _ in sizes], [str(s) for s, _ in sizes])
            ax.minorticks_off()
            ax.grid(True, which="both", alpha=0.3)
        axes[0][0].set_ylabel("median time (ms)")
        axes[0][-1].legend(fontsize=7)
        fig.suptitle("Time against canvas size")
        fig.tight_layout()
        written.append(os.path.join(outdir, "perf_vs_canvas.png"))
        fig.savefig(written[-1], dpi=110)
        plt.close(fig)
    return written


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("json", nargs="+", help="Google Benchmark JSON output files")
    ap.add_argument("--plots", metavar="DIR", help="write PNG plots into DIR")
    args = ap.parse_args()

    res = Results(*load(args.json))
    if not res.scenes and not res.scenes3d and not res.poly_scenes:
        sys.exit("report.py: no benchmarks in " + ", ".join(args.json))
    print("\n".join(machine_lines(res)))
    if res.scenes:
        print("\nMedian time (ms):\n")
        print(markdown(time_table(res)))
        print(f"\nRatios (time of the baseline / time of render with {res.all_threads} "
              "threads; above 1: render is faster):\n")
        print(markdown(ratio_table(res)))
    if res.scenes3d and (res.has("drawMesh3d") or res.has("llvmpipe")):
        print("\n3D: drawMesh3d and llvmpipe (the same mesh, camera and lighting formula in "
              "GLSL), three point lights; median time (ms), and llvmpipe's time / drawMesh3d's "
              f"with {res.all_threads} threads (above 1: drawMesh3d is faster):\n")
        print(markdown(time_table_3d(res)))
        print()
        print("\n".join(targets_3d(res)))
    if res.scenes3d and (res.has("drawTexturedMesh3d") or res.has("llvmpipeTextured")):
        print("\nTextured 3D: drawTexturedMesh3d and llvmpipe drawing the same textured mesh "
              "(512 x 512 texture, bilinear, wrapped: BORDER_WRAP / GL_REPEAT), lit as the 3D "
              "cells; median time (ms), and llvmpipe's time / drawTexturedMesh3d's with "
              f"{res.all_threads} threads (above 1: drawTexturedMesh3d is faster):\n")
        print(markdown(time_table_textured_3d(res)))
    if res.poly_scenes:
        print("\nPolygons: fillPolygons against cv::fillPoly (LINE_8, 8 fractional bits) on "
              "random star-shaped concave polygons (polyN) and self-crossing ones (crossN), "
              "1024 x 1024 CV_8UC3, and their "
              "triangulation against GLU's tessellator; median time (ms):\n")
        print(markdown(polygon_table(res)))
        coverage = polygon_coverage_table(res)
        if coverage:
            print("\nThe triangulations drawn with the library's rasterizer (the same snapped "
                  "points; GLU's crossings from its combine callback), against fillPolygons' "
                  "coverage, even-odd; samples:\n")
            print(markdown(coverage))
    if args.plots and res.scenes:  # the plots are of the 2D scenes
        for path in plot(res, args.plots):
            print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
