#!/usr/bin/env python3
"""Draws the figures of one `vt eval` output folder, as SVG and PNG, with matplotlib.

usage: evaluation-plots.py FOLDER      (or: python3 - FOLDER < evaluation-plots.py)

FOLDER holds frames.csv and summary.json as `vt eval` writes them. summary.json's "figures" list
names each figure: {"stem": "basic5", "title": ..., "measure": "ssim" | "wssim" | "rmse",
"runs": [configuration names]}; each becomes STEM.svg and STEM.png: one curve per configuration
over the frames, the storyboard's named motions shaded and labelled by their number (motions of
kind "hold" are left unshaded). Configurations that differ only in "seed" (independent draws of
the Random heuristic) are drawn as one curve, their per-frame mean, with a band from the lowest
to the highest seed.

`vt eval` embeds this file and runs it on the folder it is about to publish; a failure there
fails the evaluation. scripts/chapter4-report.py imports it for its own figures (curves, and
paired differences with a bootstrap confidence band).

Exit status: 0 when every figure was drawn; 3 when matplotlib (or numpy) is missing, with one
line on stderr saying so; 1 on any other error.
"""
import csv
import json
import os
import re
import sys

MEASURE_LABELS = {"ssim": "SSIM", "wssim": "WSSIM", "rmse": "RMSE"}
# The thesis's figures span 1024 x 768 runs of several hundred frames; 10 x 4.5 inches at
# 100 dpi keeps a 400-frame curve readable and the legend beside it.
FIGURE_SIZE = (10.0, 4.5)
PNG_DPI = 100


def import_plotting():
    """matplotlib's pyplot (Agg, no display) and numpy, or exit 3 with one line naming the gap."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        # SVG element ids come from a hash salted with this: fixed, so the same data gives the
        # same file.
        matplotlib.rcParams["svg.hashsalt"] = "vt-evaluation"
        import matplotlib.pyplot as pyplot
        import numpy
    except ImportError as error:
        sys.stderr.write(f"matplotlib or numpy missing for {sys.executable} ({error}); "
                         "install python3-matplotlib (scripts/install-deps.sh)\n")
        sys.exit(3)
    return pyplot, numpy


class EvaluationFolder:
    """summary.json and frames.csv of one `vt eval` output folder.

    measures[name][measure] is the per-frame list of that configuration's measure, for every
    column of frames.csv after "configuration" and "frame" (ssim, wssim, rmse, needed_pages,
    misses, ...)."""

    def __init__(self, folder):
        self.folder = folder
        with open(os.path.join(folder, "summary.json")) as f:
            self.summary = json.load(f)
        self.names = [run["name"] for run in self.summary["runs"]]
        self.frames = self.summary["frames"]
        self.measures = {name: {} for name in self.names}
        with open(os.path.join(folder, "frames.csv")) as f:
            for row in csv.DictReader(f):
                columns = self.measures[self.names[int(row["configuration"])]]
                for key, value in row.items():
                    if key not in ("configuration", "frame"):
                        columns.setdefault(key, []).append(float(value))

    def run(self, name):
        """The summary's entry of configuration `name`."""
        return self.summary["runs"][self.names.index(name)]

    def seed_group(self, name):
        """Names of the configurations equal to `name`'s but for "seed" and the name (itself
        included), in the summary's order."""
        def without_seed(run):
            return {k: v for k, v in run["configuration"].items() if k not in ("seed", "name")}
        own = without_seed(self.run(name))
        return [run["name"] for run in self.summary["runs"] if without_seed(run) == own]

    def series(self, name, measure, numpy):
        """Per-frame values of `measure` for `name` as an array (seeds x frames): one row per
        configuration of its seed group."""
        return numpy.array([self.measures[n][measure] for n in self.seed_group(name)])


def motion_bands(summary):
    """(first, last, label) of every named motion except holds; a name like "9: fast turn"
    is labelled by its number."""
    bands = []
    for motion in summary.get("motions", []):
        if motion["kind"] == "hold":
            continue
        number = re.match(r"\s*([^:]+):", motion["name"])
        bands.append((motion["first"], motion["last"],
                      number.group(1) if number else motion["name"]))
    return bands


def shade_motions(axes, bands):
    """Shades every motion band, alternating two greys, with its label at the top."""
    for i, (first, last, label) in enumerate(bands):
        axes.axvspan(first - 0.5, last + 0.5, color="0.85" if i % 2 == 0 else "0.92", zorder=0,
                     linewidth=0)
        axes.text((first + last) / 2, 1.0, label, transform=axes.get_xaxis_transform(),
                  ha="center", va="bottom", fontsize=8)


def save(figure, stem, pyplot):
    """Writes STEM.svg and STEM.png and closes the figure. The SVG carries no date, so the same
    data gives the same bytes. Each file is written under a temporary name and renamed into place,
    so that a run killed while drawing never leaves a partial plot under its final name."""
    for extension, options in (("svg", {"metadata": {"Date": None}}), ("png", {"dpi": PNG_DPI})):
        temporary = stem + "." + extension + ".tmp"
        figure.savefig(temporary, format=extension, **options)
        os.replace(temporary, stem + "." + extension)
    pyplot.close(figure)


def new_axes(pyplot, title, y_label):
    """A figure with one set of axes, titled, frames along x."""
    figure, axes = pyplot.subplots(figsize=FIGURE_SIZE)
    axes.set_title(title, pad=14)
    axes.set_xlabel("frame")
    axes.set_ylabel(y_label)
    return figure, axes


def finish(figure, axes):
    """Legend beside the axes (long configuration names), tight layout."""
    if axes.get_legend_handles_labels()[0]:
        axes.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    figure.tight_layout()


def draw_curves(stem, title, measure, curves, bands, plotting):
    """One curve per (label, values) in `curves`, values an array seeds x frames: a single row is
    drawn as is, several as their mean with a band from their minimum to their maximum."""
    pyplot, numpy = plotting
    figure, axes = new_axes(pyplot, title, MEASURE_LABELS.get(measure, measure))
    shade_motions(axes, bands)
    for label, values in curves:
        x = numpy.arange(values.shape[1])
        if values.shape[0] == 1:
            axes.plot(x, values[0], linewidth=1.0, label=label)
        else:
            line, = axes.plot(x, values.mean(axis=0), linewidth=1.0,
                              label=f"{label} (mean of {values.shape[0]} seeds)")
            axes.fill_between(x, values.min(axis=0), values.max(axis=0), alpha=0.25,
                              color=line.get_color(), linewidth=0)
    finish(figure, axes)
    save(figure, stem, pyplot)


def draw_difference(stem, title, y_label, difference, frames, interval, bands, plotting):
    """A paired per-frame difference over the frames of a claim, as points, and across those
    frames its mean with a shaded confidence interval (low, high), and zero."""
    pyplot, numpy = plotting
    figure, axes = new_axes(pyplot, title, y_label)
    shade_motions(axes, bands)
    frames = numpy.asarray(frames)
    axes.axhline(0.0, color="black", linewidth=0.8)
    axes.plot(frames, difference, ".", markersize=2.5, label="per frame")
    if len(frames):
        low, high = interval
        span = (frames.min() - 0.5, frames.max() + 0.5)
        axes.fill_between(span, [low, low], [high, high], alpha=0.3, color="tab:red",
                          linewidth=0, label="95% interval of the mean (block bootstrap)")
        axes.plot(span, [float(numpy.mean(difference))] * 2, color="tab:red", linewidth=1.2,
                  label="mean")
    finish(figure, axes)
    save(figure, stem, pyplot)


def figure_curves(evaluation, runs, measure, numpy):
    """(label, seeds x frames array) for the figure's runs, each seed group drawn once."""
    curves, drawn = [], set()
    for name in runs:
        if name not in evaluation.names:
            raise ValueError(f"no configuration named '{name}'")
        group = evaluation.seed_group(name)
        if group[0] in drawn:
            continue
        drawn.add(group[0])
        curves.append((group[0] if len(group) > 1 else name,
                       evaluation.series(name, measure, numpy)))
    return curves


def draw_folder(folder, plotting):
    """Draws every figure summary.json names into the folder; returns the stems drawn."""
    evaluation = EvaluationFolder(folder)
    bands = motion_bands(evaluation.summary)
    stems = []
    for figure in evaluation.summary.get("figures", []):
        measure = figure.get("measure", "ssim")
        runs = figure.get("runs") or evaluation.names
        try:
            curves = figure_curves(evaluation, runs, measure, plotting[1])
        except ValueError as error:
            raise ValueError(f"figure '{figure['stem']}': {error}") from None
        draw_curves(os.path.join(folder, figure["stem"]), figure["title"], measure, curves, bands,
                    plotting)
        stems.append(figure["stem"])
    return stems


def main():
    if len(sys.argv) != 2:
        sys.stderr.write("usage: evaluation-plots.py FOLDER\n")
        return 2
    plotting = import_plotting()
    try:
        draw_folder(sys.argv[1], plotting)
    except (OSError, ValueError, KeyError) as error:
        sys.stderr.write(f"evaluation-plots: {sys.argv[1]}: {error}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
