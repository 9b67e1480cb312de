#!/usr/bin/env python3
"""The ssstar test suite (make test): every tests/suite_*.py. Each test states the requirement it checks; the last
line is "N passed, N failed". Usage: tests/run.py [-k SUBSTRING] [-v]"""
import argparse
import glob
import importlib
import os
import subprocess
import sys
import time
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import OUT, TESTS, Failure  # noqa: E402

for path in sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), "suite_*.py"))):
    importlib.import_module(os.path.splitext(os.path.basename(path))[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("-k", default="", help="run only tests whose name contains this")
    parser.add_argument("-v", action="store_true", help="print each requirement")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    passed = failed = 0
    for name, requirement, fn in TESTS:
        if args.k not in name:
            continue
        t0 = time.time()
        try:
            fn()
            passed += 1
            print("ok   %-28s %6.1fs" % (name, time.time() - t0), flush=True)
        except Exception as e:  # a test that breaks is a failure of that test, not the end of the suite
            failed += 1
            detail = str(e) if isinstance(e, (Failure, subprocess.TimeoutExpired)) else traceback.format_exc()
            print("FAIL %-28s %6.1fs\n  requirement: %s\n  %s" % (name, time.time() - t0, requirement, detail.replace("\n", "\n  ")), flush=True)
        if args.v:
            print("     " + requirement)
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
