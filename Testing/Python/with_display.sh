#!/usr/bin/env bash
# Runs a command with an X display: the current one if DISPLAY is set (scripts/test.sh starts one
# Xvfb for the whole test run), else a private one from xvfb-run.
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
fi
# Under load the shared Xvfb now and then refuses a connection ("bad X server connection", about
# one run in several): that one failure, and only it, is retried once after a pause.
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$@" > >(tee "$log") 2> >(tee -a "$log" >&2)
status=$?
wait
if [ "$status" -ne 0 ] && grep -q "bad X server connection" "$log"; then
  echo "with_display.sh: the X server refused the connection; trying once more" >&2
  sleep 2
  "$@"
  status=$?
fi
exit "$status"
