#!/usr/bin/python3
"""Picks the committed corpus of a fuzz target from a libFuzzer merge.

pick_corpus.py CONTROL_FILE OUT MAX_FILES: reads the control file of a
`-merge=1 -merge_control_file=CONTROL_FILE` run and copies into OUT at most
MAX_FILES inputs, chosen greedily by the coverage edges (COV lines) they add,
the smallest input first among equals. The full merged corpus stays in the
build folder for the next fuzzing run; the committed one is a small regression
suite (every regression-* file is kept besides, by scripts/fuzz.sh).
"""
import os
import shutil
import sys


def read_control(path):
    with open(path) as f:
        lines = f.read().splitlines()
    count = int(lines[0])
    files = lines[2:2 + count]
    edges = {}
    for line in lines[2 + count:]:
        parts = line.split()
        if parts and parts[0] == "COV":
            edges[int(parts[1])] = set(parts[2:])
    return files, edges


def pick(files, edges, max_files):
    covered = set()
    chosen = []
    candidates = {i for i in edges if os.path.exists(files[i])}
    while candidates and len(chosen) < max_files:
        best = max(candidates,
                   key=lambda i: (len(edges[i] - covered), -os.path.getsize(files[i])))
        gain = edges[best] - covered
        if not gain:
            break
        chosen.append(best)
        covered |= gain
        candidates.discard(best)
    return chosen, covered


def main():
    control, out, max_files = sys.argv[1], sys.argv[2], int(sys.argv[3])
    files, edges = read_control(control)
    chosen, covered = pick(files, edges, max_files)
    everything = set().union(*edges.values()) if edges else set()
    os.makedirs(out, exist_ok=True)
    for i in chosen:
        shutil.copy(files[i], os.path.join(out, os.path.basename(files[i])))
    print(f"pick_corpus: {len(chosen)} inputs cover {len(covered)} of {len(everything)} edges")


if __name__ == "__main__":
    main()
