"""How "SAVR Volume" divides work and memory over MPI ranks in ParaView: per-rank figures.

    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a -s "-screen 0 1024x768x24 -noreset" mpirun --allow-run-as-root --oversubscribe -np N \\
      pvbatch --mpi --symmetric Benchmarks/savr_pvbatch_scaling.py --scene wavelet|amr|mesh
        [--plugin SAVRPlugin.so] [--extent 127] [--mesh-extent 24] [--cells 64] [--frames 4]
        [--size 512]

Every rank runs the script (--symmetric) and reads its own mapper. Scenes: the wavelet on
[-extent, extent]^3 (127: 255^3 points, ParaView splits it over the ranks); the tests' AMR rings
with `--cells` level-0 cells per edge (each rank draws a region, see ParaView/README.md); the
wavelet on [-mesh-extent, mesh-extent]^3 as hexahedra and wedges (ParaView redistributes the
cells). After a camera change the view renders `--frames` refinement frames; printed per rank:
samples taken per frame, samples stored at the end and their memory, and the mapper's seconds
per frame; and the median Render() time per frame (whole, composited). On a machine with fewer
cores than ranks the ranks share the cores: the figures show how work and memory divide, not
speed.
"""
import argparse
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402
from paraview import simple as pvs  # noqa: E402
from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

# The mapper's own methods from Python: the module built against ParaView's VTK.
sys.path.insert(0, os.path.join(T.BUILD, "python"))
import vtksavr  # noqa: E402,F401

FIELDS = ["samples per frame", "stored samples", "stored MiB", "mapper s/frame"]


def scene(view, args):
    if args.scene == "wavelet":
        source, rep, camera = T.wavelet_scene(view, extent=args.extent)
        rep.ScalarOpacityUnitDistance = 2.0 * args.extent / 10.0  # the same look at any size
    elif args.scene == "amr":
        source, rep, camera = T.amr_rings_scene(view, cells=args.cells)
    else:
        wavelet, rep, camera = T.wavelet_scene(view, extent=args.mesh_extent)
        pvs.Hide(wavelet, view)
        source = T.hex_wedge_mesh(wavelet)
        rep = pvs.Show(source, view)
        rep.Representation = "SAVR Volume"
        pvs.ColorBy(rep, ("POINTS", "RTData"))
        rep.ScalarOpacityUnitDistance = 2.0 * args.mesh_extent / 10.0
    rep.MaximumNumberOfFrames = args.frames
    return rep, camera


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=T.DEFAULT_PLUGIN)
    parser.add_argument("--scene", choices=["wavelet", "amr", "mesh"], default="wavelet")
    parser.add_argument("--extent", type=int, default=127)
    parser.add_argument("--mesh-extent", type=int, default=24)
    parser.add_argument("--cells", type=int, default=64)
    parser.add_argument("--frames", type=int, default=4)
    parser.add_argument("--size", type=int, default=512)
    args = parser.parse_args()

    controller = vtkMultiProcessController.GetGlobalController()
    ranks = controller.GetNumberOfProcesses() if controller else 1
    me = controller.GetLocalProcessId() if controller else 0
    T.load_plugin(args.plugin, remote=False)
    view = T.make_view()
    view.ViewSize = [args.size, args.size]
    rep, camera = scene(view, args)
    T.start_view(view, rep, camera)
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    mapper = volumes[0].GetMapper() if volumes else None
    taken = mapper.GetNumberOfSamplesTaken() if mapper else 0
    walls, frame_times = [], []
    for _ in range(args.frames):
        wall, _, _ = T.render_timed(view)
        walls.append(wall)
        frame_times.append(mapper.GetLastFrameTime() if mapper else 0.0)
    mine = [0.0] * len(FIELDS)
    if mapper:
        mine = [(mapper.GetNumberOfSamplesTaken() - taken) / args.frames,
                float(mapper.GetNumberOfStoredSamples()),
                mapper.GetMemoryInUse() / 2.0**20,
                statistics.median(frame_times)]
    send = vtkDoubleArray()
    for value in mine:
        send.InsertNextValue(value)
    gathered = vtkDoubleArray()
    if controller and ranks > 1:
        controller.AllGather(send, gathered)
    else:
        gathered.DeepCopy(send)
    if me == 0:
        print("%s on %d rank(s), %dx%d, %d frames; median Render() per frame %.3f s" % (
            args.scene, ranks, args.size, args.size, args.frames, statistics.median(walls)))
        print("rank  " + "  ".join("%16s" % f for f in FIELDS))
        for r in range(ranks):
            row = [gathered.GetValue(r * len(FIELDS) + i) for i in range(len(FIELDS))]
            print("%4d  %16.0f  %16.0f  %16.1f  %16.3f" % (r, *row))
        sys.stdout.flush()
    T.close_session()


if __name__ == "__main__":
    main()
