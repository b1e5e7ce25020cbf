#!/usr/bin/env bash
# Runs a command with an X display: the current one if DISPLAY is set (scripts/test.sh starts one
# Xvfb for the whole test run), else a private one from xvfb-run.
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
fi
# Under load the shared Xvfb now and then refuses a connection ("bad X server connection", about
# one run in several, and now and then twice in a row): that failure, and only it, is retried up
# to three times after growing pauses.
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
for pause in 2 4 8 0; do
  : > "$log"
  "$@" > >(tee "$log") 2> >(tee -a "$log" >&2)
  status=$?
  wait
  if [ "$status" -eq 0 ] || ! grep -q "bad X server connection" "$log" || [ "$pause" -eq 0 ]; then
    break
  fi
  echo "with_display.sh: the X server refused the connection; trying again in ${pause} s" >&2
  sleep "$pause"
done
exit "$status"
