"""Scores another tsynth (the previous landing, say) against python.legibility's bars.

Each drawing of Testing/Python/test_legibility.py is synthesised by OTHER_TSYNTH with both of that
test's exemplars and seeds 0-2, then measured by this build's `tsynth evaluate` (which the other may
not have). Prints each run's legible shares beside the bar and whether the run passes it, so that a
landing's change of behaviour can be shown against the same assertions:

    /usr/bin/python3 Testing/Benchmarks/legibility_vs_landing.py \\
        --tsynth build/bin/tsynth --other OTHER_TSYNTH [--data Data] [--seeds 0 1 2]

Exits 0 whatever the scores: it reports, the test asserts.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "Python"))
import sketch_drawing  # noqa: E402
import test_legibility  # noqa: E402


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=900)
    if result.returncode != 0:
        raise SystemExit("%s failed: %s" % (command[0], result.stderr.strip()))
    return result.stdout


def shares(ours, terrain, dem, sketch):
    """(all, ridge, valley) legible shares of terrain, as this build's tsynth evaluate reads them."""
    evaluated = json.loads(run([ours, "evaluate", terrain, "--exemplar", dem, "--sketch", sketch, "--json",
                                "--patch", test_legibility.PATCH]))["terrain"]["legibility"]
    return {"all": evaluated["legible_share"], "ridge": evaluated["ridge"]["legible_share"],
            "valley": evaluated["valley"]["legible_share"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tsynth", required=True, help="this build's tsynth (measures)")
    parser.add_argument("--other", required=True, help="the tsynth that synthesises")
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "Data"), help="the bundled Data/")
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    args = parser.parse_args()
    fmt = lambda v: "  -  " if v is None else "%.2f" % v
    failed = total = 0
    with tempfile.TemporaryDirectory(prefix="tsynth-legibility-landing-") as tmp:
        print("%-18s %-20s %4s  %-24s %s" % ("drawing", "exemplar", "seed", "all ridge valley", "bar"))
        for name, bar in test_legibility.BARS.items():
            sketch = getattr(sketch_drawing, name)().save(os.path.join(tmp, name + ".png"))
            for exemplar in test_legibility.BOTH:
                dem = os.path.join(args.data, "dems", exemplar)
                for seed in args.seeds:
                    out = os.path.join(tmp, "%s_%s_%d.tif" % (name, exemplar, seed))
                    run([args.other, "synth", "--exemplar", dem, "--sketch", sketch, "-o", out, "--patch",
                         test_legibility.PATCH, "--seed", str(seed), "--no-progress"])
                    got = shares(args.tsynth, out, dem, sketch)
                    passes = all(got[k] is not None and got[k] >= least for k, least in bar.items())
                    failed += not passes
                    total += 1
                    print("%-18s %-20s %4d  %s %s %s    %s %s" % (
                        name, exemplar, seed, fmt(got["all"]), fmt(got["ridge"]), fmt(got["valley"]),
                        " ".join("%s>=%.2f" % kv for kv in bar.items()), "pass" if passes else "FAIL"))
    print("%d of %d runs fail the bars" % (failed, total))


if __name__ == "__main__":
    main()
