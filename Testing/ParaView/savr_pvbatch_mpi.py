"""pvbatch test of the SAVR ParaView plugin on several processes (or one).

    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a -s "-screen 0 1024x768x24 -noreset" mpirun --allow-run-as-root --oversubscribe -np 2 \\
      pvbatch --mpi Testing/ParaView/savr_pvbatch_mpi.py --ranks 2 [--plugin SAVRPlugin.so]
        [--baselines DIR] [--output DIR] [--extent N]

The wavelet, split across the ranks (each renders its piece with "SAVR Volume" and IceT
composites the pieces in depth order), refines render after render until the first rank's mapper
reports completion (all ranks sample the same number of frames), and the composited image matches
the single-process baseline ParaViewWavelet.png within a looser tolerance than the single-process
test (see MPI_MAX_LEVEL): each piece's rays start their sample lattice where they enter the
piece, and each piece's last interval ends at the piece's boundary, so the samples near the cut
differ from one volume's. Prints every frame's time for comparison with one process (run the
same script without mpirun and --mpi). With --extent N (not 10) the wavelet is
[-N, N]^3 and only times are reported. Then the same pieces as hexahedra and wedges: each
rank's mapper gets them as they are (not tetrahedra) and the composited image matches the same
baseline. With --scenes particles: the particle cloud of the single-process test, spread over the
ranks, is gathered on the first rank, which draws every point alone; the composited image
matches ParaViewParticles.png (within PARTICLES_MPI_MAX_LEVEL).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import savr_paraview_testing as T  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview import simple as pvs  # noqa: E402

# Composited pieces vs one volume: per channel and on average, in 8-bit levels.
MPI_MAX_LEVEL = 16
MPI_MAX_MEAN = 0.2
# The particles gathered on the first rank and composited vs the single-process image. Measured
# on 2 ranks: max 45 levels, mean 0.07, at the cloud's silhouette and inner opacity edges only
# (the same script on one rank: 0 levels), where the first rank's partly transparent image is
# composited with the others' empty ones.
PARTICLES_MPI_MAX_LEVEL = 64
PARTICLES_MPI_MAX_MEAN = 0.2
# AMR regions composited vs the single-process image (the bounds).
AMR_MAX_LEVEL = 24
AMR_MAX_MEAN = 0.5


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=T.DEFAULT_PLUGIN)
    parser.add_argument("--baselines", default=T.DEFAULT_BASELINES)
    parser.add_argument("--output", default=T.DEFAULT_OUTPUT)
    parser.add_argument("--ranks", type=int, default=0, help="expected number of ranks")
    parser.add_argument("--extent", type=int, default=10)
    parser.add_argument("--scenes", choices=["wavelet", "amr", "particles"], default="wavelet",
                        help="the wavelet and its hexahedra and wedges, the AMR rings, or the "
                        "particle cloud")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    failures = T.Failures()
    ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
    print("ranks: %d" % ranks)
    if args.ranks:
        failures.check(ranks == args.ranks, "running on %d ranks (expected %d)" % (ranks, args.ranks))
    # remote=True loads the plugin on every rank (the data and render servers), not only here.
    T.load_plugin(args.plugin, remote=True)
    view = T.make_view()
    if args.scenes == "amr":
        for mode in ("Composite", "Maximum Intensity"):
            check_amr(view, ranks, mode, args, failures)
        failures.exit()
        return
    if args.scenes == "particles":
        check_particles(view, ranks, args, failures)
        failures.exit()
        return
    source, rep, camera = T.wavelet_scene(view, extent=args.extent)

    # Each rank holds a piece: the process id of every point spans all ranks.
    ids = pvs.ProcessIds(Input=source) if hasattr(pvs, "ProcessIds") else pvs.ProcessIdScalars(Input=source)
    ids.UpdatePipeline()
    array = ids.PointData.keys()[0]
    low, high = ids.PointData[array].GetRange()
    failures.check(low == 0 and high == ranks - 1,
        "the wavelet is split across the ranks (process ids %g to %g)" % (low, high))
    pvs.Delete(ids)
    del ids

    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    T.print_frames("Wavelet on %d ranks" % ranks, frames)
    last = frames[-1]
    failures.check(frames[0]["NumberOfFramesAccumulated"] == 1,
        "the first render after a camera change is one frame")
    failures.check(last["RefinementComplete"] == 1 and
        last["NumberOfFramesAccumulated"] == last["FrameLimit"] == len(frames),
        "refinement converges: complete after %d renders (%d/%d frames on rank 0)" % (
            len(frames), last["NumberOfFramesAccumulated"], last["FrameLimit"]))
    T.is_drawn(final, failures, "the composited wavelet")
    # Each rank samples only its own piece: the first rank stores well under what one process
    # stores for the whole wavelet (written by the single-process test, which runs first).
    whole = os.path.join(args.output, "ParaViewWavelet.memory")
    if args.extent == 10 and ranks > 1:
        failures.check(os.path.exists(whole),
            "the single-process test's stored-sample memory is there (%s)" % whole)
        if os.path.exists(whole):
            with open(whole) as f:
                single = int(f.read())
            failures.check(0 < last["MemoryInUse"] < 0.75 * single,
                "rank 0 stores samples for its piece only: %.2f MiB against %.2f MiB in one "
                "process" % (last["MemoryInUse"] / 2**20, single / 2**20))
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "refinement changed the composited image (first frame vs final: max %d, mean %.3f)" % (
            worst, mean))
    shot = os.path.join(args.output, "ParaViewWaveletRanks%dScreenshot.png" % ranks)
    pvs.SaveScreenshot(shot, view, ImageResolution=T.VIEW_SIZE)
    failures.check(T.difference(T.read_png(shot), final)[0] == 0,
        "SaveScreenshot after completion saves the final composited image")
    mapper = sum(f["LastFrameTime"] for f in frames)
    wall = sum(f["wall"] for f in frames)
    print("Wavelet [-%d, %d]^3 on %d ranks: %d frames, rank 0 mapper %.3f s (%.3f s per frame), "
          "Render() %.3f s wall (%.3f s per frame)" % (
              args.extent, args.extent, ranks, len(frames), mapper, mapper / len(frames), wall,
              wall / len(frames)))
    if args.extent == 10:
        T.compare_baseline(final, "ParaViewWaveletRanks%d" % ranks, args.baselines, args.output,
            failures, max_level=MPI_MAX_LEVEL, max_mean=MPI_MAX_MEAN,
            baseline_name="ParaViewWavelet")
        # The first frame is reported, not checked: one frame's samples sit differently per piece.
        T.write_png(first, os.path.join(args.output, "ParaViewWaveletRanks%dFirstFrame.png" % ranks))
        expected = os.path.join(args.baselines, "ParaViewWaveletFirstFrame.png")
        if os.path.exists(expected):
            print("first frame vs the single-process first frame: max %d, mean %.3f" %
                  T.difference(first, T.read_png(expected)))
    if args.extent == 10:
        check_hex_wedge(view, source, camera, ranks, args, failures)
    failures.exit()


def check_amr(view, ranks, mode, args, failures):
    """The AMR rings (three levels, blocks of every level spread over the ranks by the source)
    shown as "SAVR Volume" with blend mode `mode`. Composite: each rank draws its region of the
    domain with the blocks it gets from the others; maximum intensity: the first rank gathers
    every block and draws alone. Either way the composited image matches the single-process one
    (the baseline; in one process, strictly)."""
    source, rep, camera = T.amr_rings_scene(view)
    rep.BlendMode = mode
    # 8 frames (to an eighth of level 0's spacing, half the finest level's) keep the 4-rank run
    # short on two cores.
    rep.MaximumNumberOfFrames = 8
    source.UpdatePipeline()
    here = source.GetClientSideObject().GetOutputDataObject(0)
    held = T.held_blocks(here)
    total = here.GetTotalNumberOfBlocks()
    failures.check(here.GetNumberOfLevels() == 3 and held == (total + ranks - 1) // ranks,
        "AMR rings: the source gives this rank %d of its %d blocks in 3 levels" % (held, total))
    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    label = "AMR rings, %s, %d rank%s" % (mode, ranks, "s" if ranks > 1 else "")
    T.print_frames(label, frames)
    last = frames[-1]
    failures.check(last["RefinementComplete"] == 1 and
        last["NumberOfFramesAccumulated"] == last["FrameLimit"] == len(frames),
        "%s: refinement completes, one frame per render (%d renders, %d/%d frames)" % (
            label, len(frames), last["NumberOfFramesAccumulated"], last["FrameLimit"]))
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    failures.check(len(volumes) == 1, "%s: one SAVR volume drawn here" % label)
    if volumes:
        data = volumes[0].GetMapper().GetInputDataObject(0, 0)
        mine = T.held_blocks(data)
        print("%s: this rank's mapper holds %d blocks (the source gave it %d)" % (label, mine, held))
        if ranks > 1 and mode == "Composite":
            # Each rank draws its region, with blocks received from the others (in this small
            # hierarchy every region reaches all 24 blocks, or a cell short of them).
            failures.check(volumes[0].GetMapper().GetCropping() == 1 and mine > held,
                "%s: this rank samples its own region, with the %d blocks it needs" % (label, mine))
        elif ranks > 1:
            # A maximum is not composited front to back: the first rank draws every block.
            failures.check(volumes[0].GetMapper().GetCropping() == 0 and
                mine == T.held_blocks_total(data),
                "%s: the first rank holds every block (%d) and draws alone" % (label, mine))
    T.is_drawn(final, failures, label)
    # Each rank stores the samples of its region only: against what one process stores (the
    # single-process run, which runs first, writes it).
    whole = os.path.join(args.output, "ParaViewAMRRings.memory")
    if mode == "Composite" and ranks == 1:
        with open(whole, "w") as f:
            f.write("%d" % last["MemoryInUse"])
    elif mode == "Composite":
        single = int(open(whole).read()) if os.path.exists(whole) else 0
        failures.check(0 < last["MemoryInUse"] < 0.75 * single,
            "%s: the first rank stores the samples of its region only: %.1f MiB against %.1f MiB "
            "in one process" % (label, last["MemoryInUse"] / 2**20, single / 2**20))
    name = "ParaViewAMRRings" + ("" if mode == "Composite" else "Maximum")
    if ranks == 1:
        T.compare_baseline(final, name, args.baselines, args.output, failures)
    else:
        T.compare_baseline(final, "%sRanks%d" % (name, ranks), args.baselines, args.output,
            failures, max_level=AMR_MAX_LEVEL, max_mean=AMR_MAX_MEAN, baseline_name=name)
    pvs.Delete(rep)
    pvs.Delete(source)


def check_particles(view, ranks, args, failures):
    """The particle cloud of the single-process test, spread over the ranks by its source, shown
    as "SAVR Volume": the first rank gathers every point and draws alone (a kernel reaches
    across any split), the other ranks draw nothing, and the composited image matches the
    single-process baseline (see PARTICLES_MPI_MAX_LEVEL)."""
    source, rep, camera = T.particles_scene(view)
    rep.ParticleRadiusArray = "radius"
    rep.ParticleKernel = "SPH Cubic"
    source.UpdatePipeline()
    here = source.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
    failures.check(here == len(range(0, 14 ** 3, ranks)),
        "particles: the source gives the first rank %d of the %d points" % (here, 14 ** 3))
    T.start_view(view, rep, camera)
    _, final, frames = T.refine(view, rep)
    label = "Particles on %d rank%s" % (ranks, "s" if ranks > 1 else "")
    T.print_frames(label, frames)
    failures.check(frames[-1]["RefinementComplete"] == 1 and len(frames) == 4,
        "%s: refinement completes in 4 renders (%d)" % (label, len(frames)))
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    data = volumes[0].GetMapper().GetInputDataObject(0, 0) if volumes else None
    drawn = data.GetNumberOfPoints() if data is not None else 0
    failures.check(len(volumes) == 1 and drawn == 14 ** 3,
        "%s: the first rank draws every point (%d volumes, %d points)" % (label, len(volumes), drawn))
    T.is_drawn(final, failures, label)
    T.compare_baseline(final, "ParaViewParticlesRanks%d" % ranks, args.baselines, args.output,
        failures, max_level=PARTICLES_MPI_MAX_LEVEL, max_mean=PARTICLES_MPI_MAX_MEAN,
        baseline_name="ParaViewParticles")
    pvs.Delete(rep)
    pvs.Delete(source)


def check_hex_wedge(view, source, camera, ranks, args, failures):
    """The wavelet's pieces as hexahedra and wedges, shown as "SAVR Volume": ParaView
    redistributes the cells across the ranks and composites them in order; each rank's mapper
    gets them as they are (no tetrahedra), and the image is close to the single-process one."""
    pvs.Hide(source, view)
    mesh = T.hex_wedge_mesh(source)
    rep = pvs.Show(mesh, view)
    rep.Representation = "SAVR Volume"
    T.prepare(rep)
    # Compared with the image data's baseline: the image mappers' reading of opacity.
    rep.MeshOpacityAsAttenuation = 0
    pvs.ColorBy(rep, ("POINTS", "RTData"))
    rep.ScalarOpacityUnitDistance = 2.0
    T.start_view(view, rep, camera)
    _, final, frames = T.refine(view, rep)
    T.print_frames("Hexahedra and wedges on %d ranks" % ranks, frames)
    volume = rep.GetClientSideObject().GetActiveRepresentation().GetActor()
    types = T.mapper_cell_types(volume)
    failures.check(types and set(types) <= {12, 13},
        "rank 0's mapper gets hexahedra and wedges as they are (VTK types %s)" % types)
    failures.check(frames[-1]["RefinementComplete"] == 1, "hexahedra and wedges refine to completion")
    T.compare_baseline(final, "ParaViewHexWedgeRanks%d" % ranks, args.baselines, args.output,
        failures, max_level=MPI_MAX_LEVEL, max_mean=MPI_MAX_MEAN, baseline_name="ParaViewWavelet")
    pvs.Delete(rep)
    pvs.Delete(mesh)


if __name__ == "__main__":
    main()
