#!/usr/bin/env python3
"""The mapper from Python: refines frame by frame, reports its state, matches its baseline.

    TestSAVRPython.py -V baseline.png -T outdir
"""

import os
import sys

from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_DOUBLE

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "Examples", "Python"))
import savr_wavelet  # noqa: E402
import vtksavr  # noqa: E402


def pixels(window):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ShouldRerenderOff()
    grab.Update()
    image = grab.GetOutput()
    return image, values(image)


def values(image):
    """The image's RGB bytes as one list of ints."""
    scalars = image.GetPointData().GetScalars()
    components = scalars.GetNumberOfComponents()
    return [int(scalars.GetComponent(i, c)) for i in range(scalars.GetNumberOfTuples())
            for c in range(3) if c < components]


def main(argv):
    baseline = argv[argv.index("-V") + 1] if "-V" in argv else None
    outdir = argv[argv.index("-T") + 1] if "-T" in argv else "."
    failures = []

    def expect(condition, what):
        if not condition:
            failures.append(what)
            print("FAILED:", what)

    window, renderer, mapper = savr_wavelet.build_scene(size=200)
    window.SetOffScreenRendering(1)
    expect(isinstance(mapper, vtksavr.vtkSAVRVolumeMapper), "the wrapped class is importable")
    mapper.SetMaximumNumberOfFrames(8)
    events = []
    mapper.AddObserver(vtksavr.vtkSAVRVolumeMapper.RefinementFrameEvent,
                       lambda caller, event: events.append(caller.GetNumberOfFramesAccumulated()))
    progress = []

    @calldata_type(VTK_DOUBLE)
    def on_progress(caller, event, amount):
        progress.append((event, amount))

    mapper.AddObserver("ProgressEvent", on_progress)
    renders = savr_wavelet.refine(window, mapper)
    expect(renders == 8, "8 renders refine to 8 frames (got %d)" % renders)
    expect(events == list(range(1, 9)), "one event per frame: %s" % events)
    # The pipeline's update of the mapper's input reports 0 and 1 first; then one per frame.
    expect(progress[-8:] == [("ProgressEvent", k / 8.0) for k in range(1, 9)],
           "a named ProgressEvent per frame, frames over the limit as its double: %s" % progress)
    expect(mapper.GetMemoryInUse() > 0, "samples are stored")
    expect(0.0 <= mapper.GetErrorEstimate() < 0.01, "an error estimate after refinement")

    image, got = pixels(window)
    background = [255.0 * c for c in renderer.GetBackground()]
    covered = sum(1 for i in range(0, len(got), 3)
                  if any(abs(got[i + c] - background[c]) > 8 for c in range(3))) / (len(got) / 3)
    print("covered fraction %.3f" % covered)
    expect(covered > 0.1, "the image is not blank")

    # A transfer-function edit re-blends without sampling.
    memory = mapper.GetMemoryInUse()
    renderer.GetVolumes().GetLastProp().GetProperty().GetScalarOpacity().AddPoint(160.0, 0.5)
    window.Render()
    expect(mapper.GetNumberOfFramesAccumulated() == 8 and mapper.GetMemoryInUse() == memory,
           "a transfer-function edit re-blends the stored samples")
    renderer.GetVolumes().GetLastProp().GetProperty().GetScalarOpacity().RemovePoint(160.0)
    window.Render()

    # The AMR and unstructured-grid adaptors are wrapped too.
    from vtkmodules.vtkFiltersAMR import vtkAMRGaussianPulseSource
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    pulse = vtkAMRGaussianPulseSource()
    pulse.SetRootSpacing(0.5)
    pulse.Update()
    amr = vtksavr.vtkSAVRAMRSampler()
    built = amr.Build(pulse.GetOutput(), 4, 1, 0, "Gaussian-Pulse", None, 1)  # cell field data
    expect(built and amr.GetFinestSpacing() == 0.25 and amr.GetCoarsestSpacing() == 0.5,
           "the AMR adaptor builds from Python (finest %g, coarsest %g)" % (
               amr.GetFinestSpacing(), amr.GetCoarsestSpacing()))
    wavelet = vtkRTAnalyticSource()
    wavelet.SetWholeExtent(-4, 4, -4, 4, -4, 4)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputConnection(wavelet.GetOutputPort())
    tets.Update()
    grid = tets.GetOutput()
    mesh = vtksavr.vtkSAVRUnstructuredSampler()
    built = mesh.Build(grid, grid.GetPointData().GetScalars(), False, None)
    expect(built and mesh.GetNumberOfSkippedCells() == 0 and mesh.GetTypicalCellSize() == 1.0,
           "the unstructured adaptor builds from Python (typical cell size %g)" %
           mesh.GetTypicalCellSize())

    image, got = pixels(window)
    name = os.path.basename(baseline) if baseline else "SAVRPython.png"
    if baseline and os.path.exists(baseline):
        reader = vtkPNGReader()
        reader.SetFileName(baseline)
        reader.Update()
        expected = values(reader.GetOutput())
        if len(expected) != len(got):
            expect(False, "the baseline has another size")
        else:
            difference = [abs(a - b) for a, b in zip(expected, got)]
            largest, mean = max(difference), sum(difference) / len(difference)
            print("against baseline: max %d mean %.4f levels" % (largest, mean))
            expect(largest <= 3 and mean <= 0.05, "the image matches the baseline")
    else:
        expect(False, "no baseline %s" % baseline)
    if failures:
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(outdir, name))
        writer.SetInputData(image)
        writer.Write()
        print("wrote", os.path.join(outdir, name))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
