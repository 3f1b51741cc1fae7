"""Shared pieces of the ParaView tests of the SAVR plugin (run under pvbatch, see
run-paraview-tests.sh): scenes, refinement, image capture and strict baseline comparison.

Images are numpy arrays of shape (height, width, 3), uint8, rows bottom-up as VTK stores them.
"""
import glob
import gzip
import os
import shutil
import sys
import time

import numpy as np
from paraview import servermanager
from paraview import simple as pvs
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
import vtkmodules.vtkRenderingVolume  # noqa: F401 (vtkVolumeMapper for objects handed to Python)

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
BUILD = os.path.join(REPO, "build-paraview")
# "paraview-5.11", "paraview-5.13": the folder of the ParaView that runs this.
PARAVIEW_FOLDER = "paraview-%d.%d" % (servermanager.vtkSMProxyManager.GetVersionMajor(),
                                      servermanager.vtkSMProxyManager.GetVersionMinor())
DEFAULT_PLUGIN = os.path.join(BUILD, "lib", PARAVIEW_FOLDER, "plugins", "SAVRPlugin", "SAVRPlugin.so")
DEFAULT_BASELINES = os.path.join(REPO, "Testing", "Data", "Baseline")
DEFAULT_OUTPUT = os.path.join(BUILD, "Testing", "Temporary")
HEAD_FILE = "/usr/share/mricron/templates/ch2.nii.gz"


def shipped_plugin(name):
    """The path of a plugin that the installed ParaView ships (in its own library folder)."""
    pattern = os.path.join("/usr/lib", "*", PARAVIEW_FOLDER, "plugins", name, name + ".so")
    found = sorted(glob.glob(pattern))
    if not found:
        raise RuntimeError("ParaView's plugin %s is not installed (%s)" % (name, pattern))
    return found[0]


VIEW_SIZE = [400, 300]
BACKGROUND = [0.1, 0.1, 0.15]
# The baseline comparison, as strict as the project's VTK tests: every channel of every pixel
# within 3 levels, and the mean absolute difference at most 0.05 levels.
MAX_LEVEL = 3
MAX_MEAN = 0.05

# Each Render() of the pvbatch tests is a whole frame (they count frames per render): no bound on
# a render's time (the property's default, 0.2 s, splits long frames over renders, for the GUI).
# The GUI tests set this to None, which keeps the default.
RENDER_TIME_BOUND = 0.0


def prepare(rep):
    """Applies RENDER_TIME_BOUND to a SAVR representation."""
    if RENDER_TIME_BOUND is not None:
        rep.MaximumRenderTime = RENDER_TIME_BOUND
    return rep


STATE_PROPERTIES = ["NumberOfFramesAccumulated", "FrameLimit", "RefinementComplete",
                    "ErrorEstimate", "LastFrameTime", "MemoryInUse", "EffectiveSampleDistance"]


class Failures:
    """Collects failed checks so that one run reports all of them."""

    def __init__(self):
        self.messages = []

    def check(self, condition, message):
        print(("ok:   " if condition else "FAIL: ") + message)
        sys.stdout.flush()
        if not condition:
            self.messages.append(message)
        return condition

    def exit(self):
        """Closes the session; exits with 1 when a check failed."""
        if self.messages:
            print("%d check(s) failed:" % len(self.messages))
            for m in self.messages:
                print("  " + m)
        else:
            print("all checks passed")
        sys.stdout.flush()
        close_session()
        if self.messages:
            sys.exit(1)
        # On success the script just ends: pvbatch then finalizes MPI itself (sys.exit(0) on rank
        # 0 of an MPI run skips MPI_Finalize, which mpirun reports as an abnormal exit).


def close_session():
    """Deletes every representation, view and source: pvbatch 5.11 fails at exit (GLXBadContext,
    exit code 1, whatever the code asked for) when sys.exit is called with views still alive."""
    for view in pvs.GetViews():
        for rep in list(view.Representations):
            pvs.Delete(rep)
        pvs.Delete(view)
    for source in list(pvs.GetSources().values()):
        pvs.Delete(source)


def load_plugin(path, remote):
    if not os.path.exists(path):
        raise SystemExit("plugin not found: %s (run Utilities/setup-paraview.sh)" % path)
    pvs.LoadPlugin(path, remote=remote, ns=globals())


def make_view():
    view = pvs.CreateView("RenderView")
    view.ViewSize = VIEW_SIZE
    view.OrientationAxesVisibility = 0
    if "UseColorPaletteForBackground" in view.ListProperties():
        view.UseColorPaletteForBackground = 0
    view.Background = BACKGROUND
    return view


def wavelet_scene(view, representation="SAVR Volume", extent=10):
    """The Wavelet source (RTData, about 37 to 277) with a fixed transfer function and camera."""
    source = pvs.Wavelet()
    source.WholeExtent = [-extent, extent] * 3
    rep = pvs.Show(source, view)
    rep.Representation = representation
    prepare(rep)
    pvs.ColorBy(rep, ("POINTS", "RTData"))
    lut = pvs.GetColorTransferFunction("RTData")
    lut.ColorSpace = "Diverging"
    lut.RGBPoints = [37.35, 0.23, 0.299, 0.754, 157.09, 0.865, 0.865, 0.865,
                     276.83, 0.706, 0.016, 0.15]
    pwf = pvs.GetOpacityTransferFunction("RTData")
    pwf.Points = [37.35, 0.0, 0.5, 0.0, 276.83, 1.0, 0.5, 0.0]
    rep.ScalarOpacityUnitDistance = 2.0
    # The same view of any extent (the wavelet has unit spacing around the origin).
    s = extent / 10.0
    camera = dict(position=[-30.0 * s, -48.0 * s, 35.0 * s], focal=[0.0, 0.0, 0.0],
                  up=[0.0, 0.0, 1.0])
    return source, rep, camera


# A jittered 14^3 lattice over [-10, 10]^3 (spacing h0 = 20 / 13), each point with a smooth
# value and a radius between 0.8 and 1.2 h0; numpy only (a programmable source's script shadows
# builtins such as sum and max). Piece i of n holds every n-th point from the i-th, so that on
# several ranks the cloud is spread over them (PARTICLES_INFORMATION_SCRIPT lets the source make
# any piece).
PARTICLES_INFORMATION_SCRIPT = """
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
self.GetOutputInformation(0).Set(vtkAlgorithm.CAN_HANDLE_PIECE_REQUEST(), 1)
"""
PARTICLES_SCRIPT = """
import numpy as np
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.util.numpy_support import numpy_to_vtk
n = 14
h0 = 20.0 / (n - 1)
rng = np.random.RandomState(7)
axis = -10.0 + h0 * np.arange(n)
z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
p = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
p = p + 0.3 * h0 * (rng.random_sample(p.shape) - 0.5)
radius = h0 * (0.8 + 0.4 * rng.random_sample(len(p)))
info = self.GetOutputInformation(0)
piece = info.Get(sddp.UPDATE_PIECE_NUMBER()) if info.Has(sddp.UPDATE_PIECE_NUMBER()) else 0
pieces = info.Get(sddp.UPDATE_NUMBER_OF_PIECES()) if info.Has(sddp.UPDATE_NUMBER_OF_PIECES()) else 1
p = np.ascontiguousarray(p[piece::pieces])
radius = radius[piece::pieces]
points = vtkPoints()
points.SetData(numpy_to_vtk(p, deep=1))
out = self.GetPolyDataOutput()
out.SetPoints(points)
value = 150.0 + 70.0 * np.sin(0.35 * p[:, 0]) * np.cos(0.3 * p[:, 1]) + 3.0 * p[:, 2]
output = dsa.WrapDataObject(out)
output.PointData.append(value, "value")
output.PointData.append(radius, "radius")
"""
PARTICLE_LUT = [40.0, 0.23, 0.299, 0.754, 150.0, 0.865, 0.865, 0.865, 260.0, 0.706, 0.016, 0.15]
PARTICLE_OPACITY = [40.0, 0.0, 0.5, 0.0, 260.0, 0.8, 0.5, 0.0]
PARTICLE_UNIT_DISTANCE = 2.0


def particles_source():
    """The cloud of PARTICLES_SCRIPT, a vtkPolyData of 2744 points without cells (spread over
    the ranks)."""
    source = pvs.ProgrammableSource()
    source.OutputDataSetType = "vtkPolyData"
    source.Script = PARTICLES_SCRIPT
    source.ScriptRequestInformation = PARTICLES_INFORMATION_SCRIPT
    return source


def color_particles(rep):
    """Colors `rep` by the particles' value with the scene's transfer functions (set after
    ColorBy, which may rescale them to the data)."""
    pvs.ColorBy(rep, ("POINTS", "value"))
    lut = pvs.GetColorTransferFunction("value")
    lut.ColorSpace = "RGB"
    lut.Discretize = 0
    lut.RGBPoints = PARTICLE_LUT
    pwf = pvs.GetOpacityTransferFunction("value")
    pwf.Points = PARTICLE_OPACITY
    rep.ScalarOpacityUnitDistance = PARTICLE_UNIT_DISTANCE


def particles_scene(view, representation="SAVR Volume"):
    """The particle cloud shown as `representation` with the SPH cubic kernel, the point array
    "radius" as radii, normalized; a fixed transfer function (RGB, not discretized, so that the
    same numbers give the same colours in plain VTK) and camera."""
    source = particles_source()
    rep = pvs.Show(source, view)
    rep.Representation = representation
    prepare(rep)
    color_particles(rep)
    camera = dict(position=[-38.0, -61.0, 44.0], focal=[0.0, 0.0, 0.0], up=[0.0, 0.0, 1.0])
    return source, rep, camera


def head_scene(view, work_dir, representation="SAVR Volume"):
    """The MRI head (Colin27, 181 x 217 x 181, 8 bit), read by the NIfTI reader ParaView ships
    (plugin AnalyzeNIfTIReaderWriter); that reader does not read .nii.gz (it crashes), so the
    file is decompressed first. Skin and bone transfer functions, shading on."""
    functions = {"__doc__": None}  # not empty: LoadPlugin fills globals() when ns is falsy
    pvs.LoadPlugin(shipped_plugin("AnalyzeNIfTIReaderWriter"), remote=False, ns=functions)
    os.makedirs(work_dir, exist_ok=True)
    nii = os.path.join(work_dir, "ch2.nii")
    if not os.path.exists(nii):
        with gzip.open(HEAD_FILE) as compressed, open(nii + ".part", "wb") as plain:
            shutil.copyfileobj(compressed, plain)
        os.replace(nii + ".part", nii)
    reader = functions["NIfTIVolumereader"](FileName=nii)
    rep = pvs.Show(reader, view)
    rep.Representation = representation
    prepare(rep)
    array = reader.PointData.keys()[0]
    pvs.ColorBy(rep, ("POINTS", array))
    lut = pvs.GetColorTransferFunction(array)
    lut.ColorSpace = "RGB"
    lut.RGBPoints = [0.0, 0.0, 0.0, 0.0, 60.0, 0.75, 0.45, 0.35, 110.0, 0.95, 0.8, 0.7,
                     255.0, 1.0, 1.0, 0.95]
    pwf = pvs.GetOpacityTransferFunction(array)
    pwf.Points = [40.0, 0.0, 0.5, 0.0, 70.0, 0.05, 0.5, 0.0, 120.0, 0.25, 0.5, 0.0,
                  255.0, 0.6, 0.5, 0.0]
    rep.ScalarOpacityUnitDistance = 1.0
    rep.Shade = 1
    rep.Ambient = 0.3
    rep.Diffuse = 0.7
    rep.Specular = 0.2
    rep.SpecularPower = 10.0
    # Face the head from the front right, a little from above (+y anterior, +z superior).
    bounds = reader.GetDataInformation().GetBounds()
    center = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]
    direction = np.array([np.sin(np.radians(35)), np.cos(np.radians(35)), 0.1])
    direction /= np.linalg.norm(direction)
    camera = dict(position=list(np.array(center) + 620.0 * direction), focal=center,
                  up=[0.0, 0.0, 1.0])
    return reader, rep, camera


def amr_pulse_scene(view, representation="SAVR Volume"):
    """ParaView's AMRGaussianPulseSource (vtkOverlappingAMR, 2 levels: root spacing 0.5, the
    refined blocks 0.25), a Gaussian pulse off the centre, colored by its cell array
    "Gaussian-Pulse" (about 0 to 0.97) with a fixed transfer function and camera."""
    source = pvs.AMRGaussianPulseSource()
    source.Dimension = "3D"
    source.RootSpacing = 0.5
    source.RefinementRatio = 2
    source.XPulseOrigin, source.YPulseOrigin, source.ZPulseOrigin = -0.4, -0.5, 1.2
    source.XPulseWidth = source.YPulseWidth = source.ZPulseWidth = 0.8
    source.PulseAmplitude = 1.0
    rep = pvs.Show(source, view)
    rep.Representation = representation
    prepare(rep)
    pvs.ColorBy(rep, ("CELLS", "Gaussian-Pulse"))
    lut = pvs.GetColorTransferFunction("Gaussian-Pulse")
    lut.ColorSpace = "Diverging"
    lut.RGBPoints = [0.0, 0.23, 0.299, 0.754, 0.5, 0.865, 0.865, 0.865, 1.0, 0.706, 0.016, 0.15]
    pwf = pvs.GetOpacityTransferFunction("Gaussian-Pulse")
    pwf.Points = [0.05, 0.0, 0.5, 0.0, 1.0, 1.0, 0.5, 0.0]
    rep.ScalarOpacityUnitDistance = 0.5
    # The data spans [-2, 0.5] x [-2, 0.5] x [0, 2.5]: seen obliquely from above.
    center = [-0.75, -0.75, 1.25]
    camera = dict(position=[center[0] + 4.5, center[1] - 5.5, center[2] + 4.0], focal=center,
                  up=[0.0, 0.0, 1.0])
    return source, rep, camera


def find_volumes(view, mapper_class):
    """The visible vtkVolumes of the view's renderer drawn by a mapper of class `mapper_class`
    (the VTK objects: this process renders)."""
    volumes = view.GetClientSideObject().GetRenderer().GetVolumes()
    volumes.InitTraversal()
    found = []
    for _ in range(volumes.GetNumberOfItems()):
        volume = volumes.GetNextVolume()
        mapper = volume.GetMapper()
        if volume.GetVisibility() and mapper is not None and mapper.GetClassName() == mapper_class:
            found.append(volume)
    return found


def set_camera(view, camera):
    view.CameraPosition = camera["position"]
    view.CameraFocalPoint = camera["focal"]
    view.CameraViewUp = camera["up"]
    view.CameraViewAngle = 30.0
    view.CameraParallelProjection = 0


def state(rep):
    """The mapper's state (of the first process) after the last render."""
    rep.SMProxy.UpdatePropertyInformation()
    return {name: rep.GetProperty(name).GetData() for name in STATE_PROPERTIES}


def capture(view):
    """The image the last render left in the view's window, without rendering again (a render
    would add a refinement frame)."""
    return capture_window(view.GetRenderWindow())


def capture_window(window):
    """The image the last render left in a VTK render window, as rows of RGB bytes."""
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ShouldRerenderOff()
    grab.ReadFrontBufferOff()
    grab.SetInputBufferTypeToRGB()
    grab.Update()
    image = grab.GetOutput()
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, 3).copy()


def thread_cpu():
    """CPU seconds used so far by each thread of this process, by thread id."""
    ticks = os.sysconf("SC_CLK_TCK")
    result = {}
    for tid in os.listdir("/proc/self/task"):
        try:
            with open("/proc/self/task/%s/stat" % tid) as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
            result[tid] = (int(fields[11]) + int(fields[12])) / ticks  # utime + stime
        except (OSError, IndexError, ValueError):
            pass
    return result


def busy_threads(before, after):
    """How many threads did a good share of the work between two thread_cpu() readings: at
    least a quarter of the CPU time and 20 ms. This counts threads, not cores; over one render
    it depends on what else runs on the machine (a thread the scheduler kept waiting does little
    of that render), so a check of parallelism reads it over several."""
    used = [after[t] - before.get(t, 0.0) for t in after]
    total = sum(used)
    return sum(1 for u in used if u >= 0.02 and u >= 0.25 * total)


def render_timed(view):
    """Render() once: wall seconds, CPU seconds, and the threads busy in it (busy_threads)."""
    before, wall, cpu = thread_cpu(), time.perf_counter(), os.times()
    pvs.Render(view)
    after_cpu, wall = os.times(), time.perf_counter() - wall
    busy = busy_threads(before, thread_cpu())
    cpu = (after_cpu.user - cpu.user) + (after_cpu.system - cpu.system)
    return wall, cpu, busy


def start_view(view, rep, camera):
    """Warms the view up and starts refinement at `camera`: ParaView's first render of a view
    renders twice, so the first render is made from another camera; after the camera change,
    every render is exactly one refinement frame."""
    warm = dict(camera)
    warm["position"] = [p + 0.25 * (p - f) for p, f in zip(camera["position"], camera["focal"])]
    set_camera(view, warm)
    pvs.Render(view)
    set_camera(view, camera)


def refine(view, rep, max_renders=64):
    """Renders until the mapper reports refinement complete. Returns the image after the first
    frame, the final image, and per-frame records (state, wall and CPU seconds of Render())."""
    frames = []
    first = None
    for _ in range(max_renders):
        wall, cpu, busy = render_timed(view)
        s = state(rep)
        s["wall"], s["cpu"], s["busy"] = wall, cpu, busy
        frames.append(s)
        if first is None:
            first = capture(view)
        if s["RefinementComplete"]:
            break
    return first, capture(view), frames


def print_frames(label, frames):
    for i, f in enumerate(frames):
        print("%s render %d: frames %d/%d complete %d  mapper %.3f s  Render() %.3f s wall, "
              "%.3f s CPU (CPU/wall %.2f, %d busy threads)  error estimate %.5f  stored %.1f MiB" % (
                  label, i + 1, f["NumberOfFramesAccumulated"], f["FrameLimit"],
                  f["RefinementComplete"], f["LastFrameTime"], f["wall"], f["cpu"],
                  f["cpu"] / max(f["wall"], 1e-9), f["busy"], f["ErrorEstimate"], f["MemoryInUse"] / 2**20))
    sys.stdout.flush()


def write_png(image, path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    data = vtkImageData()
    data.SetDimensions(image.shape[1], image.shape[0], 1)
    data.GetPointData().SetScalars(numpy_to_vtk(image.reshape(-1, image.shape[2]), deep=1))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.Write()


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    pixels = vtk_to_numpy(scalars).reshape(height, width, scalars.GetNumberOfComponents())
    return pixels[..., :3].copy()


def difference(a, b):
    d = np.abs(a.astype(np.int32) - b.astype(np.int32))
    return int(d.max()), float(d.mean())


def is_drawn(image, failures, label):
    """Not blank: a good part of the image differs from the background, with structure."""
    background = np.round(np.array(BACKGROUND) * 255).astype(np.int32)
    off = np.abs(image.astype(np.int32) - background).max(axis=2) > 8
    fraction = float(off.mean())
    spread = float(image[off].std()) if off.any() else 0.0
    return failures.check(fraction > 0.05 and spread > 5.0,
        "%s is drawn: %.1f%% of pixels differ from the background, spread %.1f levels" % (
            label, 100 * fraction, spread))


def compare_baseline(image, name, baseline_dir, output_dir, failures, max_level=MAX_LEVEL,
                     max_mean=MAX_MEAN, baseline_name=None):
    """Compares with <baseline_dir>/<baseline_name or name>.png. The image is always written to
    <output_dir>/<name>.png; a missing baseline fails (copy the written image there after
    reviewing it)."""
    written = os.path.join(output_dir, name + ".png")
    write_png(image, written)
    baseline = os.path.join(baseline_dir, (baseline_name or name) + ".png")
    if not os.path.exists(baseline):
        return failures.check(False, "%s: no baseline %s; the image was written to %s" % (
            name, baseline, written))
    expected = read_png(baseline)
    if expected.shape != image.shape:
        return failures.check(False, "%s: size %s, baseline %s" % (name, image.shape, expected.shape))
    worst, mean = difference(image, expected)
    ok = worst <= max_level and mean <= max_mean
    if not ok:
        d = np.abs(image.astype(np.int32) - expected.astype(np.int32))
        write_png(np.clip(d * 16, 0, 255).astype(np.uint8), os.path.join(output_dir, name + ".diff.png"))
    return failures.check(ok, "%s vs baseline: max %d levels (at most %d), mean %.4f (at most %.2f)" % (
        name, worst, max_level, mean, max_mean))


def check_placement(view, rep, volume, label, failures):
    """The representation's placement (the name ParaView gives its translation, Position before
    5.12 and Translation since, and Scale) reaches the SAVR volume."""
    translation = "Translation" if rep.GetProperty("Translation") is not None else "Position"
    rep.SetPropertyWithName(translation, [4.0, 0.0, -2.0])
    rep.Scale = [1.0, 2.0, 1.0]
    pvs.Render(view)
    placed = (list(volume.GetPosition()), list(volume.GetScale()))
    failures.check(placed == ([4.0, 0.0, -2.0], [1.0, 2.0, 1.0]),
        "%s: %s and Scale reach the volume (position %s, scale %s)" % (
            label, translation, placed[0], placed[1]))
    rep.SetPropertyWithName(translation, [0.0, 0.0, 0.0])
    rep.Scale = [1.0, 1.0, 1.0]


def mapper_cell_types(volume):
    """The VTK cell types of the grid the mapper was given."""
    grid = volume.GetMapper().GetInputDataObject(0, 0)
    return sorted({grid.GetCellType(i) for i in range(grid.GetNumberOfCells())})


HEX_WEDGE_SCRIPT = """
from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_WEDGE
grid = self.GetInput()
out = self.GetOutput()
e = grid.GetExtent()
nx, ny, nz = e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1
out.SetPoints(grid.GetPoints())
out.GetPointData().ShallowCopy(grid.GetPointData())
out.Allocate(2 * (nx - 1) * (ny - 1) * (nz - 1))
def pid(i, j, k):
    return i + nx * (j + ny * k)
for k in range(nz - 1):
    for j in range(ny - 1):
        for i in range(nx - 1):
            c = [pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k), pid(i, j + 1, k),
                 pid(i, j, k + 1), pid(i + 1, j, k + 1), pid(i + 1, j + 1, k + 1),
                 pid(i, j + 1, k + 1)]
            if 2 * k < nz - 1:
                out.InsertNextCell(VTK_HEXAHEDRON, 8, c)
            else:
                out.InsertNextCell(VTK_WEDGE, 6, [c[0], c[1], c[2], c[4], c[5], c[6]])
                out.InsertNextCell(VTK_WEDGE, 6, [c[0], c[2], c[3], c[4], c[6], c[7]])
"""


def hex_wedge_mesh(source):
    """The wavelet's voxels as hexahedra in its lower half and, above, each cut into two wedges
    (VTK types 12 and 13), with the wavelet's point values: a mesh the stock preprocessing would
    cut into tetrahedra."""
    mesh = pvs.ProgrammableFilter(Input=pvs.ImageDatatoPointSet(Input=source))
    mesh.OutputDataSetType = "vtkUnstructuredGrid"
    mesh.Script = HEX_WEDGE_SCRIPT
    return mesh


# A three-level vtkOverlappingAMR over [-2, 0.5] x [-2, 0.5] x [0, 2.5] (the AMR pulse scene's
# box): level 0 has CELLS cells per edge, level 1 refines the middle half of each edge, level 2 the
# middle quarter, each level in 8 blocks of (CELLS / 2)^3 cells. Cell array "Gaussian-Pulse": a
# pulse with rings, exp(-r^2 / 0.6^2) (0.75 + 0.25 cos(12 r)) about the box's centre, at every
# level's cell centres, so finer levels hold finer detail. Run as a Programmable Source on every
# rank: the metadata of all 24 blocks everywhere, the data of block b on rank b % ranks only (so
# blocks of all levels are spread over the ranks, as a parallel reader would spread them).
AMR_RINGS_SCRIPT = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkAMRBox, vtkAMRUtilities, vtkUniformGrid
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp

cells = CELLS
info = self.GetOutputInformation(0)
rank = info.Get(sddp.UPDATE_PIECE_NUMBER()) if info.Has(sddp.UPDATE_PIECE_NUMBER()) else 0
ranks = info.Get(sddp.UPDATE_NUMBER_OF_PIECES()) if info.Has(sddp.UPDATE_NUMBER_OF_PIECES()) else 1
amr = self.GetOutput()
origin = np.array([-2.0, -2.0, 0.0])
size = 2.5
centre = origin + 0.5 * size
amr.Initialize(3, [8, 8, 8])
amr.SetOrigin(list(origin))
amr.SetGridDescription(8)  # VTK_XYZ_GRID
flat = 0
for level in range(3):
    h = size / (cells * 2 ** level)
    amr.SetSpacing(level, [h, h, h])
    amr.SetRefinementRatio(level, 2)
    first = (cells * 2 ** level - cells) // 2
    half = cells // 2
    index = 0
    for k in range(2):
        for j in range(2):
            for i in range(2):
                lo = [first + i * half, first + j * half, first + k * half]
                hi = [c + half - 1 for c in lo]
                amr.SetAMRBox(level, index, vtkAMRBox(lo, hi))
                if ranks < 2 or flat % ranks == rank:
                    grid = vtkUniformGrid()
                    corner = origin + h * np.array(lo)
                    grid.SetOrigin(list(corner))
                    grid.SetSpacing(h, h, h)
                    grid.SetDimensions(half + 1, half + 1, half + 1)
                    axis = (np.arange(half) + 0.5) * h
                    z, y, x = np.meshgrid(axis + corner[2], axis + corner[1], axis + corner[0],
                                          indexing="ij")
                    r = np.sqrt((x - centre[0]) ** 2 + (y - centre[1]) ** 2 + (z - centre[2]) ** 2)
                    value = np.exp(-(r / 0.6) ** 2) * (0.75 + 0.25 * np.cos(12.0 * r))
                    array = numpy_to_vtk(value.ravel().astype(np.float32), deep=1)
                    array.SetName("Gaussian-Pulse")
                    grid.GetCellData().AddArray(array)
                    amr.SetDataSet(level, index, grid)
                index += 1
                flat += 1
vtkAMRUtilities.BlankCells(amr)
"""


def amr_rings_source(cells=16):
    """The three-level hierarchy of AMR_RINGS_SCRIPT with `cells` level-0 cells per edge (a
    multiple of 2), as a Programmable Source."""
    source = pvs.ProgrammableSource()
    source.OutputDataSetType = "vtkHierarchicalBoxDataSet"  # a vtkOverlappingAMR
    source.Script = AMR_RINGS_SCRIPT.replace("CELLS", str(int(cells)))
    return source


def amr_rings_scene(view, cells=16):
    """amr_rings_source shown as "SAVR Volume", colored by "Gaussian-Pulse" with a transfer
    function that shows the rings, and a camera close to them."""
    source = amr_rings_source(cells)
    rep = pvs.Show(source, view)
    rep.Representation = "SAVR Volume"
    prepare(rep)
    pvs.ColorBy(rep, ("CELLS", "Gaussian-Pulse"))
    lut = pvs.GetColorTransferFunction("Gaussian-Pulse")
    lut.ColorSpace = "Diverging"
    lut.RGBPoints = [0.0, 0.23, 0.299, 0.754, 0.5, 0.865, 0.865, 0.865, 1.0, 0.706, 0.016, 0.15]
    pwf = pvs.GetOpacityTransferFunction("Gaussian-Pulse")
    pwf.Points = [0.05, 0.0, 0.5, 0.0, 0.4, 0.1, 0.5, 0.0, 1.0, 0.9, 0.5, 0.0]
    rep.ScalarOpacityUnitDistance = 0.25
    center = [-0.75, -0.75, 1.25]
    camera = dict(position=[center[0] + 1.8, center[1] - 2.2, center[2] + 1.6], focal=center,
                  up=[0.0, 0.0, 1.0])
    return source, rep, camera


def held_blocks(amr):
    """How many blocks of a vtkOverlappingAMR this process holds data for. (A loop, not sum():
    once a Programmable Source has run, `sum` in the script's namespace is numpy_interface's.)"""
    count = 0
    for level in range(amr.GetNumberOfLevels()):
        for i in range(amr.GetNumberOfDataSets(level)):
            if amr.GetDataSet(level, i):
                count += 1
    return count


def held_blocks_total(amr):
    """How many blocks the metadata of a vtkOverlappingAMR lists, held here or not."""
    count = 0
    for level in range(amr.GetNumberOfLevels()):
        count += amr.GetNumberOfDataSets(level)
    return count
