#!/usr/bin/env python3
"""Counts the tests in CTest's JUnit files (ctest --output-junit) and prints the closing line
of tools/run_tests.sh, `tests: N passed, N failed, N skipped`.

    count_tests.py [--fail-on-skip] RESULTS.xml...
    count_tests.py --names passed|failed|skipped RESULTS.xml...

CTest's own summary counts a skipped test as passed ("100% tests passed"), so the count is made
here from each test's status. A test that CTest did not run for another reason (its executable
is missing, a required file is absent) counts as failed. The exit status is 1 when a test
failed, a file holds no results or, with --fail-on-skip, a test was skipped. With --names, the
names of the tests of that kind are printed, one a line, and the exit status is 0.
"""

import argparse
import sys
import xml.etree.ElementTree as ElementTree


def outcome(testcase):
    """passed, failed or skipped, from the status CTest writes on the test case."""
    status = testcase.get("status")
    if status == "run":
        return "passed"
    if status == "disabled":
        return "skipped"
    # CTest marks "notrun" both the tests that skipped themselves and those it could not start
    # (no executable, REQUIRED_FILES absent), which its summary lists as failed; the message
    # tells them apart.
    skipped = testcase.find("skipped")
    if status == "notrun" and skipped is not None and skipped.get("message", "").startswith(
            ("SKIP_RETURN_CODE", "SKIP_REGULAR_EXPRESSION")):
        return "skipped"
    return "failed"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fail-on-skip", action="store_true", help="a skipped test fails the run")
    parser.add_argument("--names", choices=("passed", "failed", "skipped"), help="print these tests' names")
    parser.add_argument("results", nargs="+", help="JUnit files written by ctest --output-junit")
    args = parser.parse_args()

    counts = {"passed": 0, "failed": 0, "skipped": 0}
    unreadable = False
    for path in args.results:
        try:
            testcases = ElementTree.parse(path).getroot().iter("testcase")
        except (OSError, ElementTree.ParseError) as error:
            print(f"no test results in {path}: {error}", file=sys.stderr)
            unreadable = True
            continue
        here = {"passed": [], "failed": [], "skipped": []}
        for testcase in testcases:
            here[outcome(testcase)].append(testcase.get("name"))
        if args.names:
            print("\n".join(here[args.names]), end="\n" if here[args.names] else "")
            continue
        # One line per file, worded unlike the closing line, which is the one CI reads.
        print(f"{path}: {sum(map(len, here.values()))} tests, of which passed {len(here['passed'])}, "
              f"failed {len(here['failed'])}, skipped {len(here['skipped'])}")
        for kind in ("failed", "skipped"):
            for name in here[kind]:
                print(f"  {kind}: {name}")
        for kind in counts:
            counts[kind] += len(here[kind])

    if args.names:
        return 1 if unreadable else 0
    skips_fail = args.fail_on_skip and counts["skipped"] > 0
    if skips_fail:
        print("skipped tests fail this run: tools/install_dependencies.sh ran, so everything they need "
              "should be here (set SKIP_APT=1 to allow skips)")
    print(f"tests: {counts['passed']} passed, {counts['failed']} failed, {counts['skipped']} skipped")
    return 1 if unreadable or counts["failed"] > 0 or skips_fail else 0


if __name__ == "__main__":
    sys.exit(main())
