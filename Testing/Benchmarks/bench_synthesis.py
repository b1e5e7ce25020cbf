#!/usr/bin/env python3
"""End-to-end synthesis speed, per stage, with ratios taken in the same run.

Cases (each a `tsynth synth` run; the per-stage split comes from --report):
  default   1024 x 1024 from one 648 x 648 exemplar (colorado, y_ridges), on
            the backend auto picks (the default), on OpenCL and on the CPU; the
            outputs must be identical.
  --large   4096 x 4096 from five exemplars (needs ../shared/data), on auto
            (--both: on all three).
  --dense   dense feature sets (on auto): a DEM as the target (alps-montblanc, 647 x 647)
            and a real DEM's own feature tree as a poly-line sketch (Mount
            Jackson's ridges and valleys from `tsynth features --both`), at the
            size the tree gives (957 x 1235) and at 648 x 648.
Comparisons (the figures that count on a shared, noisy machine):
  --vs BUILD    runs BUILD/bin/tsynth (for example the previous landing) on the
                same case, alternating with ours, --runs times; prints both
                medians and the median of the pair-by-pair ratios ours / BUILD,
                and whether the outputs are identical.
  --peer DIR    runs Tasse's CPU code (built in DIR by ../shared/peers/tasse/
                build.sh) once on the default case's sketch scaled to the
                output size, and prints its time over our median.
  --preview     each run writes the quick coarse look first (tsynth synth
                --preview): its seconds (in the process: set-up, synthesis,
                upsampling) are printed with their ratio to the same run's whole
                synthesis and, with --vs, to the baseline's preview; then
                the last preview's own stages (its report's times_s).
  --rss         samples our resident memory every 0.25 s and says when, in
                which stage, it peaked (on with --large).
  --edit        also times the re-synthesis of edits (tsynth synth --previous)
                against full tiled syntheses of the same edited sketches, pair by
                pair, and checks their bits: bench_local_edit.py's cases.
  --cache       ours reads the exemplars' preparation back from an exemplar
                cache (in the temporary folder, filled by one untimed run):
                a redrawn sketch. Without it every build that has a cache
                runs with --no-cache, so ratios compare the same work.
Timings are reported, never asserted.

Usage: bench_synthesis.sh [--large [--both]] [--dense] [--vs BUILD] [--peer DIR]
                          [--cache] [--preview] [--rss] [--edit] [--runs N] [build dir]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
DATA = os.path.join(ROOT, "Data")
LARGE_EXEMPLARS = ["colorado", "alaska", "appalachians", "himalaya-everest", "andes-chile"]


class Case:
    """One synthesis: its label, tsynth synth arguments and backends to time."""

    def __init__(self, label, args, backends, sketch=None, size=None):
        self.label = label
        self.args = args
        self.backends = backends
        self.sketch = sketch  # the raster sketch the peer can read, if any
        self.size = size      # (width, height) for the peer's scaled sketch


def fail(message):
    print("bench_synthesis: " + message, file=sys.stderr)
    sys.exit(2)


def cache_args(tsynth, cache_dir):
    """How a build runs: reading a cache in cache_dir, or with none (older builds have none)."""
    help_text = subprocess.run([tsynth, "synth", "--help"], capture_output=True, text=True).stdout
    if "--no-cache" not in help_text:
        return []
    return ["--cache", cache_dir] if cache_dir else ["--no-cache"]


def preview_args(tsynth, tmp, wanted):
    """--preview into tmp when wanted and the build has it."""
    help_text = subprocess.run([tsynth, "synth", "--help"], capture_output=True, text=True).stdout
    if not wanted or "--preview" not in help_text:
        return []
    return ["--preview", os.path.join(tmp, f"preview-{abs(hash(tsynth))}.tif")]


def preview_line(label, seconds, wholes):
    """Median preview seconds and their median ratio to the same runs' whole synthesis."""
    ratios = [p / w for p, w in zip(seconds, wholes)]
    return (f"{label} preview {statistics.median(seconds):.3f} s (median of {len(seconds)}), "
            f"{statistics.median(ratios):.3f} of the same run's synthesis")


RSS_INTERVAL_S = 0.25  # resident memory sampled this often with --rss


def resident_gb(pid):
    """The process's resident memory now, GB (None once it has gone)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024 / 1e9
    except OSError:
        return None
    return None


def child_pid(pid):
    """The one child of /usr/bin/time: the tsynth it runs (None until it has started)."""
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            children = f.read().split()
    except OSError:
        return None
    return int(children[0]) if children else None


def run_synth(tsynth, case, backend, out, report, extra=(), rss=False):
    """One timed run; returns (wall seconds, report dict with its peak memory in GB added, and
    with rss its resident memory over time as [seconds, GB] pairs)."""
    command = [tsynth, "synth", *case.args, "--backend", backend, "-o", out,
               "--report", report, "--no-progress", *extra]
    peak = report + ".peak"
    start = time.monotonic()
    process = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", peak, *command],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    samples = []
    while rss and process.poll() is None:
        pid = child_pid(process.pid)
        gb = resident_gb(pid) if pid else None
        if gb is not None:
            samples.append([time.monotonic() - start, gb])
        time.sleep(RSS_INTERVAL_S)
    _, err = process.communicate()
    wall = time.monotonic() - start
    if process.returncode != 0:
        fail(f"{' '.join(command)} failed: {err.strip()}")
    with open(report) as f:
        result = json.load(f)
    with open(peak) as f:
        result["peak_gb"] = int(f.read().split()[-1]) * 1024 / 1e9  # kB of resident memory
    result["rss"] = samples
    return wall, result


def rss_line(report):
    """Where resident memory peaked among the samples: when, and in which stage (the report's
    stage times laid end to end from the start of the process)."""
    samples = report.get("rss")
    if not samples:
        return None
    when, gb = max(samples, key=lambda s: s[1])
    t = report["times_s"]
    names = {"prepare": "preparation", "setup": "matcher set-up", "features": "feature placement",
             "fill": "fill", "finish": "finishing", "write": "writing", "measure": "measures"}
    stage, end = "measures", 0.0
    for name in names:
        end += t.get(name, 0.0)  # a baseline's report may lack the later stages
        if when <= end:
            stage = names[name]
            break
    median = statistics.median(s[1] for s in samples)
    return (f"resident memory (sampled every {RSS_INTERVAL_S} s): peak {gb:.2f} GB at {when:.1f} s, "
            f"in the {stage}; median {median:.2f} GB")


def stages(report):
    t = report["times_s"]
    features = report.get("feature_placements", 0)
    fills = report["placements"] - features
    cache = report.get("exemplar_cache")
    exemplars = "" if not cache else (f" (of it the exemplars' {cache['seconds']:.2f}, "
                                      f"{'read back' if cache['hit'] else 'computed'})")
    after = "" if "finish" not in t else (f", finishing {t['finish']:.2f}, writing {t['write']:.2f}, "
                                          f"figures {t['measure']:.2f}")
    return (f"prepare {t['prepare']:.2f}{exemplars}, matcher setup {t['setup']:.2f}, features "
            f"{t['features']:.2f} ({1e3 * t['features'] / max(1, features):.1f} ms for each of "
            f"{features}), fill {t['fill']:.2f} ({1e3 * t['fill'] / max(1, fills):.1f} ms for "
            f"each of {fills}){after}; peak memory {report['peak_gb']:.2f} GB")


def same_file(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def time_case(case, tsynth, baseline, runs, tmp, cached, preview, rss=False):
    """Times each backend of the case; returns our median wall (first backend)."""
    print(case.label)
    ours_extra = cache_args(tsynth, os.path.join(tmp, "cache") if cached else None)
    ours_extra += preview_args(tsynth, tmp, preview)
    base_extra = cache_args(baseline, None) + preview_args(baseline, tmp, preview) if baseline else []
    if cached:  # fills the cache, untimed
        run_synth(tsynth, case, case.backends[0], os.path.join(tmp, "warm.tif"),
                  os.path.join(tmp, "rep.json"), ours_extra)
    medians = {}
    outputs = {}
    for backend in case.backends:
        ours, theirs, ratios = [], [], []
        previews = {"ours": ([], []), "baseline": ([], [])}  # (preview s, whole synthesis s)
        report = None
        for r in range(runs):
            out = os.path.join(tmp, f"ours-{backend}.tif")
            wall, report = run_synth(tsynth, case, backend, out, os.path.join(tmp, "rep.json"),
                                     ours_extra, rss)
            ours.append(wall)
            if "preview" in report:
                previews["ours"][0].append(report["preview"]["seconds"])
                previews["ours"][1].append(wall)
            if baseline:
                base_out = os.path.join(tmp, f"base-{backend}.tif")
                base_wall, base_report = run_synth(baseline, case, backend, base_out,
                                                   os.path.join(tmp, "rep-base.json"), base_extra)
                theirs.append(base_wall)
                ratios.append(wall / base_wall)
                if "preview" in base_report:
                    previews["baseline"][0].append(base_report["preview"]["seconds"])
                    previews["baseline"][1].append(base_wall)
        outputs[backend] = out
        medians[backend] = statistics.median(ours)
        label = f"auto ({report['backend'].split(' ')[0]})" if backend == "auto" else backend
        line = f"  {label:>6}: {medians[backend]:6.2f} s end to end (median of {runs}); {stages(report)}"
        print(line)
        if rss_line(report):
            print("          ours' last run: " + rss_line(report))
        if baseline:
            print(f"          baseline {statistics.median(theirs):6.2f} s; ours / baseline "
                  f"{statistics.median(ratios):.3f} (pairs: {', '.join(f'{x:.3f}' for x in ratios)});"
                  f" output {'identical' if same_file(out, base_out) else 'DIFFERENT'}")
            print(f"          baseline's last run: {stages(base_report)}")
        for who, (seconds, wholes) in previews.items():
            if seconds:
                print("         " + preview_line(who, seconds, wholes))
        if "times_s" in report.get("preview", {}):
            t = report["preview"]["times_s"]
            split = ", ".join(f"{k} {t[k]:.3f}" for k in ("prepare", "setup", "features", "fill", "finish"))
            print(f"          ours' last preview: {split}")
        if previews["ours"][0] and previews["baseline"][0]:
            pairs = [a / b for a, b in zip(*(previews[w][0] for w in ("ours", "baseline")))]
            print(f"          preview ours / baseline {statistics.median(pairs):.3f}")
    if len(outputs) >= 2:
        first, *others = outputs.values()
        same = all(same_file(first, other) for other in others)
        print(f"  identical output on all {len(outputs)} backends" if same else "  OUTPUTS DIFFER")
    return medians[case.backends[0]]


def run_peer(peer, case, ours_wall, tmp):
    """Tasse's CPU code on the case's sketch at the output size, once."""
    if case.sketch is None:
        return
    width, height = case.size
    scaled = os.path.join(tmp, "peer-sketch.png")
    subprocess.run(["gdal_translate", "-q", "-of", "PNG", "-r", "near", "-outsize", str(width),
                    str(height), case.sketch, scaled], check=True)
    exemplar = case.args[case.args.index("--exemplar") + 1]
    start = time.monotonic()
    done = subprocess.run(["bash", os.path.join(SHARED, "peers", "tasse", "run.sh"), peer, exemplar,
                           scaled, os.path.join(tmp, "peer.tif")], capture_output=True, text=True)
    wall = time.monotonic() - start
    if done.returncode != 0:
        fail("the peer failed: " + (done.stderr.strip() or done.stdout.strip()))
    print(f"  peer (Tasse's CPU code, one thread): {wall:6.1f} s; ours is {wall / ours_wall:.1f}x "
          f"faster")


def tree_sketch(tsynth, tmp):
    """Mount Jackson's ridges and valleys as a poly-line sketch (written once)."""
    dem = os.path.join(SHARED, "data", "dems", "mount_jackson_n39_w107_3arc.tif")
    tree = os.path.join(tmp, "jackson-tree.vtp")
    subprocess.run([tsynth, "features", dem, "--both", "-o", tree], check=True,
                   stdout=subprocess.DEVNULL)
    return tree


def cases(options, tsynth, tmp):
    colorado = os.path.join(DATA, "dems", "colorado.png")
    y_ridges = os.path.join(DATA, "sketches", "strokes_y_ridges.png")
    if options.large:
        args = []
        for dem in LARGE_EXEMPLARS:
            args += ["--exemplar", os.path.join(SHARED, "data", "dems", dem + ".png")]
        args += ["--sketch", os.path.join(SHARED, "data", "sketches", "strokes_valley_meander.png"),
                 "--size", "4096x4096"]
        yield Case("4096x4096 from five exemplars", args,
                   ["auto", "opencl", "cpu"] if options.both else ["auto"])
        return
    yield Case("1024x1024 from one exemplar",
               ["--exemplar", colorado, "--sketch", y_ridges, "--size", "1024x1024"],
               ["auto", "opencl", "cpu"], sketch=y_ridges, size=(1024, 1024))
    if options.dense:
        montblanc = os.path.join(DATA, "dems", "alps-montblanc.png")
        yield Case("a DEM as the target (alps-montblanc, 647x647), colorado exemplar",
                   ["--exemplar", colorado, "--sketch", montblanc], ["auto"],
                   sketch=montblanc, size=(647, 647))
        tree = tree_sketch(tsynth, tmp)
        yield Case("Mount Jackson's feature tree as the sketch, colorado exemplar",
                   ["--exemplar", colorado, "--sketch", tree], ["auto"])
        # The size issue 21's dense-feature goal is stated at.
        yield Case("Mount Jackson's feature tree as the sketch at 648x648, colorado exemplar",
                   ["--exemplar", colorado, "--sketch", tree, "--size", "648x648"], ["auto"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    parser.add_argument("--large", action="store_true")
    parser.add_argument("--both", action="store_true", help="--large on OpenCL and on the CPU too")
    parser.add_argument("--dense", action="store_true")
    parser.add_argument("--vs", metavar="BUILD", help="a baseline build directory")
    parser.add_argument("--peer", metavar="DIR", help="where Tasse's code was built")
    parser.add_argument("--cache", action="store_true",
                        help="ours reads the exemplars' preparation from a warm cache")
    parser.add_argument("--preview", action="store_true",
                        help="each run writes --preview first; its seconds are reported")
    parser.add_argument("--rss", action="store_true",
                        help="sample our resident memory over each run (on with --large)")
    parser.add_argument("--edit", action="store_true",
                        help="also bench_local_edit.py: --previous against a full synthesis")
    parser.add_argument("--runs", type=int, default=3, help="runs per case and backend (default 3)")
    options = parser.parse_args()
    if options.runs < 1:
        fail("--runs must be at least 1")
    tsynth = os.path.join(options.build, "bin", "tsynth")
    baseline = os.path.join(options.vs, "bin", "tsynth") if options.vs else None
    for program in filter(None, [tsynth, baseline]):
        if not os.access(program, os.X_OK):
            fail(f"no tsynth at {program}; build it first")
    if (options.large or options.dense or options.peer) and not os.path.isdir(SHARED):
        fail("--large, --dense and --peer need ../shared beside the checkout")
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases(options, tsynth, tmp):
            ours = time_case(case, tsynth, baseline, options.runs, tmp, options.cache,
                             options.preview, options.rss or options.large)
            if options.peer:
                run_peer(options.peer, case, ours, tmp)
    if options.edit:
        edit = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                            "bench_local_edit.py"),
                               "--runs", str(options.runs), options.build])
        if edit.returncode != 0:
            fail("a re-synthesised edit differs from the full synthesis")


if __name__ == "__main__":
    main()
