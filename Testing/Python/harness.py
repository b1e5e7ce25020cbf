"""Shared argument handling for the Python tests: paths come from CTest."""
import argparse
import sys
import unittest

PATHS = argparse.Namespace()


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
