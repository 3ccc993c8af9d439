#!/usr/bin/env python3
"""Alternating paired runs of two commands: A/B wall-time ratio per pair, then the median.

    scripts/paired_ratio.py -n 5 --a 'CMD_A ...' --b 'CMD_B ...'

Runs B, A, B, A, ... (one warm-up of each first, not counted), times each whole process,
and prints every pair's times and ratio, then the median ratio and the spread. A machine
that drifts slower or faster moves both runs of a pair alike, so the ratio holds where
absolute times do not (docs/BENCHMARKS.md, "The paired floor ratio"). The commands'
output goes to --log (appended), so that their own timings can be read afterwards.
"""
import argparse
import shlex
import statistics
import subprocess
import sys
import time


def timed(command, log):
    start = time.monotonic()
    status = subprocess.run(command, stdout=log, stderr=log).returncode
    seconds = time.monotonic() - start
    if status != 0:
        sys.exit(f"{shlex.join(command)}: exit status {status}")
    return seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--a", required=True, help="the command whose time is the numerator")
    parser.add_argument("--b", required=True, help="the command whose time is the denominator")
    parser.add_argument("-n", type=int, default=5, help="counted pairs (default 5)")
    parser.add_argument("--log", default="/dev/null", help="append the commands' output here")
    args = parser.parse_args()
    a, b = shlex.split(args.a), shlex.split(args.b)
    ratios = []
    with open(args.log, "a") as log:
        timed(b, log)
        timed(a, log)
        for pair in range(1, args.n + 1):
            tb = timed(b, log)
            ta = timed(a, log)
            ratios.append(ta / tb)
            print(f"pair {pair}: A {ta:.2f} s, B {tb:.2f} s, A/B {ta / tb:.3f}", flush=True)
    print(f"median A/B {statistics.median(ratios):.3f} "
          f"(min {min(ratios):.3f}, max {max(ratios):.3f}, {len(ratios)} pairs)")


if __name__ == "__main__":
    main()
