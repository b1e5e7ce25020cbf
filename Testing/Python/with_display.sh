#!/usr/bin/env bash
# Runs a command with an X display: the current one if DISPLAY is set (scripts/test.sh starts one
# Xvfb for the whole test run), else a private one from xvfb-run.
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
