#!/usr/bin/env python3
"""Runs the benchmarks behind the summary table of Documentation/benchmarks.md and writes it.

Each benchmark program measures SAVR side by side with a VTK peer in one run and prints its
medians and ratios; this script runs each configuration --runs times (3), reads the ratios from
what the programs print, and writes the markdown table (each cell: one value per run, in bold
where every run meets the target). With --write it replaces the table between the markers in the
given file; otherwise it prints it.

    xvfb-run -a python3 Utilities/benchmark-summary.py --write Documentation/benchmarks.md

Run it on a quiet machine (the timings are of whole renders); it takes about 8 minutes on 2
cores with a Release build in build/.
"""

import argparse
import os
import re
import subprocess
import sys

BEGIN = "<!-- summary table: written by Utilities/benchmark-summary.py -->"
END = "<!-- end of the summary table -->"
CH2BETTER = "/usr/share/mricron/templates/ch2better.nii.gz"


def run(program, args):
    """The text a benchmark program prints."""
    result = subprocess.run([program] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, check=False)
    if result.returncode != 0:
        sys.exit("benchmark-summary: %s %s failed:\n%s" % (program, " ".join(args), result.stdout))
    return result.stdout


def table_row(text, label):
    """The (seconds, ratio) columns of savr_benchmark's row that starts with `label`."""
    for line in text.splitlines():
        if line.startswith(label):
            numbers = re.findall(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?", line[len(label):])
            seconds = float(numbers[0]) if numbers else None
            ratio = float(numbers[1]) if len(numbers) > 1 else None
            return seconds, ratio
    sys.exit("benchmark-summary: no row %r in:\n%s" % (label, text))


def head(text):
    """The ratios of one savr_benchmark run."""
    fixed_seconds, _ = table_row(text, "fixed point, step 1x")
    first_seconds, _ = table_row(text, "SAVR first accumulating frame")
    return {
        "interacting": table_row(text, "SAVR interacting frame, step 1x")[1],
        "refine": table_row(text, "SAVR refine to 4 frames (vs fixed point 1/4x)")[1],
        "accumulating": first_seconds / fixed_seconds,
    }


def mesh(text):
    """The ratios against the faster peer of one savr_unstructured_benchmark run."""
    match = re.search(r"against the faster peer \([^)]*\): SAVR interacting frame ([\d.]+), "
                      r"refinement to completion ([\d.]+)", text)
    if not match:
        sys.exit("benchmark-summary: no ratios against the faster peer in:\n%s" % text)
    return {"interacting": float(match.group(1)), "refine": float(match.group(2))}


def rate(text):
    """SAVR's seconds per interacting frame and its ratio to the peer at a DesiredUpdateRate."""
    match = re.search(r"SAVR single pass.*?([\d.]+) s\s+ratio ([\d.]+)", text)
    if not match:
        sys.exit("benchmark-summary: no rate line in:\n%s" % text)
    return {"seconds": float(match.group(1)), "ratio": float(match.group(2))}


def cell(values, target, unit="", digits=2):
    text = ", ".join("%.*f" % (digits, v) for v in values) + unit
    return "**%s**" % text if target is not None and all(v <= target for v in values) else text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", help="the build folder (build)")
    parser.add_argument("--runs", type=int, default=3, help="runs of each configuration (3)")
    parser.add_argument("--write", help="a markdown file whose table to replace")
    options = parser.parse_args()
    bin_dir = os.path.join(options.build, "bin")
    image = os.path.join(bin_dir, "savr_benchmark")
    unstructured = os.path.join(bin_dir, "savr_unstructured_benchmark")

    runs = range(options.runs)
    translucent = [head(run(image, [])) for _ in runs]
    opaque = [head(run(image, ["--opaque", "1"])) for _ in runs]
    shaded = [head(run(image, ["--shade", "1"])) for _ in runs]
    meshes = {kind: [mesh(run(unstructured, ["--mesh", kind])) for _ in runs]
              for kind in ("tetra", "hexahedra", "mixed")}
    rates = []
    if os.path.exists(CH2BETTER):
        rates = [rate(run(image, ["--file", CH2BETTER, "--size", "1024", "--rate", "10"]))
                 for _ in runs]

    def of(results, key):
        return [r[key] for r in results]

    rows = [
        ("images (MRI head), interacting frame", "fixed point, same step", 0.75,
         of(translucent, "interacting")),
        ("images, refinement to a quarter voxel (4 frames)", "fixed point at a quarter voxel",
         1.0, of(translucent, "refine")),
        ("opaque transfer function (`--opaque 1`), interacting frame", "fixed point, same step",
         0.75, of(opaque, "interacting")),
        ("opaque, refinement to a quarter voxel", "fixed point at a quarter voxel", 1.5,
         of(opaque, "refine")),
        ("shaded (`--shade 1`), first accumulating frame", "fixed point shaded, same step", 1.0,
         of(shaded, "accumulating")),
        ("shaded, refinement to a quarter voxel", "fixed point shaded at a quarter voxel", 1.3,
         of(shaded, "refine")),
        ("shaded, interacting frame", "fixed point shaded, same step", None,
         of(shaded, "interacting")),
    ]
    names = {"tetra": "tetrahedra (519,115)", "hexahedra": "warped hexahedra (64,000)",
             "mixed": "hexahedra and wedges (96,000)"}
    for kind in ("tetra", "hexahedra", "mixed"):
        rows.append(("%s, interacting frame" % names[kind],
                     "the faster of VTK's two unstructured mappers", 0.35,
                     of(meshes[kind], "interacting")))
        rows.append(("%s, refinement to completion" % names[kind], "the same", 1.5,
                     of(meshes[kind], "refine")))
    lines = ["| measurement | peer | target | %s |" % ("runs" if options.runs != 3 else
                                                      "three runs"),
             "|---|---|---|---|"]
    for what, peer, target, values in rows:
        lines.append("| %s | %s | %s | %s |" % (
            what, peer, "at most %g" % target if target is not None else "", cell(values, target)))
    if rates:
        lines.append("| ch2better (301x370x316) at 1024x1024, interacting at `DesiredUpdateRate` "
                     "10 (`--rate 10`), seconds a frame | fixed point with its "
                     "`AutoAdjustSampleDistances` (ratio in brackets) | at most 0.125 s | %s (%s) |"
                     % (cell(of(rates, "seconds"), 0.125, " s", 3),
                        ", ".join("%.2f" % v for v in of(rates, "ratio"))))
    table = "\n".join(lines)

    if not options.write:
        print(table)
        return
    with open(options.write) as f:
        text = f.read()
    if BEGIN not in text or END not in text:
        sys.exit("benchmark-summary: %s lacks the markers %s ... %s" % (options.write, BEGIN, END))
    before, rest = text.split(BEGIN, 1)
    _, after = rest.split(END, 1)
    with open(options.write, "w") as f:
        f.write(before + BEGIN + "\n" + table + "\n" + END + after)
    print(table)


if __name__ == "__main__":
    main()
