"""The many-seed quality sweep: a tsynth against another (the previous landing, say), run for run.

The bundled stroke sketches (the Y of ridges and the valley meander) with Colorado and Mont Blanc,
seeds 0-10 by default: 44 terrains per build, all at default settings, each measured by this build's
`tsynth evaluate` (so a build without the newer measures is judged by the same ones). Prints the means
of the legible share, the flank agreement, the slope distance, the seam index and the valleys'
drainage per build, and on how many of the runs A beats B (lower slope distance and seam index,
higher legibility, flank agreement and drainage).

    /usr/bin/python3 Testing/Benchmarks/sweep_seeds.py --tsynth build/bin/tsynth \\
        [--a A_TSYNTH] [--b B_TSYNTH] [--data Data] [--seeds 0 1 ... 10] [--by-sketch]
        [--sketches SKETCH ...] [--exemplars DEM ...]

--sketches and --exemplars sweep other drawings (say those of Examples/legibility/draw_sketches.py,
whose isolated strokes and dashes the short-stroke experiments of the tenth session's note used, with
../shared/data/dems/colorado.png and alps-montblanc.png) instead of the bundled ones.

A defaults to --tsynth. About 2.5 minutes per build on two cores. Against the previous landing
(4230cf3): legible 0.556 vs 0.300 (A better on 43 of 44), slope 0.043 vs 0.056 (35), seam 0.898 vs
0.894 (20), drainage 0.537 vs 0.512 (25). Exits 0 whatever the figures: it
reports; the tests assert.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
SKETCHES = ("strokes_y_ridges.png", "strokes_valley_meander.png")
EXEMPLARS = ("colorado.png", "alps-montblanc.png")
# figure: (where in evaluate's "terrain" JSON, True when higher is better)
FIGURES = {
    "legible": (("legibility", "legible_share"), True),
    "flanks": (("legibility", "flank_agreement"), True),
    "slope": (("slope_distance",), False),
    "seam": (("seam_index",), False),
    "drainage": (("landforms", "valley_drainage"), True),
}


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=900)
    if result.returncode != 0:
        raise SystemExit("%s failed: %s" % (" ".join(command[:2]), result.stderr.strip()))
    return result.stdout


def figure(terrain, path):
    value = terrain
    for key in path:
        value = value.get(key) if isinstance(value, dict) else None
    return value


def sweep(synth, measure, cases, seeds, tmp, label):
    """{(sketch, exemplar, seed): {figure: value}} for every run of one build."""
    out = {}
    for sketch, drawn in cases[0]:
        for exemplar, dem in cases[1]:
            for seed in seeds:
                terrain = os.path.join(tmp, "%s_%s_%s_%d.tif" % (label, sketch, exemplar, seed))
                run([synth, "synth", "--exemplar", dem, "--sketch", drawn, "--seed", str(seed), "-o", terrain,
                     "--no-progress"])
                t = json.loads(run([measure, "evaluate", terrain, "--exemplar", dem, "--sketch", drawn,
                                    "--json"]))["terrain"]
                out[(sketch, exemplar, seed)] = {name: figure(t, where) for name, (where, _) in FIGURES.items()}
                os.remove(terrain)
            print("%s: %s with %s done" % (label, sketch, exemplar), file=sys.stderr)
    return out


def mean(values):
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tsynth", required=True, help="this build's tsynth (measures)")
    parser.add_argument("--a", help="the tsynth swept (default: --tsynth)")
    parser.add_argument("--b", help="the tsynth it is compared with, run for run")
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "Data"), help="the bundled Data/")
    parser.add_argument("--seeds", type=int, nargs="+", default=list(range(11)))
    parser.add_argument("--sketches", nargs="+", help="sketch files to sweep instead of the bundled two")
    parser.add_argument("--exemplars", nargs="+", help="exemplar DEMs to sweep instead of Colorado and Mont Blanc")
    parser.add_argument("--by-sketch", action="store_true",
                        help="also print each figure's means per sketch and exemplar")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="tsynth-sweep-") as tmp:
        sketches = [(os.path.basename(p), p) for p in args.sketches] if args.sketches else \
            [(s, os.path.join(args.data, "sketches", s)) for s in SKETCHES]
        exemplars = [(os.path.basename(p), p) for p in args.exemplars] if args.exemplars else \
            [(e, os.path.join(args.data, "dems", e)) for e in EXEMPLARS]
        cases = (sketches, exemplars)
        a = sweep(args.a or args.tsynth, args.tsynth, cases, args.seeds, tmp, "A")
        b = sweep(args.b, args.tsynth, cases, args.seeds, tmp, "B") if args.b else None
    print("%d runs per build (%d seeds x %d sketches x %d exemplars)" % (
        len(a), len(args.seeds), len(sketches), len(exemplars)))
    print("%-9s %8s" % ("figure", "A mean") + (" %8s %s" % ("B mean", "A better") if b is not None else ""))
    for name, (_, higher) in FIGURES.items():
        line = "%-9s %8.3f" % (name, mean(r[name] for r in a.values()))
        if b is not None:
            pairs = [(a[k][name], b[k][name]) for k in a if a[k][name] is not None and b[k][name] is not None]
            better = sum(1 for x, y in pairs if (x > y if higher else x < y))
            line += " %8.3f %d of %d" % (mean(r[name] for r in b.values()), better, len(pairs))
        print(line)
    if args.by_sketch:
        print_by_sketch(a, b, [s for s, _ in sketches], [e for e, _ in exemplars])


def print_by_sketch(a, b, sketches, exemplars):
    """The means of each figure per sketch and exemplar (A, then B where swept)."""
    print("%-28s %-20s %s" % ("sketch", "exemplar", "  ".join("%-15s" % name for name in FIGURES)))
    for sketch in sketches:
        for exemplar in exemplars:
            cells = []
            for name in FIGURES:
                keys = [k for k in a if k[0] == sketch and k[1] == exemplar]
                cell = "%.3f" % mean(a[k][name] for k in keys)
                if b is not None:
                    cell += " %.3f" % mean(b[k][name] for k in keys)
                cells.append("%-15s" % cell)
            print("%-28s %-20s %s" % (sketch, exemplar, "  ".join(cells)))


if __name__ == "__main__":
    main()
