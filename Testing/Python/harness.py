"""Shared argument handling for the Python tests: paths come from CTest."""
import argparse
import os
import sys
import time
import unittest

PATHS = argparse.Namespace()

# scripts/sanitize.sh sets TSYNTH_TEST_INSTRUMENTED=1: the tsynth under test is built with
# AddressSanitizer and UndefinedBehaviorSanitizer and runs several times slower, so the few tests
# whose timing only holds for a normal build skip themselves (skip_if_instrumented).
INSTRUMENTED = os.environ.get("TSYNTH_TEST_INSTRUMENTED") == "1"


def skip_if_instrumented(why):
    """Skips a test whose timing an instrumented tsynth cannot meet; why says what it times."""
    return unittest.skipIf(INSTRUMENTED, "instrumented tsynth (TSYNTH_TEST_INSTRUMENTED=1): " + why)


# "Stops promptly" is judged against the same work run to its end in the same test, never against
# a wall-clock constant: load on a shared machine slows both alike (a fixed second failed at a load
# average of 3-4). Stopping takes under this share of the whole run: one abort check's worth of
# work, where an unchecked loop would run on for most of it.
PROMPT_SHARE = 0.1


def seconds_to_run(action):
    """Runs action() and returns the seconds it took (monotonic clock)."""
    start = time.monotonic()
    action()
    return time.monotonic() - start


def assert_stopped_promptly(test, what, latency, whole):
    """latency: seconds from the request to stop to the end; whole: seconds of the same work run
    uninterrupted, measured in the same test."""
    print("%s stopped %.3f s after the request; the whole run took %.3f s" % (what, latency, whole))
    test.assertLess(latency, PROMPT_SHARE * whole,
                    "%s stopped %.2f s after the request, more than %.0f%% of the %.2f s of the whole run"
                    % (what, latency, 100 * PROMPT_SHARE, whole))


def gl_preload_environment():
    """The environment for a 3D render: with TSYNTH_TEST_GL_PRELOAD (a library path, set by
    scripts/sanitize.sh to Mesa's GL driver) that library is preloaded. Mesa unloads its driver
    (dlclose) when VTK closes the display, before LeakSanitizer's check at exit; the driver's
    globals then no longer count as references, and what they held is reported as leaked from an
    unmapped address. Kept loaded, the driver's memory is still reachable and nothing else is
    hidden. ASan's check that its runtime is the first library must then be off."""
    library = os.environ.get("TSYNTH_TEST_GL_PRELOAD")
    if not library:
        return None
    env = dict(os.environ, LD_PRELOAD=library)
    env["ASAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "verify_asan_link_order=0"]))
    return env


def run(test_module_name):
    parser = argparse.ArgumentParser()
    parser.add_argument("--tsynth", required=True)
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--python-dir", required=True)
    parser.add_argument("--shared-data", required=True)
    parser.add_argument("--bundled-data", required=True)
    args, rest = parser.parse_known_args()
    vars(PATHS).update(vars(args))
    program = unittest.main(module=test_module_name, argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    result = program.result
    if result.testsRun == 0:
        print("no test ran")
        sys.exit(1)
    sys.exit(0 if result.wasSuccessful() else 1)
