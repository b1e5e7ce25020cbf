#!/usr/bin/env python3
"""A cost model of tiled synthesis on N MPI ranks (issue 22), measured, not guessed.

    python3 Testing/Benchmarks/tile_cost_model.py [--sizes 1024 2048] [--tile 256] [--ranks 1 2 4]
                                                  [--extrapolate 16384] [--tsynth PATH]

1. Measures. `tsynth synth --tile-size T --report` on one thread (OMP_NUM_THREADS=1, the CPU
   backend) at each of --sizes gives every tile pass's cost (the report's "tiles") and the part
   every rank repeats whole: the rest of the run (reading, set-up, finishing, writing), fitted as
   a + b * cells over the sizes.
2. Checks the schedule against real ranks. `mpiexec -np N pvbatch Examples/pvbatch/tiled_synthesis.py`
   on the largest size, one thread per rank, oversubscribed past the cores: each rank's closing line
   gives its CPU time in tiles, set beside the sum of the one-process costs of the tiles the schedule
   gives it (tile k of a colour step goes to rank k mod N). On more ranks than cores only CPU times
   are comparable; wall times are printed for N up to the core count.
3. Extrapolates. A run on N ranks takes the repeated part, plus, for each step of the tile schedule
   (4 colour classes x 2 passes, each waiting for its slowest rank), the most any rank places in it,
   at the mean measured cost of a tile pass. It prints time, speed-up and efficiency for 1 to 64
   ranks at --extrapolate cells a side, and where adding ranks stops paying (efficiency under one
   half) and why: a colour step of fewer tiles than ranks, or the repeated whole-terrain part. The
   last column is the placement's own speed-up, which bounds what tiling the whole-terrain part
   (the target's set-up, the finishing) would gain.

Timings are reported, never asserted: the machine is shared.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "Data")
SCRIPT = os.path.join(ROOT, "Examples", "pvbatch", "tiled_synthesis.py")
PLUGIN = os.path.join(ROOT, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so")
COLOURS = 4  # the 2 x 2 colour classes of Kernels/Synthesis/Tiling.h
PASSES = ("features", "fill")
# Efficiency below which more ranks are not worth having.
WORTHWHILE_EFFICIENCY = 0.5
RANK_LINE = re.compile(r"rank (\d+) of (\d+): (\d+) feature and (\d+) fill tile passes in ([\d.]+) s "
                       r"\(CPU ([\d.]+) s\), waited ([\d.]+) s")


def one_thread_env():
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    env["OMP_NUM_THREADS"] = "1"
    env["TSYNTH_PLUGIN"] = PLUGIN
    return env


def inputs():
    return ["--exemplar", os.path.join(DATA, "dems", "colorado.png"),
            "--sketch", os.path.join(DATA, "sketches", "strokes_y_ridges.png")]


def measure_one_process(tsynth, size, tile, tmp):
    out = os.path.join(tmp, "one%d.tif" % size)
    report = os.path.join(tmp, "one%d-report.json" % size)
    start = time.monotonic()
    done = subprocess.run([tsynth, "synth", *inputs(), "--size", "%dx%d" % (size, size), "--tile-size", str(tile),
                           "--backend", "cpu", "--no-progress", "-o", out, "--report", report],
                          env=one_thread_env(), capture_output=True, text=True)
    wall = time.monotonic() - start
    if done.returncode != 0:
        sys.exit("tsynth synth failed: " + done.stderr.strip())
    with open(report) as f:
        r = json.load(f)
    tiles = r["tiles"]
    in_tiles = sum(t["seconds"] for t in tiles)
    # The figures tsynth prints (times_s.measure) are no part of a pvbatch run: left out.
    return {"size": size, "cells": size * size, "wall": wall, "tiles": tiles, "in_tiles": in_tiles,
            "repeated": wall - in_tiles - r["times_s"]["measure"]}


def steps_of(tiles):
    """The schedule's steps: runs of tile passes of one pass and colour, in the order placed."""
    steps = []
    for t in tiles:
        key = (t["pass"], t["colour"])
        if not steps or steps[-1][0] != key:
            steps.append((key, []))
        steps[-1][1].append(t)
    return [s for _, s in steps]


def rank_loads(tiles, ranks):
    """CPU seconds each rank spends in tiles when the schedule gives tile k of a step to rank k mod N."""
    load = [0.0] * ranks
    for step in steps_of(tiles):
        for k, t in enumerate(step):
            load[k % ranks] += t["cpu_seconds"]
    return load


def placement_on(tiles, ranks):
    """Wall seconds of the placement on N ranks: each step waits for its busiest rank."""
    total = 0.0
    for step in steps_of(tiles):
        load = [0.0] * ranks
        for k, t in enumerate(step):
            load[k % ranks] += t["seconds"]
        total += max(load)
    return total


def check_against_ranks(size, tile, ranks_list, one, tmp):
    mpiexec, pvbatch = shutil.which("mpiexec"), shutil.which("pvbatch")
    if not mpiexec or not pvbatch:
        print("  (no mpiexec or pvbatch here: the check against real ranks is skipped)")
        return
    cores = os.cpu_count() or 1
    print("  ranks  rank: CPU in tiles measured / from the schedule   wall measured / modelled")
    repeated = None  # pvbatch's own: its start-up and the whole-terrain part, from the 1-rank run
    for n in sorted(ranks_list):
        out = os.path.join(tmp, "ranks%d.pvti" % n)
        start = time.monotonic()
        done = subprocess.run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-np", str(n), pvbatch, SCRIPT,
                               *inputs(), "--size", "%dx%d" % (size, size), "--tile-size", str(tile), "-o", out],
                              env=one_thread_env(), capture_output=True, text=True)
        wall = time.monotonic() - start
        if done.returncode != 0:
            print("  %5d  failed: %s" % (n, (done.stderr or done.stdout).strip().splitlines()[-1:]))
            continue
        measured = {int(m.group(1)): float(m.group(6)) for m in RANK_LINE.finditer(done.stdout)}
        predicted = rank_loads(one["tiles"], n)
        per_rank = "  ".join("%d: %.2f/%.2f" % (r, measured.get(r, float("nan")), predicted[r]) for r in range(n))
        if n == 1:
            repeated = wall - one["in_tiles"]
            per_rank = "no sharing; pvbatch repeats %.1f s outside the tiles (tsynth %.1f s)" % (
                repeated, one["repeated"])
        modelled = (repeated if repeated is not None else one["repeated"]) + placement_on(one["tiles"], n)
        walls = ("%.1f / %.1f s" % (wall, modelled)) if n <= cores else "(oversubscribed)"
        print("  %5d  %s   %s" % (n, per_rank, walls))


def fit_repeated(runs):
    """The repeated part as a + b * cells, from the runs at two or more sizes (least squares)."""
    if len(runs) < 2:
        return runs[0]["repeated"], 0.0
    xs = [r["cells"] for r in runs]
    ys = [r["repeated"] for r in runs]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - b * mx, b


def extrapolate(runs, tile, side):
    a, b = fit_repeated(runs)
    biggest = max(runs, key=lambda r: r["size"])
    per_pass = {p: [t["seconds"] for t in biggest["tiles"] if t["pass"] == p] for p in PASSES}
    mean = {p: sum(v) / len(v) for p, v in per_pass.items()}
    across = math.ceil(side / tile)
    per_colour = math.ceil(across / 2) ** 2  # the fullest colour class
    repeated = a + b * side * side
    print("\nExtrapolated to %d x %d cells in tiles of %d (%d x %d tiles, up to %d in a colour step); a tile "
          "pass costs %.2f s (features) and %.2f s (fill) on one thread; every rank repeats %.1f s "
          "(%.2f s + %.3g s per cell)." % (side, side, tile, across, across, per_colour, mean["features"],
                                           mean["fill"], repeated, a, b))
    print("  ranks  time s   speed-up  efficiency  tiles a rank places per step   placement alone: speed-up")
    one = None
    placement_one = None
    stop = None
    for n in (1, 2, 4, 8, 16, 32, 64):
        per_rank = math.ceil(per_colour / n)
        placement = COLOURS * per_rank * (mean["features"] + mean["fill"])
        total = repeated + placement
        one = one or total
        placement_one = placement_one or placement
        efficiency = one / total / n
        print("  %5d  %7.1f  %8.2f  %10.2f  %29d   %8.2f" % (n, total, one / total, efficiency, per_rank,
                                                             placement_one / placement))
        if stop is None and efficiency < WORTHWHILE_EFFICIENCY:
            why = ("a colour step holds %d tiles, fewer than the ranks" % per_colour if per_colour < n else
                   "the whole-terrain part every rank repeats (%.0f s) outweighs the %.0f s of placement "
                   "left to each" % (repeated, placement))
            stop = "Past %d ranks the efficiency falls under %.1f: %s." % (n // 2, WORTHWHILE_EFFICIENCY, why)
    print(stop or "It keeps an efficiency of %.1f or more up to 64 ranks." % WORTHWHILE_EFFICIENCY)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[1024, 2048])
    p.add_argument("--tile", type=int, default=256)
    p.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    p.add_argument("--extrapolate", type=int, default=16384)
    p.add_argument("--tsynth", default=os.path.join(ROOT, "build", "bin", "tsynth"))
    a = p.parse_args()
    tmp = tempfile.mkdtemp(prefix="tsynth-cost-")
    try:
        runs = []
        for size in sorted(a.sizes):
            r = measure_one_process(a.tsynth, size, a.tile, tmp)
            runs.append(r)
            costs = sorted(t["seconds"] for t in r["tiles"])
            print("%d x %d in tiles of %d, one process, one thread: %.1f s, of which %d tile passes %.1f s "
                  "(median %.2f s, slowest %.2f s), the rest %.1f s" % (
                      size, size, a.tile, r["wall"], len(costs), r["in_tiles"], costs[len(costs) // 2],
                      costs[-1], r["repeated"]))
        largest = runs[-1]
        print("\nThe schedule against real ranks, %d x %d on pvbatch, one thread each:" % ((largest["size"],) * 2))
        check_against_ranks(largest["size"], a.tile, a.ranks, largest, tmp)
        extrapolate(runs, a.tile, a.extrapolate)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
