#!/usr/bin/env python3
"""Resident peak of each stage of one `tsynth synth` run.

    bash Testing/Benchmarks/rss_timeline.sh LOG -- tsynth synth ... --report R.json
    python3 Testing/Benchmarks/rss_stages.py R.json LOG

rss_timeline.sh samples resident memory every 0.25 s; the report's times_s gives each stage's
duration. The stages ran one after the other in the order below, so laid end to end from the
process start they tell which samples each stage owns (the start-up before `prepare` is folded
into it, so the first stage reads a little long).
"""
import json
import sys

STAGES = ["prepare", "setup", "features", "fill", "finish", "write", "measure"]


def main(report_path, log_path):
    with open(report_path) as f:
        times = json.load(f)["times_s"]
    with open(log_path) as f:
        samples = [tuple(map(float, line.split())) for line in f if line.strip()]
    if not samples:
        sys.exit(f"{log_path} holds no samples: run rss_timeline.sh first")
    start = 0.0
    for stage in STAGES:
        end = start + times.get(stage, 0.0)
        peak_kb = max([kb for ms, kb in samples if start <= ms / 1000 < end] or [0])
        print(f"{stage:9s} {start:6.1f}-{end:6.1f} s  {peak_kb / 1024:6.0f} MB")
        start = end
    overall = max(samples, key=lambda s: s[1])
    print(f"peak      {overall[1] / 1024:.0f} MB at {overall[0] / 1000:.1f} s")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: rss_stages.py REPORT.json RSS_LOG")
    main(sys.argv[1], sys.argv[2])
