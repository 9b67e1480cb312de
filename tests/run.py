#!/usr/bin/env python3
"""The ssstar test suite: every test of tests/suite_*.py. `make test` runs the default set, `make test-full` adds the
slow tests (registered with full=True). Each test runs in a process of its own, several at a time (-j, default the
number of cores): its files go to tests/output/<test>/, so tests running together never share one, and the meshes
they make to tests/output/cache/ssstar, not to the user's cache. Each test states the requirement it checks; the end
of the output gives the time per suite, and the last line is "N passed, N failed".
Usage: tests/run.py [-k SUBSTRING] [-j N] [--full] [--list] [-v]"""
import argparse
import glob
import importlib
import json
import os
import subprocess
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
TIMINGS = os.path.join(HERE, "output", "timings.json")  # the last run's seconds per test: the longest start first
SHIPPED_TIMINGS = os.path.join(HERE, "timings.json")  # a fresh clone's: a whole run's, measured here on a quiet machine
TEST_CACHE = os.path.join(HERE, "output", "cache")  # $XDG_CACHE_HOME of the tests: their mesh cache
TEST_TIMEOUT = 1800  # seconds: a test that runs longer hangs


def load_suites(only=None):
    for path in sorted(glob.glob(os.path.join(HERE, "suite_*.py"))):
        module = os.path.splitext(os.path.basename(path))[0]
        if only is None or module == only:
            importlib.import_module(module)


def run_one(module, name):
    """Worker: runs one test (SSSTAR_TEST_OUT set by the parent); exit status 0 passed, 1 failed, the failure on stdout"""
    load_suites(module)
    from harness import TESTS, Failure
    fn = next(t[2] for t in TESTS if t[0] == name)
    os.makedirs(os.environ["SSSTAR_TEST_OUT"], exist_ok=True)
    try:
        fn()
    except Exception as e:  # a test that breaks is a failure of that test, not of the suite
        print(str(e) if isinstance(e, (Failure, subprocess.TimeoutExpired)) else traceback.format_exc())
        return 1
    return 0


def environment(out):
    # the meshes the tests make go to a cache of the tests' own (tests/output/cache/ssstar), not the user's; matplotlib
    # keeps its font cache where it was
    user_cache = os.environ.get("XDG_CACHE_HOME") if os.environ.get("XDG_CACHE_HOME", "").startswith("/") else os.path.expanduser("~/.cache")
    env = dict(os.environ, SSSTAR_TEST_OUT=out, XDG_CACHE_HOME=TEST_CACHE)
    env.setdefault("MPLCONFIGDIR", os.path.join(user_cache, "matplotlib"))
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    # mpiexec binds -n 1 and -n 2 jobs to cores from core 0 up: two jobs at once would share core 0
    env.setdefault("OMPI_MCA_hwloc_base_binding_policy", "none")
    return env


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-k", action="append", default=[], help="run only tests whose name (or suite's name) contains this; repeatable")
    parser.add_argument("-j", type=int, default=os.cpu_count() or 1, help="tests run at the same time (default: cores)")
    parser.add_argument("--full", action="store_true", help="also the slow tests (make test-full)")
    parser.add_argument("--list", action="store_true", help="list the tests that would run, with their requirements")
    parser.add_argument("-v", action="store_true", help="print each requirement")
    parser.add_argument("--worker", nargs=2, metavar=("MODULE", "TEST"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        sys.exit(run_one(*args.worker))

    load_suites()
    from harness import OUT, TESTS
    chosen = [t for t in TESTS if (not args.k or any(k in t[0] or k in t[2].__module__ for k in args.k)) and (args.full or not t[3])]
    if args.list:
        for name, requirement, fn, full in chosen:
            print("%-32s %-16s %s%s" % (name, fn.__module__, "[full] " if full else "", requirement))
        print("%d tests" % len(chosen))
        return
    os.makedirs(OUT, exist_ok=True)
    previous = {}
    for name in (SHIPPED_TIMINGS, TIMINGS):
        try:
            previous.update(json.load(open(name)))
        except (OSError, ValueError):
            pass
    order = sorted(chosen, key=lambda t: -previous.get(t[0], 1e9))  # the longest (or unknown) first: no long tail
    print("%d tests, %d at a time%s" % (len(order), args.j, " (with the slow ones of make test-full)" if args.full else ""), flush=True)
    start = time.time()
    running, results, timings = [], {}, dict(previous)
    while order or running:
        while order and len(running) < args.j:
            name, requirement, fn, full = order.pop(0)
            out = os.path.join(OUT, name)
            proc = subprocess.Popen([sys.executable, os.path.abspath(__file__), "--worker", fn.__module__, name], cwd=HERE,
                                    env=environment(out), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            running.append((proc, name, requirement, fn.__module__, time.time()))
        time.sleep(0.2)
        for item in list(running):
            proc, name, requirement, module, t0 = item
            timed_out = time.time() - t0 > TEST_TIMEOUT
            if proc.poll() is None and not timed_out:
                continue
            if timed_out:
                proc.kill()
            detail = proc.communicate()[0]
            running.remove(item)
            seconds = time.time() - t0
            ok = proc.returncode == 0
            results[name] = (ok, module, seconds)
            timings[name] = seconds
            if ok:
                print("ok   %-32s %6.1fs" % (name, seconds), flush=True)
            else:
                detail = ("killed after %d s\n" % TEST_TIMEOUT if timed_out else "") + detail
                print("FAIL %-32s %6.1fs\n  requirement: %s\n  %s" % (name, seconds, requirement, detail.strip().replace("\n", "\n  ")), flush=True)
            if args.v:
                print("     " + requirement)
    json.dump(timings, open(TIMINGS, "w"), indent=0, sort_keys=True)
    suites = {}
    for ok, module, seconds in results.values():
        s = suites.setdefault(module, [0, 0, 0.0])
        s[0 if ok else 1] += 1
        s[2] += seconds
    print("\n%-18s %6s %6s %9s" % ("suite", "passed", "failed", "seconds"))
    for module in sorted(suites, key=lambda m: -suites[m][2]):
        print("%-18s %6d %6d %9.1f" % (module, *suites[module]))
    passed = sum(1 for ok, _, _ in results.values() if ok)
    failed = len(results) - passed
    print("%d tests in %.0f s of wall time (%.0f s of test time, %d at a time)" % (len(results), time.time() - start, sum(t for _, _, t in results.values()), args.j))
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
