"""pvbatch test of the SAVR ParaView plugin, one process.

    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a pvbatch Testing/ParaView/savr_pvbatch.py [--plugin SAVRPlugin.so]
        [--baselines DIR] [--output DIR]
        [--scenes python,wavelet,tetrahedra,curvilinear,hexwedge,head,amr,particles,interactor,saved,slice,translucent,progress,panel]
        [--no-threads]

For the wavelet and the MRI head shown as "SAVR Volume": every Render() adds one refinement
frame until the representation reports RefinementComplete (read through its information
properties); the final image and the image after the first frame match their baselines
(Testing/Data/Baseline/ParaView*.png, at most 3 levels per channel, 0.05 on average), are not
blank, and differ from each other; SaveScreenshot then saves the final image. Also: the
settings have their documented defaults and reach the mapper; ParaView's volume property
(transfer functions, unit distance, shading, blend mode, isosurfaces) reaches the mapper; the
image is close to ParaView's stock "Volume" representation; the wavelet cut into tetrahedra,
shown as "SAVR Volume" of an unstructured grid, and the wavelet as a curvilinear (structured) grid,
are close to the image's baseline; on the head,
NumberOfThreads 1 and 0 give identical images, one thread vs several threads doing the work.
The AMR Gaussian pulse (vtkOverlappingAMR, 2 levels) shown as "SAVR Volume" reaches the mapper
as the hierarchy itself (read from the VTK objects), refines in 8 renders and matches
ParaViewAMRPulse.png. `import vtksavr` from build-paraview/python (the module wrapped against
ParaView's VTK) renders the wavelet to completion with no module of Debian's VTK loaded. A point
cloud (a Programmable Source's vtkPolyData with a value and a radius per point) offers "SAVR
Volume"; shown so, the points reach the mapper with the radius array and kernel chosen, refine
in 4 renders, match ParaViewParticles.png and equal plain VTK's vtkSAVRVolumeMapper (vtksavr)
on the same points and settings (at most 3 levels, 0.05 on average; measured 0); the same points
as an unstructured grid without cells, shown as "SAVR Volume" with the same settings, draw the same
image. A
screenshot and an animation frame saved at twice the view's size are the refined image at that
size (RefineSavedImages); with it off, one frame. With a translucent sphere through the wavelet,
and one in front of it, and ParaView's default depth peeling (for volumes too), each render
refines one frame and the image is within a mean of 3 levels of the stock "Volume"
representation's. BlendMode "Slice"
draws the representation's slice plane in one render, close to the stock representation's, and
again where the plane is moved to. The representation
reports each frame as its own progress (ParaView's progress handler observes representations).
For image data, unstructured and structured grids and AMR, the Properties panel's groups: the SAVR
settings and state (read-only) for "SAVR Volume", the stock volume properties that apply to it
for "SAVR Volume" and "Volume".
Exits non-zero when a check fails. A missing baseline fails, and the image is written to the
output folder (default build-paraview/Testing/Temporary) for review.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import savr_paraview_testing as T  # noqa: E402
import savr_pvbatch_particles  # noqa: E402
from paraview import simple as pvs  # noqa: E402

DEFAULTS = {"SampleDistance": 0.0, "MaximumNumberOfFrames": 0, "MemoryBudget": 1024.0,
            "ErrorTolerance": 0.0, "PreIntegration": 0, "NumberOfThreads": 0}


def refine_and_check(view, rep, camera, name, args, failures):
    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    T.print_frames(name, frames)
    last = frames[-1]
    failures.check(frames[0]["NumberOfFramesAccumulated"] == 1,
        "%s: the first render after a camera change is one frame" % name)
    failures.check(last["RefinementComplete"] == 1 and last["FrameLimit"] == 4 and
        last["NumberOfFramesAccumulated"] == 4 and len(frames) == 4,
        "%s: refinement completes after 4 renders at the default settings (%d renders, %d/%d "
        "frames)" % (name, len(frames), last["NumberOfFramesAccumulated"], last["FrameLimit"]))
    T.is_drawn(final, failures, name)
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "%s: refinement changed the image (first frame vs final: max %d levels, mean %.3f)" % (
            name, worst, mean))
    T.compare_baseline(final, "ParaView" + name, args.baselines, args.output, failures)
    T.compare_baseline(first, "ParaView" + name + "FirstFrame", args.baselines, args.output, failures)
    # Once complete, another render draws the same image again (nothing is sampled).
    pvs.Render(view)
    after = T.state(rep)
    failures.check(T.difference(T.capture(view), final)[0] == 0 and
        after["NumberOfFramesAccumulated"] == 4,
        "%s: a render after completion redraws the final image (%.3f s)" % (name, after["LastFrameTime"]))
    shot = os.path.join(args.output, "ParaView%sScreenshot.png" % name)
    pvs.SaveScreenshot(shot, view, ImageResolution=T.VIEW_SIZE)
    failures.check(T.difference(T.read_png(shot), final)[0] == 0,
        "%s: SaveScreenshot after completion saves the final image" % name)
    return first, final, frames


def compare_with_stock(view, rep, image, label, args, failures, max_mean):
    """Shows `rep` as the stock "Volume" representation, renders once and checks that `image`
    (SAVR's, of the same view) is within a mean of `max_mean` levels of it; the stock image is
    written as ParaView<label>StockVolume.png."""
    rep.Representation = "Volume"
    pvs.Render(view)
    stock = T.capture(view)
    stock_mapper = rep.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
    T.write_png(stock, os.path.join(args.output, "ParaView%sStockVolume.png" % label))
    worst, mean = T.difference(stock, image)
    failures.check(mean <= max_mean,
        "%s: SAVR Volume vs the stock Volume representation (%s): mean %.2f levels (at most %g), "
        "max %d" % (label, stock_mapper.GetClassName(), mean, max_mean, worst))


def check_wavelet(view, args, failures):
    source, rep, camera = T.wavelet_scene(view)
    failures.check("SAVR Volume" in rep.GetProperty("Representation").Available,
        "'SAVR Volume' is offered for image data")
    for name, value in DEFAULTS.items():
        failures.check(rep.GetPropertyValue(name) == value,
            "default %s = %r (is %r)" % (name, value, rep.GetPropertyValue(name)))
    first, final, frames = refine_and_check(view, rep, camera, "Wavelet", args, failures)
    # For the distributed test, which runs next: each rank must store less than this.
    with open(os.path.join(args.output, "ParaViewWavelet.memory"), "w") as f:
        f.write("%d\n" % frames[-1]["MemoryInUse"])

    # ParaView's volume settings reach the mapper: read them from the VTK objects (this process
    # is also the data server).
    volume = rep.GetClientSideObject().GetActiveRepresentation().GetActor()
    mapper_class = volume.GetMapper().GetClassName() if volume.GetMapper() else None
    failures.check(mapper_class == "vtkSAVRVolumeMapper",
        "the representation's volume is drawn by %s" % mapper_class)
    prop = volume.GetProperty()
    failures.check(prop.GetRGBTransferFunction(0).GetSize() == 3 and
        prop.GetScalarOpacity(0).GetSize() == 2 and prop.GetScalarOpacityUnitDistance() == 2.0,
        "the volume property holds the lookup table (3 points), the opacity function (2 points) "
        "and the unit distance")
    rep.Shade = 1
    rep.ScalarOpacityUnitDistance = 3.0
    rep.BlendMode = "Isosurface"
    rep.IsosurfaceValues = [150.0, 200.0]
    pvs.Render(view)
    failures.check(prop.GetShade() == 1 and prop.GetScalarOpacityUnitDistance() == 3.0 and
        prop.GetIsoSurfaceValues().GetNumberOfContours() == 2 and
        volume.GetMapper().GetBlendMode() == 5,
        "Shade, ScalarOpacityUnitDistance, IsosurfaceValues and BlendMode reach the volume "
        "property and the mapper")
    rep.Shade = 0
    rep.ScalarOpacityUnitDistance = 2.0
    rep.BlendMode = "Composite"
    T.check_placement(view, rep, volume, "Wavelet", failures)

    # The mapper's own settings reach it (seen in the frame limit it reports).
    rep.MaximumNumberOfFrames = 8
    pvs.Render(view)
    failures.check(T.state(rep)["FrameLimit"] == 8, "MaximumNumberOfFrames 8 gives a frame limit of 8")
    # The step in effect is state the panel shows (read only).
    asked = rep.SampleDistance
    rep.SampleDistance = 0.5
    pvs.Render(view)
    effective = T.state(rep)["EffectiveSampleDistance"]
    failures.check(effective == 0.5,
        "SampleDistance 0.5 is the EffectiveSampleDistance the panel shows (%g)" % effective)
    rep.SampleDistance = asked
    # The budget holds the images first (about 100 bytes per pixel), then about 1 MiB of
    # samples.
    budget = T.VIEW_SIZE[0] * T.VIEW_SIZE[1] * 104 + (1 << 20)
    rep.MemoryBudget = budget / 2**20  # in MiB
    pvs.Render(view)
    s = T.state(rep)
    failures.check(s["FrameLimit"] < 8 and s["MemoryInUse"] <= budget,
        "a MemoryBudget with about 1 MiB for samples caps the frames (frame limit %d, %.2f MiB "
        "stored)" % (s["FrameLimit"], s["MemoryInUse"] / 2**20))
    rep.MaximumNumberOfFrames = 0
    # In MiB, above what 32 bits of bytes hold, to the byte.
    rep.MemoryBudget = 5120 + 2**-20
    mapper = volume.GetMapper()
    failures.check(not hasattr(mapper, "GetMemoryBudget")
        or mapper.GetMemoryBudget() == (5 << 30) + 1,
        "MemoryBudget 5120 MiB + 1 byte reaches the mapper to the byte (%s)" % (
            mapper.GetMemoryBudget() if hasattr(mapper, "GetMemoryBudget") else "property only"))
    rep.MemoryBudget = 1024
    rep.ErrorTolerance = 0.5
    pvs.Render(view)
    pvs.Render(view)
    pvs.Render(view)
    s = T.state(rep)
    failures.check(s["RefinementComplete"] == 1 and s["NumberOfFramesAccumulated"] < 4,
        "ErrorTolerance 0.5 stops refinement early (%d frames)" % s["NumberOfFramesAccumulated"])
    rep.ErrorTolerance = 0.0

    # Close to ParaView's stock volume representation (another mapper, another sampling: a loose
    # bound on the mean, which a lost transfer function or unit distance would break).
    compare_with_stock(view, rep, final, "Wavelet", args, failures, 3.0)
    pvs.Hide(source, view)


def check_cells(view, args, failures, name, make_cells, kind, cell_types):
    """The wavelet as cells (`make_cells` of the image source), shown as "SAVR Volume" of `kind`:
    the same field, linear in each tetrahedron (ParaView's volume preprocessing cuts every cell
    into tetrahedra) instead of trilinear in each voxel, so the image is close to the image data's
    baseline."""
    source, image_rep, camera = T.wavelet_scene(view)
    pvs.Hide(source, view)
    cells = make_cells(source)
    rep = pvs.Show(cells, view)
    failures.check("SAVR Volume" in rep.GetProperty("Representation").Available,
        "'SAVR Volume' is offered for %s (%s)" % (kind, rep.GetXMLName()))
    rep.Representation = "SAVR Volume"
    T.prepare(rep)
    # Compared with the image data's baseline: the image mappers' reading of opacity.
    failures.check(rep.MeshOpacityAsAttenuation == 1,
        "%s: opacity is read as VTK's unstructured mappers read it by default" % name)
    rep.MeshOpacityAsAttenuation = 0
    pvs.ColorBy(rep, ("POINTS", "RTData"))
    rep.ScalarOpacityUnitDistance = 2.0
    rep.SelectMapper = "Z sweep"  # ignored: SAVR stays the mapper
    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    T.print_frames(name, frames)
    volume = rep.GetClientSideObject().GetActiveRepresentation().GetActor()
    failures.check(volume.GetMapper().GetClassName() == "vtkSAVRVolumeMapper",
        "the %s representation's volume is drawn by %s" % (kind, volume.GetMapper().GetClassName()))
    failures.check(T.mapper_cell_types(volume) == cell_types,
        "%s: the mapper receives the cells as they are (VTK types %s, expected %s)" % (
            name, T.mapper_cell_types(volume), cell_types))
    last = frames[-1]
    failures.check(frames[0]["NumberOfFramesAccumulated"] == 1 and last["RefinementComplete"] == 1
        and last["NumberOfFramesAccumulated"] == last["FrameLimit"] == len(frames) == 4,
        "%s: one frame per render, complete after 4 renders" % name)
    T.is_drawn(final, failures, name)
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "%s: refinement changed the image (max %d, mean %.3f)" % (name, worst, mean))
    T.compare_baseline(final, "ParaView" + name, args.baselines, args.output, failures,
        max_level=8, max_mean=0.2, baseline_name="ParaViewWavelet")
    # Shading, the plugin's own property for grids (the stock grid volume has none), with the
    # surface's Lighting coefficients: it reaches the volume and lights the image.
    rep.Shade = 1
    rep.Specular = 0.4
    _, lit, _ = T.refine(view, rep)
    prop = volume.GetProperty()
    failures.check(prop.GetShade() == 1 and abs(prop.GetSpecular() - 0.4) < 1e-12,
        "%s: Shade and the Lighting group's Specular reach the volume (Shade %d, Specular %g)" % (
            name, prop.GetShade(), prop.GetSpecular()))
    worst, mean = T.difference(final, lit)
    failures.check(mean > 1.0, "%s: shading lights the image (max %d, mean %.2f levels)" % (
        name, worst, mean))
    rep.Shade = 0
    rep.Specular = 0.0
    pvs.Delete(rep)
    pvs.Delete(cells)
    pvs.Delete(image_rep)
    pvs.Delete(source)


def check_tetrahedra(view, args, failures):
    check_cells(view, args, failures, "Tetrahedra",
        lambda source: pvs.Tetrahedralize(Input=source), "unstructured grids", [10])


def check_curvilinear(view, args, failures):
    check_cells(view, args, failures, "Curvilinear",
        lambda source: pvs.ImageDatatoPointSet(Input=source), "structured grids", [12])


def check_hex_wedge(view, args, failures):
    check_cells(view, args, failures, "HexWedge", T.hex_wedge_mesh, "unstructured grids", [12, 13])


# What the Properties panel shows for each data type (the GUI test, savr_gui_panel.xml, looks at
# the image data's panel itself): the stock volume properties that apply to "SAVR Volume".
PANEL_VOLUME_PROPERTIES = {
    "UniformGridRepresentation": ["ScalarOpacityUnitDistance", "Shade", "BlendMode",
                                  "IsosurfaceValues", "SliceFunction", "UseCropping",
                                  "CroppingOrigin", "CroppingScale"],
    "UnstructuredGridRepresentation": ["ScalarOpacityUnitDistance"],
    "StructuredGridRepresentation": ["ScalarOpacityUnitDistance"],
    "AMRRepresentation": ["ScalarOpacityUnitDistance", "Shade"],
}
# Volume properties the plugin adds for "SAVR Volume" only (the stock type has none).
PANEL_SAVR_ONLY_PROPERTIES = {
    "UnstructuredGridRepresentation": ["Shade"],
    "StructuredGridRepresentation": ["Shade"],
}
PANEL_SAVR_SETTINGS = ["SampleDistance", "MaximumNumberOfFrames", "MemoryBudget", "ErrorTolerance",
                       "PreIntegration", "RefineSavedImages", "NumberOfThreads"]


def panel_group(proxy, name):
    """The property group the panel shows the property `name` of `proxy` with: the last one
    that lists it (the panel's rule); its label and its decorators' Representation values."""
    prop = proxy.GetProperty(name)
    found = None
    for i in range(proxy.GetNumberOfPropertyGroups()):
        group = proxy.GetPropertyGroup(i)
        if any(group.GetProperty(j) is prop for j in range(group.GetNumberOfProperties())):
            found = group
    if found is None:
        return None, set()
    values = set()
    pending = [found.GetHints()] if found.GetHints() else []
    while pending:
        element = pending.pop()
        if element.GetAttribute("property") == "Representation" and element.GetAttribute("value"):
            values.add(element.GetAttribute("value"))
        pending.extend(element.GetNestedElement(k) for k in range(element.GetNumberOfNestedElements()))
    return found.GetXMLLabel(), values


def check_panel_groups(view, failures):
    """Which group each property is shown with, for the four data types, and the state shown
    read-only: the SAVR settings and state for "SAVR Volume" only; the stock volume properties
    that apply for "SAVR Volume" and, as before, for "Volume"."""
    wavelet = pvs.Wavelet()
    wavelet.WholeExtent = [-4, 4] * 3
    sources = [wavelet, pvs.Tetrahedralize(Input=wavelet), pvs.ImageDatatoPointSet(Input=wavelet),
               pvs.AMRGaussianPulseSource(Dimension="3D")]
    for source in sources:
        rep = pvs.Show(source, view)
        proxy = rep.SMProxy
        kind = proxy.GetXMLName()
        wrong = []
        for name in PANEL_VOLUME_PROPERTIES[kind]:
            label, values = panel_group(proxy, name)
            if label not in ("Volume Rendering", "Cropping Parameters") or \
                    not {"Volume", "SAVR Volume"} <= values:
                wrong.append("%s (group %r, for %s)" % (name, label, sorted(values)))
        failures.check(not wrong, "%s: %s shown for Volume and SAVR Volume%s" % (
            kind, ", ".join(PANEL_VOLUME_PROPERTIES[kind]),
            "; not: " + ", ".join(wrong) if wrong else ""))
        wrong = []
        for name in PANEL_SAVR_SETTINGS + T.STATE_PROPERTIES + \
                PANEL_SAVR_ONLY_PROPERTIES.get(kind, []):
            label, values = panel_group(proxy, name)
            if values != {"SAVR Volume"}:
                wrong.append("%s (group %r, for %s)" % (name, label, sorted(values)))
        failures.check(not wrong, "%s: the SAVR settings, state%s shown for SAVR Volume only%s" % (
            kind, "".join(" and " + n for n in PANEL_SAVR_ONLY_PROPERTIES.get(kind, [])),
            "; not: " + ", ".join(wrong) if wrong else ""))
        failures.check(rep.GetProperty("MemoryBudget").GetClassName() == "vtkSMDoubleVectorProperty",
            "%s: MemoryBudget is a double property (5.11's panel has no widget for vtkIdType)" % kind)
        shown = [name for name in T.STATE_PROPERTIES
                 if rep.GetProperty(name).GetPanelVisibility() in ("default", "advanced")]
        failures.check(shown == T.STATE_PROPERTIES,
            "%s: the state properties are in the panel (%s)" % (kind, ", ".join(shown)))
        pvs.Delete(rep)
    for source in reversed(sources):
        pvs.Delete(source)


def check_head(view, args, failures):
    reader, rep, camera = T.head_scene(view, args.output)
    first, final, frames = refine_and_check(view, rep, camera, "Head", args, failures)
    # Shaded under ParaView's default lighting (a light kit, two-sided lighting): within what
    # VTK's own two mappers differ by there (measured on the head in TestSAVRConformanceLights:
    # the fixed-point mapper 4.6 levels from the GPU mapper, which lights both sides of a surface
    # where the fixed-point mapper, and SAVR, turn the normal to the viewer). Measured: 4.2.
    compare_with_stock(view, rep, final, "HeadShaded", args, failures, 5.0)
    rep.Representation = "SAVR Volume"
    if not args.no_threads:
        check_head_threads(view, rep, final, failures)
    # The head leaves the view to the scenes after it (ParaView 5.13 reads it where their
    # cameras see it).
    pvs.Delete(rep)
    pvs.Delete(reader)


def check_head_threads(view, rep, final, failures):
    """Threads: TBB inside the mapper, whatever vtkSMPTools is set to in ParaView's VTK. Changing
    the thread count starts over; images must not depend on it."""
    results = {}
    for threads in (1, 0):
        rep.NumberOfThreads = threads
        before = T.thread_cpu()
        _, image, frames = T.refine(view, rep)
        # Over the whole refinement: one render's count depends on the machine's load.
        busy = T.busy_threads(before, T.thread_cpu())
        T.print_frames("Head, NumberOfThreads %d," % threads, frames)
        mapper = sum(f["LastFrameTime"] for f in frames)
        wall = sum(f["wall"] for f in frames)
        cpu = sum(f["cpu"] for f in frames)
        results[threads] = (mapper, wall, cpu, image, busy)
        print("Head, NumberOfThreads %d: %d frames, mapper %.3f s, Render() %.3f s wall, %.3f s "
              "CPU (CPU/wall %.2f), %d busy threads over the refinement" % (
                  threads, len(frames), mapper, wall, cpu, cpu / wall, busy))
    one, all_ = results[1], results[0]
    failures.check(T.difference(one[3], all_[3])[0] == 0 and T.difference(all_[3], final)[0] == 0,
        "images do not depend on the thread count")
    cores = len(os.sched_getaffinity(0))
    print("threads: %d cores; all cores vs one thread: %.2fx faster (mapper time), CPU/wall %.2f "
          "vs %.2f (both depend on the machine's load)" % (
              cores, one[0] / all_[0], all_[2] / all_[1], one[2] / one[1]))
    failures.check(one[4] == 1, "NumberOfThreads 1: one thread does the work")
    if cores > 1:
        failures.check(all_[4] >= 2,
            "NumberOfThreads 0: %d threads share the refinement's work (vtkSMPTools is "
            "Sequential in ParaView's VTK; the mapper's TBB is not)" % all_[4])
    rep.NumberOfThreads = 0


def check_amr(view, args, failures):
    """vtkOverlappingAMR (AMRGaussianPulseSource, 2 levels) shown as "SAVR Volume": the
    hierarchy itself reaches vtkSAVRVolumeMapper (no resampling), refines to its frame limit
    (8 at the default settings: the coarsest spacing as the step, down to a quarter of the finest
    level's) and matches its baseline. A view of its own, so that no earlier scene shows."""
    view = T.make_view()
    source, rep, camera = T.amr_pulse_scene(view)
    failures.check("SAVR Volume" in rep.GetProperty("Representation").Available,
        "'SAVR Volume' is offered for overlapping AMR (%s)" % rep.GetXMLName())
    for name, value in DEFAULTS.items():
        failures.check(rep.GetPropertyValue(name) == value,
            "AMR: default %s = %r (is %r)" % (name, value, rep.GetPropertyValue(name)))
    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    T.print_frames("AMRPulse", frames)
    last = frames[-1]
    failures.check(frames[0]["NumberOfFramesAccumulated"] == 1 and last["RefinementComplete"] == 1
        and last["NumberOfFramesAccumulated"] == last["FrameLimit"] == len(frames) == 8,
        "AMRPulse: one frame per render, complete after 8 renders (%d renders, %d/%d frames)" % (
            len(frames), last["NumberOfFramesAccumulated"], last["FrameLimit"]))
    # The VTK objects: the volume is drawn by vtkSAVRVolumeMapper, whose input is the hierarchy.
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    failures.check(len(volumes) == 1,
        "AMR: one visible volume in the view is drawn by vtkSAVRVolumeMapper (%d)" % len(volumes))
    if volumes:
        volume = volumes[0]
        mapper = volume.GetMapper()
        data = mapper.GetInputDataObject(0, 0)
        data_class = data.GetClassName() if data is not None else None
        is_amr = data_class == "vtkOverlappingAMR"
        failures.check(is_amr and data.GetNumberOfLevels() == 2,
            "AMR: the mapper's input is the hierarchy itself (%s, %d levels, %d blocks)" % (
                data_class, data.GetNumberOfLevels() if is_amr else 0,
                data.GetTotalNumberOfBlocks() if is_amr else 0))
        failures.check(mapper.GetArrayName() == "Gaussian-Pulse" and mapper.GetScalarMode() == 4,
            "AMR: the mapper draws the cell array %r (scalar mode %d)" % (
                mapper.GetArrayName(), mapper.GetScalarMode()))
        prop = volume.GetProperty()
        failures.check(prop.GetRGBTransferFunction(0).GetSize() == 3 and
            prop.GetScalarOpacity(0).GetSize() == 2 and prop.GetScalarOpacityUnitDistance() == 0.5,
            "AMR: the volume property holds the lookup table (3 points), the opacity function "
            "(2 points) and the unit distance")
    T.is_drawn(final, failures, "AMRPulse")
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "AMRPulse: refinement changed the image (first frame vs final: max %d levels, mean %.3f)" % (
            worst, mean))
    T.compare_baseline(final, "ParaViewAMRPulse", args.baselines, args.output, failures)
    pvs.Render(view)
    failures.check(T.difference(T.capture(view), final)[0] == 0 and
        T.state(rep)["NumberOfFramesAccumulated"] == 8,
        "AMRPulse: a render after completion redraws the final image")
    # A mapper setting reaches it.
    rep.MaximumNumberOfFrames = 4
    pvs.Render(view)
    failures.check(T.state(rep)["FrameLimit"] == 4, "AMR: MaximumNumberOfFrames 4 gives a frame limit of 4")
    rep.MaximumNumberOfFrames = 0
    if volumes:
        T.check_placement(view, rep, volumes[0], "AMR", failures)
    check_amr_vectors(view, rep, camera, failures)
    pvs.Delete(rep)
    pvs.Delete(source)
    pvs.Delete(view)


def check_amr_vectors(view, rep, camera, failures):
    """A vector array, the pulse's cell array "Centroid", drawn as the colour map's vector mode
    says, as stock draws it: by its magnitude, or by the component chosen (an error naming the
    components before, nothing drawn). Its magnitude over the pulse's box spans about 0.6 to 3.5;
    one component about -2 to 2.5."""
    images = {}
    for mode in ("Magnitude", "X"):
        pvs.ColorBy(rep, ("CELLS", "Centroid", mode))
        rep.RescaleTransferFunctionToDataRange(False, True)
        T.start_view(view, rep, camera)
        _, images[mode], frames = T.refine(view, rep)
        failures.check(frames[-1]["RefinementComplete"] == 1,
            "AMR Centroid by %s: refined (%d frames)" % (mode, len(frames)))
        T.is_drawn(images[mode], failures, "AMR Centroid by %s" % mode)
    worst, mean = T.difference(images["Magnitude"], images["X"])
    failures.check(mean > 1.0,
        "AMR Centroid: its magnitude and its X component are drawn differently (mean %.2f levels, "
        "max %d)" % (mean, worst))


def check_interactor(view, args, failures):
    """With an interactor, as in the GUI, the image refines by itself: the plugin's scheduler arms
    a timer on the view's interactor after each still render that leaves refinement pending, and
    renders the view through its proxy on the tick. pvbatch's interactor (Interact()'s) is a
    vtkGenericRenderWindowInteractor, whose host delivers timer events; the GUI's Qt interactor
    delivers them from Qt timers. Here the script plays the host: it delivers timer events and
    never calls Render(). A view of its own, so that no earlier scene shows."""
    view = T.make_view()
    source, rep, camera = T.wavelet_scene(view)
    T.start_view(view, rep, camera)
    if not view.MakeRenderWindowInteractor(True):
        failures.check(False, "pvbatch makes an interactor for the view")
        return
    interactor = view.GetInteractor()
    pvs.Render(view)  # one frame, and the scheduler arms its timer
    before = T.state(rep)
    events = 0
    while events < 64 and not T.state(rep)["RefinementComplete"]:
        interactor.TimerEvent()  # what the host does when the driver's timer fires
        events += 1
    after = T.state(rep)
    failures.check(before["NumberOfFramesAccumulated"] == 1 and after["RefinementComplete"] == 1 and
        after["NumberOfFramesAccumulated"] == after["FrameLimit"] > 1,
        "with an interactor the image refines by itself after one Render() (%d frame, then %d of "
        "%d frames after %d timer events and no Render() call)" % (
            before["NumberOfFramesAccumulated"], after["NumberOfFramesAccumulated"],
            after["FrameLimit"], events))
    final = T.capture(view)
    T.compare_baseline(final, "ParaViewWaveletInteractor", args.baselines, args.output, failures,
        baseline_name="ParaViewWavelet")
    pvs.Hide(source, view)


def check_saved_images(view, args, failures):
    """SaveScreenshot at twice the view's resolution and a frame of SaveAnimation are the refined
    image at that resolution (the view refined at that size, one render per frame), not one
    frame; RefineSavedImages off keeps the old behaviour (one frame)."""
    source, rep, camera = T.wavelet_scene(view)
    big = [2 * T.VIEW_SIZE[0], 2 * T.VIEW_SIZE[1]]
    T.start_view(view, rep, camera)
    T.refine(view, rep)
    shot = os.path.join(args.output, "ParaViewSaved2x.png")
    pvs.SaveScreenshot(shot, view, ImageResolution=big)
    saved = T.read_png(shot)
    after_shot = T.state(rep)
    rep.RefineSavedImages = 0
    T.set_camera(view, camera)
    pvs.Render(view)
    one_frame_shot = os.path.join(args.output, "ParaViewSaved2xOneFrame.png")
    pvs.SaveScreenshot(one_frame_shot, view, ImageResolution=big)
    one_frame = T.read_png(one_frame_shot)
    rep.RefineSavedImages = 1
    # The expectation: the view itself at that size, refined a render per frame.
    view.ViewSize = big
    T.start_view(view, rep, camera)
    _, refined, frames = T.refine(view, rep)
    failures.check(frames[-1]["RefinementComplete"] == 1 and len(frames) == 4,
        "the view refines at %dx%d in 4 renders" % tuple(big))
    pattern = os.path.join(args.output, "ParaViewSavedAnimation.png")
    view.ViewSize = T.VIEW_SIZE
    T.set_camera(view, camera)
    pvs.SaveAnimation(pattern, view, ImageResolution=big, FrameWindow=[0, 0])
    animated = T.read_png(pattern.replace(".png", ".0000.png"))
    # Refined images sampled from other pixel offsets (ParaView may capture in tiles) differ by a
    # few levels here and there; one frame differs everywhere (measured: mean 0.28 levels, max
    # 37, against 0.02 and 10 refined).
    for label, image in (("SaveScreenshot at 2x", saved), ("a SaveAnimation frame at 2x", animated)):
        worst, mean = T.difference(image, refined)
        failures.check(image.shape == refined.shape and worst <= 16 and mean <= 0.08,
            "%s is the refined image at that size: max %d levels (at most 16), mean %.3f "
            "(at most 0.08)" % (label, worst, mean))
    worst, mean = T.difference(one_frame, refined)
    failures.check(mean > 0.15,
        "with RefineSavedImages off, the saved image is one frame: mean %.3f levels from the "
        "refined one (more than 0.15), max %d" % (mean, worst))
    failures.check(after_shot["RefinementComplete"] == 1,
        "the view is still complete after the screenshot")
    view.ViewSize = T.VIEW_SIZE
    pvs.Delete(rep)
    pvs.Delete(source)


def check_python_module(args, failures):
    """`import vtksavr` from build-paraview/python in pvbatch: the module wrapped against
    ParaView's own VTK renders the wavelet to completion in a plain VTK window, and no module of
    Debian's VTK is loaded beside ParaView's."""
    sys.path.insert(0, os.path.join(T.BUILD, "python"))
    import vtksavr
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer,
        vtkRenderWindow, vtkVolume, vtkVolumeProperty)
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    failures.check(os.path.realpath(vtksavr.vtkSAVR.__file__).startswith(os.path.realpath(T.BUILD)),
        "vtksavr is the one built against ParaView (%s)" % vtksavr.vtkSAVR.__file__)
    foreign = sorted(name for name, module in sys.modules.items()
        if name.startswith("vtkmodules") and getattr(module, "__file__", None)
        and not os.path.realpath(module.__file__).startswith(
            os.path.realpath(os.path.join(T.BUILD, "python3-paraview"))))
    failures.check(not foreign, "only ParaView's vtkmodules are loaded (others: %s)" % foreign[:5])
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-10, 10, -10, 10, -10, 10)
    mapper = vtksavr.vtkSAVRVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    colors = vtkColorTransferFunction()
    colors.AddRGBPoint(40.0, 0.1, 0.2, 0.9)
    colors.AddRGBPoint(280.0, 1.0, 0.8, 0.1)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(40.0, 0.0)
    opacity.AddPoint(280.0, 0.6)
    prop = vtkVolumeProperty()
    prop.SetColor(colors)
    prop.SetScalarOpacity(opacity)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.SetBackground(T.BACKGROUND)
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(120, 120)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renders = 0
    while not mapper.GetRefinementComplete() and renders < 64:
        window.Render()
        renders += 1
    failures.check(renders == 4 and mapper.GetNumberOfFramesAccumulated() == 4,
        "the pvbatch-wrapped mapper refines in 4 renders (%d renders, %d frames)" % (
            renders, mapper.GetNumberOfFramesAccumulated()))
    T.is_drawn(T.capture_window(window), failures, "vtksavr in pvbatch")


def check_translucent(view, args, failures):
    """A sphere of opacity 0.4 through the wavelet, and one in front of it, with ParaView's
    defaults (depth peeling, and peeling for volumes, on): "SAVR Volume" refines one frame per
    render (dual depth peeling calls a volume's Render several times per frame) and is within a
    mean of 3 levels of the stock "Volume" representation (the GPU mapper here) on the same
    scene, which composites the two in depth order."""
    failures.check(view.DepthPeeling == 1 and view.DepthPeelingForVolumes == 1,
        "the view peels translucent geometry and volumes (ParaView's defaults)")
    for label, center in (("Translucent", [3.0, 0.0, 0.0]),
                          ("TranslucentInFront", [-9.0, -14.4, 10.5])):
        source, rep, camera = T.wavelet_scene(view)
        sphere = pvs.Sphere(Center=center, Radius=6.0, ThetaResolution=48, PhiResolution=48)
        surface = pvs.Show(sphere, view)
        surface.ColorArrayName = ["POINTS", ""]
        surface.DiffuseColor = [0.9, 0.9, 0.9]
        surface.Opacity = 0.4
        T.start_view(view, rep, camera)
        _, final, frames = T.refine(view, rep)
        T.print_frames(label, frames)
        failures.check([f["NumberOfFramesAccumulated"] for f in frames] == [1, 2, 3, 4],
            "%s: with a translucent sphere, each render refines one frame (%s)" %
            (label, [f["NumberOfFramesAccumulated"] for f in frames]))
        T.write_png(final, os.path.join(args.output, "ParaView%s.png" % label))
        compare_with_stock(view, rep, final, label, args, failures, 3.0)
        pvs.Delete(surface)
        pvs.Delete(sphere)
        pvs.Delete(rep)
        pvs.Delete(source)


def check_slice(view, args, failures):
    """BlendMode "Slice" with the representation's slice plane: the mapper draws the plane in
    one render, draws it again where it is moved, and is within a mean of 2 levels of the stock
    "Volume" representation's slice."""
    source, rep, camera = T.wavelet_scene(view)
    rep.BlendMode = "Slice"
    rep.SliceFunction.Origin = [1.0, -2.0, 0.5]
    rep.SliceFunction.Normal = [1.0, 0.6, 0.8]
    T.start_view(view, rep, camera)
    pvs.Render(view)
    s = T.state(rep)
    final = T.capture(view)
    failures.check(s["RefinementComplete"] == 1 and s["NumberOfFramesAccumulated"] >= 1,
        "Slice: the plane is complete in one render (%d frames)" % s["NumberOfFramesAccumulated"])
    T.is_drawn(final, failures, "Slice")
    T.write_png(final, os.path.join(args.output, "ParaViewSlice.png"))
    # Moving the plane (the plane proxy's own properties) moves it for the mapper as well.
    rep.SliceFunction.Origin = [-3.0, 2.0, -1.0]
    pvs.Render(view)
    moved = T.capture(view)
    worst, mean = T.difference(moved, final)
    failures.check(mean > 1.0, "Slice: moving the plane changes the image (mean %.2f levels)" % mean)
    rep.SliceFunction.Origin = [1.0, -2.0, 0.5]
    pvs.Render(view)
    compare_with_stock(view, rep, final, "Slice", args, failures, 2.0)
    pvs.Delete(rep)
    pvs.Delete(source)


def check_progress(view, args, failures):
    """The representation fires no ProgressEvent from inside the view's renders (the GUI answers
    progress by processing its events, which in the middle of a render can make another OpenGL
    context current and lose depth peeling's framebuffers); the frames are in the information
    properties instead, one more each render."""
    source, rep, camera = T.wavelet_scene(view)
    sub = rep.GetClientSideObject().GetActiveRepresentation()
    T.start_view(view, rep, camera)
    pvs.Render(view)  # the first frame (the pipeline's own progress comes with its update)
    progress = []
    tag = sub.AddObserver("ProgressEvent", lambda caller, event: progress.append(caller.GetProgress()))
    _, _, frames = T.refine(view, rep)
    sub.RemoveObserver(tag)
    counted = [f["NumberOfFramesAccumulated"] for f in frames]
    failures.check(progress == [] and counted == [2, 3, 4],
        "no progress from inside renders (%d events); the state counts the frames (%s)" % (
            len(progress), counted))
    pvs.Delete(rep)
    pvs.Delete(source)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=T.DEFAULT_PLUGIN)
    parser.add_argument("--baselines", default=T.DEFAULT_BASELINES)
    parser.add_argument("--output", default=T.DEFAULT_OUTPUT)
    parser.add_argument("--scenes",
        default="python,wavelet,tetrahedra,curvilinear,hexwedge,head,amr,particles,interactor,saved,slice,translucent,progress,panel")
    parser.add_argument("--no-threads", action="store_true", help="skip the thread-count check")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    failures = T.Failures()
    # Debian's own VTK (python3-vtk9) may have ParaView's VTK version: where the modules come
    # from tells them apart.
    import paraview
    import vtkmodules
    from vtkmodules.vtkCommonCore import vtkVersion
    failures.check(os.path.dirname(os.path.dirname(vtkmodules.__file__)) ==
                   os.path.dirname(os.path.dirname(paraview.__file__)),
        "ParaView's vtkmodules are in use (VTK %s from %s)" %
        (vtkVersion.GetVTKVersion(), os.path.dirname(vtkmodules.__file__)))
    scenes = args.scenes.split(",")
    vtksavr = None
    # First: once a SAVR object has reached Python through the plugin, its class name stands for
    # vtkVolumeMapper (its nearest wrapped base) and the wrapped module can no longer define it.
    if "python" in scenes:
        check_python_module(args, failures)
    if "particles" in scenes:
        sys.path.insert(0, os.path.join(T.BUILD, "python"))
        import vtksavr
    T.load_plugin(args.plugin, remote=False)
    view = T.make_view()
    if "wavelet" in scenes:
        check_wavelet(view, args, failures)
    # Before the head loads the NIfTI reader's plugin: a plugin loaded after a SAVR Volume has been
    # shown makes ParaView merge the proxy definitions again, without the SAVR representation's
    # own SliceFunction (see ParaView/README.md, Limits).
    if "slice" in scenes:
        check_slice(view, args, failures)
    if "tetrahedra" in scenes:
        check_tetrahedra(view, args, failures)
    if "curvilinear" in scenes:
        check_curvilinear(view, args, failures)
    if "head" in scenes:
        check_head(view, args, failures)
    if "amr" in scenes:
        check_amr(view, args, failures)
    if "interactor" in scenes:
        check_interactor(view, args, failures)
    if "saved" in scenes:
        check_saved_images(view, args, failures)
    if "translucent" in scenes:
        check_translucent(view, args, failures)
    if "progress" in scenes:
        check_progress(view, args, failures)
    if "panel" in scenes:
        check_panel_groups(view, failures)
    # Last (both run programmable scripts): ParaView's programmable filter runs its script in
    # __main__, whose star import of numpy_interface.algorithms replaces builtins such as sum and
    # any for the rest of this script.
    if "hexwedge" in scenes:
        check_hex_wedge(view, args, failures)
    if "particles" in scenes:
        savr_pvbatch_particles.check_particles(view, args, failures, vtksavr, DEFAULTS)
    failures.exit()


if __name__ == "__main__":
    main()
