#!/usr/bin/env python3
"""Runs the benchmarks behind the tables of Documentation/benchmarks.md and writes them.

Each benchmark program measures SAVR side by side with a peer in one run and prints its medians
and ratios; this script runs each configuration --runs times (3), reads what the programs print,
and writes markdown tables (each cell: one value per run, in bold where every run meets the
target). Sections (--sections, all by default):
- summary: the image and mesh benchmarks against VTK's mappers (about 10 minutes on 2 cores);
- particles: savr_particle_benchmark on 200,000 particles against ideal sampling and the
  resample-then-render path (about 12 minutes);
- first-image: savr_particle_benchmark's first image of 200,000 particles at 1024x1024 with
  MaximumRenderTime 0.2 (ParaView's default) (about 2 minutes);
- amr: Benchmarks/savr_pvbatch_amr.py in pvbatch against ParaView's stock Volume representation
  (about 3 minutes; needs the plugin that Utilities/setup-paraview.sh builds).
With --write each section replaces its table between its markers in the given file; otherwise the
tables are printed.

    xvfb-run -a python3 Utilities/benchmark-summary.py --write Documentation/benchmarks.md

Run it on a quiet machine (the timings are of whole renders), with a Release build in build/.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys

CH2BETTER = "/usr/share/mricron/templates/ch2better.nii.gz"


def markers(section):
    """The lines that enclose a section's table in the markdown file."""
    return ("<!-- %s table: written by Utilities/benchmark-summary.py -->" % section,
            "<!-- end of the %s table -->" % section)


def run(program, args, env=None):
    """The text a benchmark program prints."""
    result = subprocess.run([program] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, check=False, env=env)
    if result.returncode != 0:
        sys.exit("benchmark-summary: %s %s failed:\n%s" % (program, " ".join(args), result.stdout))
    return result.stdout


def row_numbers(text, label):
    """The decimal numbers of the printed row that starts with `label`, after the label."""
    for line in text.splitlines():
        if line.startswith(label):
            return [float(n) for n in re.findall(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?",
                                                 line[len(label):])]
    sys.exit("benchmark-summary: no row %r in:\n%s" % (label, text))


def table_row(text, label):
    """The (seconds, ratio) columns of savr_benchmark's row that starts with `label`."""
    numbers = row_numbers(text, label)
    seconds = numbers[0] if numbers else None
    ratio = numbers[1] if len(numbers) > 1 else None
    return seconds, ratio


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


def summary_table(options):
    """The summary table: images and meshes against VTK's mappers."""
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
    return "\n".join(lines)


def particle_run(text):
    """What one savr_particle_benchmark run measured: rows by name, and the resampled images."""
    result = {"rows": {}, "images": []}
    for label, key in (("SAVR first Render", "first render"),
                       ("SAVR interacting frame", "interacting"),
                       ("SAVR first accumulating frame", "accumulating"),
                       ("SAVR refinement to completion", "refine"),
                       ("ideal sampling, one pass at the final step", "ideal")):
        result["rows"][key] = row_numbers(text, label)
    memory = re.search(r"SAVR memory in use: ([\d.]+) MiB", text)
    result["memory"] = float(memory.group(1)) if memory else None
    for match in re.finditer(r"^(\d+)\^3\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+(\S+)\s+([\d.]+)\s+"
                             r"(\(no frame yet\)|\S+)", text, re.M):
        result["images"].append({"size": int(match.group(1)), "resample": float(match.group(2)),
                                 "frame": float(match.group(3)), "rmse": float(match.group(5)),
                                 "savr": match.group(7)})
    return result


def particles_table(options):
    """Particles against ideal sampling and the resample-then-render path."""
    program = os.path.join(options.build, "bin", "savr_particle_benchmark")
    args = ["--points", "200000", "--repeats", "3", "--resample", "32,64,128,256"]
    runs = [particle_run(run(program, args)) for _ in range(options.runs)]
    median = statistics.median
    lines = ["| measurement (medians of 3 camera moves) | time over ideal sampling, three runs "
             "| RMSE |",
             "|---|---|---|"]
    ideal = [r["rows"]["ideal"][0] for r in runs]
    for key, what in (("first render", "SAVR's first Render (builds the particle index)"),
                      ("interacting", "SAVR interacting frame"),
                      ("accumulating", "SAVR first accumulating frame"),
                      ("refine", "SAVR refinement to completion (4 frames)")):
        ratios = [r["rows"][key][0] / i for r, i in zip(runs, ideal)]
        errors = [r["rows"][key][2] for r in runs if len(r["rows"][key]) > 2]
        lines.append("| %s | %s | %s |" % (what, cell(ratios, None),
                                            "%.1e" % median(errors) if errors else ""))
    lines.append("| ideal sampling, one pass at SAVR's final step | 1 (%s s) | %.1e |" % (
        ", ".join("%.1f" % i for i in ideal), median(r["rows"]["ideal"][2] for r in runs)))
    memory = [r["memory"] for r in runs if r["memory"] is not None]
    lines += ["", "SAVR's stored samples after refinement: %.0f MiB (median)." % median(memory), "",
              "| resampled image | resample, s | GPU frame, s | RMSE | SAVR's RMSE by then |",
              "|---|---|---|---|---|"]
    for index, image in enumerate(runs[0]["images"]):
        same = [r["images"][index] for r in runs if len(r["images"]) > index]
        savr = sorted(i["savr"] for i in same)[len(same) // 2].strip("()")
        lines.append("| %d^3 | %.2f | %.2f | %.1e | %s |" % (
            image["size"], median(i["resample"] for i in same), median(i["frame"] for i in same),
            median(i["rmse"] for i in same), savr))
    return "\n".join(lines)


def first_image_table(options):
    """The first image of 200,000 particles at 1024x1024 in a fresh mapper with a render bound."""
    program = os.path.join(options.build, "bin", "savr_particle_benchmark")
    args = ["--points", "200000", "--size", "1024", "--first-image", "0.2"]
    runs = []
    for _ in range(options.runs):
        text = run(program, args)
        match = re.search(r"first Render ([\d.]+) s, ([\d.]+)% of the first frame sampled, window "
                          r"covered ([\d.]+) \(the complete frame covers ([\d.]+)\); the frame "
                          r"took (\d+) renders, ([\d.]+) s", text)
        if not match:
            sys.exit("benchmark-summary: no first image line in:\n%s" % text)
        runs.append([float(g) for g in match.groups()])
    lines = ["| 200,000 particles, 1024x1024, `MaximumRenderTime` 0.2 | target | three runs |",
             "|---|---|---|",
             "| first Render, seconds (the particle index built, the first frame begun, the rest "
             "of the view previewed) | at most 1 | %s |" % cell([r[0] for r in runs], 1.0),
             "| window covered by it, over what the complete first frame covers | | %s |"
             % cell([r[2] / r[3] for r in runs], None),
             "| the first frame's renders, and their seconds | | %s |"
             % ", ".join("%d (%.1f s)" % (r[4], r[5]) for r in runs)]
    return "\n".join(lines)


def amr_run(text):
    """Ratios to the stock representation in one savr_pvbatch_amr.py run."""
    result = {}
    for label, key in (("SAVR Volume, first frame after Show", "first"),
                       ("SAVR Volume, frame after a camera move", "move"),
                       ("SAVR Volume, 4 frames", "four"),
                       ("SAVR Volume, refinement to completion", "refine"),
                       ("stock Volume, frame after a camera move", "stock")):
        seconds, ratio = row_numbers(text, label)[-2:]
        result[key] = seconds if key == "stock" else ratio
    levels = re.search(r"max (\d+) levels, mean ([\d.]+)", text)
    result["mean levels"] = float(levels.group(2)) if levels else None
    return result


def amr_table(options):
    """AMR in ParaView: SAVR Volume against the stock Volume representation."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Benchmarks",
                          "savr_pvbatch_amr.py")
    plugin = os.path.join(options.paraview_build, "lib", "paraview-5.11", "plugins", "SAVRPlugin",
                          "SAVRPlugin.so")
    if not os.path.exists(plugin):
        sys.exit("benchmark-summary: no %s (Utilities/setup-paraview.sh builds it)" % plugin)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.path.join(options.paraview_build, "python3-paraview", "usr", "lib",
                                     "python3", "dist-packages")
    runs = [amr_run(run("pvbatch", [script, "--plugin", plugin], env)) for _ in range(options.runs)]
    lines = ["| measurement (medians of 5 camera moves), over the stock frame after Show (first "
             "row) or after a camera move | three runs |",
             "|---|---|"]
    for key, what in (("first", "first frame after Show (stock resamples, SAVR builds its sampler)"),
                      ("move", "frame after a camera move (SAVR: its first accumulating frame)"),
                      ("four", "SAVR, 4 frames (the step reaches the finest level's spacing)"),
                      ("refine", "SAVR, refinement to completion (a quarter of the finest "
                                 "spacing)")):
        lines.append("| %s | %s |" % (what, cell([r[key] for r in runs], None)))
    lines += ["", "The stock frame after a camera move took %s s; the final images differ by a "
              "mean of %s levels." % (", ".join("%.2f" % r["stock"] for r in runs),
                                      ", ".join("%.2f" % r["mean levels"] for r in runs))]
    return "\n".join(lines)


def write(path, section, table):
    """Replaces the section's table between its markers in the markdown file `path`."""
    begin, end = markers(section)
    with open(path) as f:
        text = f.read()
    if begin not in text or end not in text:
        sys.exit("benchmark-summary: %s lacks the markers %s ... %s" % (path, begin, end))
    before, rest = text.split(begin, 1)
    _, after = rest.split(end, 1)
    with open(path, "w") as f:
        f.write(before + begin + "\n" + table + "\n" + end + after)


def main():
    sections = {"summary": summary_table, "particles": particles_table,
                "first-image": first_image_table, "amr": amr_table}
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default="build", help="the build folder (build)")
    parser.add_argument("--paraview-build", default="build-paraview",
                        help="the plugin's build folder, for the amr section (build-paraview)")
    parser.add_argument("--runs", type=int, default=3, help="runs of each configuration (3)")
    parser.add_argument("--sections", default=",".join(sections),
                        help="which tables (%s)" % ",".join(sections))
    parser.add_argument("--write", help="a markdown file whose tables to replace")
    options = parser.parse_args()
    for section in options.sections.split(","):
        if section not in sections:
            sys.exit("benchmark-summary: no section %r (%s)" % (section, ",".join(sections)))
        table = sections[section](options)
        if options.write:
            write(options.write, section, table)
        print(table + "\n")


if __name__ == "__main__":
    main()
