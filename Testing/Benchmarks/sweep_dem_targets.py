"""Real DEMs as targets: a tsynth against another (the previous landing, say), run for run.

Dense feature sets are where feature placement costs most and where the spacing of feature sites
matters (Kernels/Synthesis/Target.cxx, kSiteClearanceInPatches). Each of four DEMs from
../shared/data/dems (alps-montblanc, appalachians, andes-chile, norway) is the target, and each of
two others (colorado, himalaya-everest) the exemplar: 8 terrains per build at default settings on
the CPU backend. Per run and per build it prints the feature and fill placements, the seconds of
feature placement and of the fill, the band-pass correlation with the target at 2, 4 and 8 cells,
the seam index, the slope distance and the ridge and valley fidelity (all from `--report`), then
the mean of each figure per build and the mean difference A - B.

    /usr/bin/python3 Testing/Benchmarks/sweep_dem_targets.py --a build/bin/tsynth \\
        [--b OTHER/bin/tsynth] [--shared ../shared] [--seed 0]

About 30 s per build on two cores. Timings are reported, never asserted; exits 0 whatever the
figures (it reports; the tests assert).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
TARGETS = ("alps-montblanc", "appalachians", "andes-chile", "norway")
EXEMPLARS = ("colorado", "himalaya-everest")


def figures(report):
    """The figures of one run, by name, from its --report JSON."""
    times = report.get("times_s", {})
    quality = report.get("quality", {})
    correlation = report.get("target_correlation") or []
    out = {
        "feature patches": report.get("feature_placements"),
        "placements": report.get("placements"),
        "features s": times.get("features"),
        "fill s": times.get("fill"),
        "seam index": quality.get("seam_index"),
        "slope distance": quality.get("slope_distance"),
    }
    for band in correlation[:3]:
        out["corr %g" % band["sigma_cells"]] = band["correlation"]
    for kind in ("ridge", "valley"):
        value = quality.get(kind + "_fidelity")
        if value is not None:
            out[kind + " fidelity"] = value
    return out


def sweep(tsynth, shared, seed, tmp, label):
    """{(target, exemplar): figures} for every run of one build."""
    runs = {}
    for target in TARGETS:
        for exemplar in EXEMPLARS:
            out = os.path.join(tmp, "%s_%s_%s.tif" % (label, target, exemplar))
            report = os.path.join(tmp, "%s_%s_%s_report.json" % (label, target, exemplar))
            command = [tsynth, "synth", "--exemplar", os.path.join(shared, "data", "dems", exemplar + ".png"),
                       "--sketch", os.path.join(shared, "data", "dems", target + ".png"),
                       "--backend", "cpu", "--seed", str(seed), "--no-progress",
                       "-o", out, "--report", report]
            done = subprocess.run(command, capture_output=True, text=True, timeout=900)
            if done.returncode != 0:
                raise SystemExit("%s failed on %s / %s: %s" % (tsynth, target, exemplar,
                                                               done.stderr.strip()))
            with open(report) as f:
                runs[(target, exemplar)] = figures(json.load(f))
    return runs


def show(value):
    if value is None:
        return "-"
    return "%d" % value if isinstance(value, int) else "%.3f" % value


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--a", required=True, help="the tsynth to judge")
    parser.add_argument("--b", help="the tsynth to compare with (optional)")
    parser.add_argument("--shared", default=os.path.join(here, "..", "..", "..", "shared"))
    parser.add_argument("--seed", type=int, default=0)
    options = parser.parse_args()
    builds = [("A", options.a)] + ([("B", options.b)] if options.b else [])
    with tempfile.TemporaryDirectory() as tmp:
        results = {label: sweep(tsynth, options.shared, options.seed, tmp, label)
                   for label, tsynth in builds}
    names = list(next(iter(results["A"].values())).keys())
    for key in results["A"]:
        print("%s as target, %s exemplar" % key)
        for label, _ in builds:
            print("  %s: %s" % (label, ", ".join("%s %s" % (n, show(results[label][key].get(n)))
                                               for n in names)))
    print("\nmeans over the %d runs" % len(results["A"]))
    for name in names:
        means = {}
        for label, _ in builds:
            values = [r[name] for r in results[label].values() if r.get(name) is not None]
            means[label] = statistics.mean(values) if values else None
        line = "  %-16s " % name + "  ".join("%s %s" % (label, show(means[label])) for label, _ in builds)
        if options.b and means["A"] is not None and means["B"] is not None:
            diffs = [results["A"][k][name] - results["B"][k][name] for k in results["A"]
                     if results["A"][k].get(name) is not None and results["B"][k].get(name) is not None]
            line += "  A - B %+.3f" % statistics.mean(diffs)
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
