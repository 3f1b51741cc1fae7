"""AMR in ParaView: "SAVR Volume" next to the stock "Volume" representation on one hierarchy.

    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a pvbatch Benchmarks/savr_pvbatch_amr.py [--plugin SAVRPlugin.so]
        [--cells 64] [--moves 5] [--size 512] [--output DIR]

The hierarchy: the tests' AMR rings (Testing/ParaView/savr_paraview_testing.py), three levels,
refinement ratio 2, over the box [-2, 0.5] x [-2, 0.5] x [0, 2.5]; level 0 is `--cells` cells per
edge in 8 blocks, level 1 refines the middle half of each edge and level 2 the middle quarter,
each in 8 blocks as well (with the default, 3 x 64^3 cells). Its cell array "Gaussian-Pulse" is a
pulse with rings about the box's centre, evaluated at every level's cell centres (so finer levels
hold finer detail), drawn with the AMR Gaussian pulse scene's transfer function and camera.

It is shown once as the stock "Volume" (vtkAMRVolumeMapper: the hierarchy resampled to one
image, then drawn by ParaView's volume mapper) and once as "SAVR Volume" (the hierarchy sampled
as it is, on the finest level at each point), with the same transfer functions and camera, in the
same window, one after the other. Printed, as medians of whole Render() calls:
- the first frame after Show (each representation prepares the data it draws: the stock one
  resamples, SAVR builds its sampler);
- a frame after a camera move (the stock one resamples again when its resampling follows the
  camera; SAVR's is its first accumulating frame);
- SAVR's refinement to completion after a camera move (the renders it takes, and their sum);
- the two final images' difference in 8-bit levels (they sample differently: the stock image is
  a resampled copy, SAVR's the hierarchy itself).
One process; the machine's every core is available to both (TBB for SAVR, the stock mapper's own
threads or the GL driver's).
"""
import argparse
import math  # math.fsum: a Programmable Source replaces sum() in the script's namespace
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402
from paraview import simple as pvs  # noqa: E402


def moved(camera, degrees):
    """The camera turned by `degrees` about the vertical axis through its focal point."""
    f = camera["focal"]
    p = camera["position"]
    a = math.radians(degrees)
    x, y = p[0] - f[0], p[1] - f[1]
    position = [f[0] + x * math.cos(a) - y * math.sin(a), f[1] + x * math.sin(a) + y * math.cos(a),
                p[2]]
    return dict(position=position, focal=f, up=camera["up"])


def measure(view, source, camera, representation, moves):
    rep = pvs.Show(source, view)
    rep.Representation = representation
    pvs.ColorBy(rep, ("CELLS", "Gaussian-Pulse"))
    rep.ScalarOpacityUnitDistance = 0.5
    T.set_camera(view, camera)
    first, _, _ = T.render_timed(view)
    result = dict(first=first, moves=[], renders=[], refine=[])
    savr = representation == "SAVR Volume"
    for m in range(moves):
        T.set_camera(view, moved(camera, 0.5 * (m + 1)))
        wall, _, _ = T.render_timed(view)
        result["moves"].append(wall)
        if savr:
            _, _, frames = T.refine(view, rep)
            result["renders"].append(len(frames) + 1)
            result["refine"].append(wall + math.fsum(f["wall"] for f in frames))
            # Four frames reach the finest level's spacing (the base step is level 0's).
            result.setdefault("four", []).append(wall + math.fsum(f["wall"] for f in frames[:3]))
            result["state"] = T.state(rep)
    result["image"] = T.capture(view)
    pvs.Hide(source, view)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=T.DEFAULT_PLUGIN)
    parser.add_argument("--cells", type=int, default=64,
                        help="level 0 cells per edge (a multiple of 8)")
    parser.add_argument("--moves", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--output", default="", help="folder for the two final images")
    args = parser.parse_args()

    T.load_plugin(args.plugin, remote=False)
    view = T.make_view()
    view.ViewSize = [args.size, args.size]
    _, _, camera = T.amr_pulse_scene(view)
    for proxy in list(pvs.GetSources().values()):
        pvs.Delete(proxy)
    source = T.amr_rings_source(args.cells)
    source.UpdatePipeline()
    amr = source.GetClientSideObject().GetOutputDataObject(0)
    cells = 0
    for level in range(amr.GetNumberOfLevels()):
        for i in range(amr.GetNumberOfDataSets(level)):
            cells += amr.GetDataSet(level, i).GetNumberOfCells()
    print("three-level AMR, %d cells per edge at level 0: %d blocks, %d cells; %dx%d view, "
          "%d camera moves of 0.5 degrees" % (args.cells, amr.GetTotalNumberOfBlocks(), cells,
              args.size, args.size, args.moves))

    stock = measure(view, source, camera, "Volume", args.moves)
    savr = measure(view, source, camera, "SAVR Volume", args.moves)
    s = savr["state"]
    med = statistics.median
    print("")
    print("%-62s %9s %9s" % ("measurement (median of whole Render() calls)", "seconds", "ratio"))
    print("%-62s %9.4f %9.2f" % ("stock Volume, first frame after Show", stock["first"], 1.0))
    print("%-62s %9.4f %9.2f" % ("SAVR Volume, first frame after Show (vs stock)", savr["first"],
                                 savr["first"] / stock["first"]))
    print("%-62s %9.4f %9.2f" % ("stock Volume, frame after a camera move", med(stock["moves"]), 1.0))
    print("%-62s %9.4f %9.2f" % ("SAVR Volume, frame after a camera move (vs stock)",
                                 med(savr["moves"]), med(savr["moves"]) / med(stock["moves"])))
    print("%-62s %9.4f %9.2f" % ("SAVR Volume, 4 frames: step of the finest level (vs stock)",
                                 med(savr["four"]), med(savr["four"]) / med(stock["moves"])))
    print("%-62s %9.4f %9.2f" % ("SAVR Volume, refinement to completion (%d renders, vs stock)" %
                                 med(savr["renders"]), med(savr["refine"]),
                                 med(savr["refine"]) / med(stock["moves"])))
    print("SAVR: %d frames, error estimate %.5f, stored samples %.1f MiB" % (
        s["NumberOfFramesAccumulated"], s["ErrorEstimate"], s["MemoryInUse"] / 2**20))
    if args.output:
        T.write_png(stock["image"], os.path.join(args.output, "amr_benchmark_stock.png"))
        T.write_png(savr["image"], os.path.join(args.output, "amr_benchmark_savr.png"))
    worst, mean = T.difference(stock["image"], savr["image"])
    print("final images, stock against SAVR: max %d levels, mean %.2f" % (worst, mean))
    T.close_session()


if __name__ == "__main__":
    main()
