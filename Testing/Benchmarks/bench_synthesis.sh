#!/usr/bin/env bash
# End-to-end synthesis speed per stage, with ratios to a baseline build and to
# Tasse's code taken in the same run: see bench_synthesis.py for the cases.
# Usage: bench_synthesis.sh [--large [--both]] [--dense] [--edit] [--vs BUILD] [--peer DIR]
#                           [--runs N] [build dir]
exec /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/bench_synthesis.py" "$@"
