#!/usr/bin/env python3
"""Compares two configurations of one `vt eval` results folder, frame by frame.
usage: compare-configurations.py RESULTS A B [--measure ssim|wssim|rmse] [--between LOW HIGH]
Prints the mean of (A - B) over every frame and its 95% confidence interval from a block bootstrap
over the storyboard's segments (the named motions and the frames between them: frames inside one
motion are not independent), as scripts/chapter4-report.py computes every claim of the chapter-4
report. With --between, also the fraction of the gap from LOW to HIGH that A closes, with its
interval (the gap closed in data/reports/chapter4-beyond.md). Exit status 1 names a configuration
the folder does not hold; 2 is a usage error.
"""
import argparse
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def load(name, file):
    spec = importlib.util.spec_from_file_location(name, os.path.join(HERE, file))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(usage=__doc__.splitlines()[1].removeprefix("usage: "))
    parser.add_argument("results")
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--measure", default="ssim", choices=["ssim", "wssim", "rmse"])
    parser.add_argument("--between", nargs=2, metavar=("LOW", "HIGH"))
    args = parser.parse_args()
    chapter4 = load("chapter4_report", "chapter4-report.py")
    beyond = load("chapter4_beyond_report", "chapter4-beyond-report.py")
    np = chapter4.np
    try:
        results = chapter4.Results(args.results)
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"compare-configurations: {args.results}: not a vt eval results folder ({e})")
    for name in [args.a, args.b] + (args.between or []):
        if not results.has(name):
            sys.exit(f"compare-configurations: {args.results}: no configuration named '{name}' "
                     f"(it holds: {', '.join(results.evaluation.names)})")
    blocks, fallback = chapter4.blocks_of(results.segments, np.arange(results.frames))
    a, b = results.values(args.a, args.measure), results.values(args.b, args.measure)
    mean, interval = chapter4.block_bootstrap(a - b, blocks)
    where = f"{len(blocks)} blocks" + (" of consecutive frames" if fallback else " (segments)")
    text = "no interval (too few blocks)" if interval is None else \
        f"95% interval [{interval[0]:+.3e}, {interval[1]:+.3e}]"
    print(f"{args.a} - {args.b}: mean {args.measure} {mean:+.3e}, {text}, {results.frames} "
          f"frames in {where}")
    if args.between:
        low = results.values(args.between[0], args.measure)
        high = results.values(args.between[1], args.measure)
        share, share_interval = beyond.gap_fraction(a, low, high, blocks)
        text = "no interval" if share_interval is None else \
            f"95% interval [{share_interval[0]:.0%}, {share_interval[1]:.0%}]"
        print(f"{args.a} closes {share:.0%} of the gap from {args.between[0]} to "
              f"{args.between[1]}, {text}")


if __name__ == "__main__":
    main()
