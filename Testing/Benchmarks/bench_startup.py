"""How long tsynth synth takes to start, and to show its preview, through the launcher.

    python3 Testing/Benchmarks/bench_startup.py [build dir] [--runs N]

tsynth (Apps/Launcher.cxx) puts synth's runtime settings in the environment and becomes
tsynth-main, which loads its libraries (136, VTK and GDAL among them) once. tsynth-main run alone sets them
itself and re-runs: the way every synth started before the launcher. Each pair runs both, in
alternating order, with the user's OMP_WAIT_POLICY and GLIBC_TUNABLES cleared:
  start:   synth on a missing exemplar, which fails as soon as the command line is read;
  preview: seconds from the start to the preview file of the bundled Y of ridges at 1024^2
           (the user's first look), after which the run is stopped (Ctrl-C).
Prints the medians and the median of the per-pair ratios (launcher / alone). Timings are
reported, never asserted.
"""
import argparse
import os
import signal
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# How often the preview file is looked for, in seconds: well under the start-up differences.
POLL_SECONDS = 0.002


def clean_environment():
    return {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GLIBC_TUNABLES")}


def seconds_to_start(program, tmp):
    start = time.monotonic()
    result = subprocess.run([program, "synth", "--exemplar", os.path.join(tmp, "absent.png"),
                             "--sketch", os.path.join(tmp, "absent.png"), "-o",
                             os.path.join(tmp, "out.tif")],
                            env=clean_environment(), capture_output=True)
    if result.returncode != 1:
        raise SystemExit("%s did not fail as expected: %s" % (program, result.stderr.decode()))
    return time.monotonic() - start


def seconds_to_preview(program, tmp):
    preview = os.path.join(tmp, "preview.tif")
    if os.path.exists(preview):
        os.remove(preview)
    start = time.monotonic()
    process = subprocess.Popen(
        [program, "synth", "--exemplar", os.path.join(ROOT, "Data", "dems", "colorado.png"),
         "--sketch", os.path.join(ROOT, "Data", "sketches", "strokes_y_ridges.png"),
         "--size", "1024x1024", "--preview", preview, "-o", os.path.join(tmp, "out.tif")],
        env=clean_environment(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while not os.path.exists(preview):
        if process.poll() is not None:
            raise SystemExit("%s ended before writing its preview" % program)
        time.sleep(POLL_SECONDS)
    seconds = time.monotonic() - start
    process.send_signal(signal.SIGINT)
    process.wait()
    return seconds


def compare(label, measure, launcher, alone, runs, tmp):
    ours, theirs = [], []
    for run in range(runs):
        order = [(launcher, ours), (alone, theirs)]
        for program, into in order if run % 2 == 0 else reversed(order):
            into.append(measure(program, tmp))
    ratios = [a / b for a, b in zip(ours, theirs)]
    print("%-8s launcher %.3f s, alone (re-running itself) %.3f s: ratio %.2f (medians of %d pairs)"
          % (label, statistics.median(ours), statistics.median(theirs), statistics.median(ratios),
             runs))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    parser.add_argument("--runs", type=int, default=7, help="pairs per figure (default 7)")
    options = parser.parse_args()
    if options.runs < 1:
        parser.error("--runs must be at least 1")
    launcher = os.path.join(options.build, "bin", "tsynth")
    alone = os.path.join(options.build, "bin", "tsynth-main")
    for program in (launcher, alone):
        if not os.access(program, os.X_OK):
            parser.error("%s is missing: build the project first" % program)
    with tempfile.TemporaryDirectory(prefix="tsynth-startup-") as tmp:
        compare("start", seconds_to_start, launcher, alone, options.runs, tmp)
        compare("preview", seconds_to_preview, launcher, alone, options.runs, tmp)


if __name__ == "__main__":
    main()
