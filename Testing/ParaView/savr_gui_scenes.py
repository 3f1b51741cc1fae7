"""ParaView GUI tests of the SAVR plugin as a user meets it, one scene per run:

    SAVR_PLUGIN=.../SAVRPlugin.so SAVR_GUI_SCENE=<scene> \\
    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a -s "-noreset" paraview --dr --script=Testing/ParaView/savr_gui_scenes.py

Runs inside the real GUI (its Qt event loop, its Qt interactor, its output window). The script
sets a scene up, then only watches on a timer of its own, which renders nothing: after the
script's one still render (as the end of a drag makes) the view must refine by itself, with the
renders the plugin asks ParaView's view proxy for. Scenes:

  peeling      the wavelet with a sphere of opacity 0.4 through it, ParaView's defaults (depth
               peeling, also for volumes): refines to the frame limit by itself, and the refined
               image is within a mean of 3 levels of the stock "Volume" of the same scene (the
               bound of the pvbatch test).
  annotations  the wavelet with its colour legend and the orientation axes: every refinement
               frame the view shows has both (their corners of the view differ from the
               background), and every frame is a render of the view proxy.
  idle         a SAVR Volume that draws nothing (solid color), then one hidden while it refines:
               no render of the view in the 2 s after.
  autoarray    a wavelet shown as an outline, switched to "SAVR Volume" as the GUI's
               representation list does (SetRepresentationType): colored by RTData at once, and
               refined by itself.
  amrfirst     the AMR Gaussian Pulse Source switched to "SAVR Volume" the same way: coloured by
               the array the GUI picks (the vector "Centroid", by its magnitude), drawn and
               refined by itself, with no message.
  drag         a drag in the view with the mouse (Qt events, QtTesting-free): the renders
               during it are interactive ones, after it the view refines by itself.
  server       run with paraview --server-url=cs://... (a pvserver): the wavelet refines by
               itself, the server rendering each frame (its state, read from the server, reaches
               the frame limit) and the client showing the refined image.
  timings      not a test (not run by the runner): prints, for the MRI head and the wavelet cut
               into tetrahedra, SAVR Volume against the stock Volume in the same GUI, the
               seconds of the renders during a mouse drag and from the release to the final
               image.
  responsive   a Point Source of 200,000 points with Elevation switched to "SAVR Volume", whose
               frames take seconds: while it refines, no render holds the event loop for more
               than 0.5 s (a timer of 50 ms never waits longer), and a camera change made
               during refinement is drawn within 0.5 s.

Each exits with 0 when its checks pass, 1 otherwise or after its deadline. The runner
(run-paraview-tests.sh) also fails a run whose output holds an error or warning of VTK or
ParaView (what the GUI would pop up in its Output Messages window).
"""
import os
import sys
import time

from paraview import simple as pvs

sys.path.insert(0, os.path.join("Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402

T.RENDER_TIME_BOUND = None  # the GUI keeps the default bound of a render's time
import numpy as np  # noqa: E402

SCENE = os.environ.get("SAVR_GUI_SCENE", "peeling")
OUTPUT = os.environ.get("SAVR_OUTPUT", "build-paraview/Testing/Temporary")
plugin = os.environ.get("SAVR_PLUGIN", T.DEFAULT_PLUGIN)
pvs.LoadPlugin(plugin, remote=False, ns=globals())
# Connected to a pvserver (paraview --server-url=cs://...): the plugin on the server too.
REMOTE = pvs.servermanager.ActiveConnection.IsRemote()
if REMOTE:
    pvs.LoadPlugin(plugin, remote=True, ns=globals())
view = pvs.GetActiveViewOrCreate("RenderView")
interactor = view.GetInteractor()
if interactor is None or interactor.GetClassName() != "QVTKInteractor":
    print("savr_gui_scenes: FAILED: the view has no Qt interactor", flush=True)
    os._exit(1)

# Every render of the view proxy, with whether it is interactive and whether the script made it.
renders = []
script_rendering = [False]


def on_render(caller, event):
    renders.append((time.time(), script_rendering[0]))


view.SMProxy.AddObserver("StartEvent", on_render)
# Every render of the view's window, whoever makes it (the view proxy, or anything that renders
# the window directly).
window_renders = []
view.GetRenderWindow().AddObserver("StartEvent", lambda caller, event: window_renders.append(
    time.time()))
failed = []


def check(ok, message):
    print("savr_gui_scenes: %s: %s" % ("ok" if ok else "FAILED", message), flush=True)
    if not ok:
        failed.append(message)
    return ok


def render():
    """One still render made by the script (as the end of a drag makes one)."""
    script_rendering[0] = True
    try:
        pvs.Render(view)
    finally:
        script_rendering[0] = False


def state(rep):
    rep.SMProxy.UpdatePropertyInformation()
    return {name: rep.GetProperty(name).GetData() for name in
            ("NumberOfFramesAccumulated", "FrameLimit", "RefinementComplete")}


def wait_refined(rep, deadline):
    """Yields until the representation reports refinement complete at its frame limit (or the
    deadline, in seconds from now, passes); returns the seconds it took, None on timeout."""
    start = time.time()
    while time.time() - start < deadline:
        s = state(rep)
        if s["RefinementComplete"] and s["NumberOfFramesAccumulated"] == s["FrameLimit"] > 1:
            return time.time() - start
        yield 0.1
    return None


# How long a scene waits for refinement to complete by itself: generous, so that a loaded
# machine (a CI runner, a user's busy desktop) passes; refinement takes seconds on an idle 2-core
# machine, and a fault that stops it waits forever.
REFINE_DEADLINE = 90.0


def refined_by_itself(rep, label, deadline=REFINE_DEADLINE):
    """Moves the camera a little and renders once, as the end of a drag does: one frame. Then
    refinement completes with renders the script did not make."""
    position = np.array(view.CameraPosition)
    focal = np.array(view.CameraFocalPoint)
    view.CameraPosition = list(focal + 1.02 * (position - focal))
    before = len(renders)
    render()
    first = state(rep)
    took = yield from wait_refined(rep, deadline)
    s = state(rep)
    own = sum(1 for _, by_script in renders[before:] if not by_script)
    # One frame at most: a frame that takes longer than a render may goes on in the next ones.
    check(first["NumberOfFramesAccumulated"] <= 1 and took is not None and
          own >= s["FrameLimit"] - 1,
          "%s: at most 1 frame after the camera change, then refined by itself to %d of %d frames in %s "
          "with %d renders of the view proxy" % (
              label, s["NumberOfFramesAccumulated"], s["FrameLimit"],
              "%.2f s" % took if took is not None else "(not within %g s)" % deadline, own))
    return took is not None


def time_renders():
    """Records the seconds of every render of the view from now on: the list, and the function
    that stops recording."""
    durations = []
    starts = {}

    def started(caller, event):
        starts["t"] = time.time()

    def ended(caller, event):
        if "t" in starts:
            durations.append(time.time() - starts.pop("t"))

    tags = [view.SMProxy.AddObserver("StartEvent", started),
            view.SMProxy.AddObserver("EndEvent", ended)]

    def stop():
        for tag in tags:
            view.SMProxy.RemoveObserver(tag)

    return durations, stop


def background_differs(image, box):
    """Whether the box (fractions of the view: x0, x1, y0, y1) holds pixels off the background."""
    h, w = image.shape[:2]
    x0, x1, y0, y1 = int(box[0] * w), int(box[1] * w), int(box[2] * h), int(box[3] * h)
    region = image[y0:y1, x0:x1].astype(np.int32)
    background = np.round(np.array(view.Background) * 255).astype(np.int32)
    return int((np.abs(region - background).max(axis=2) > 40).sum())


def scene_peeling():
    source, rep, camera = T.wavelet_scene(view)
    sphere = pvs.Sphere(Center=[3.0, 0.0, 0.0], Radius=6.0, ThetaResolution=48, PhiResolution=48)
    surface = pvs.Show(sphere, view)
    surface.ColorArrayName = ["POINTS", ""]
    surface.DiffuseColor = [0.9, 0.9, 0.9]
    surface.Opacity = 0.4
    view.OrientationAxesVisibility = 0
    if "UseColorPaletteForBackground" in view.ListProperties():
        view.UseColorPaletteForBackground = 0
    view.Background = T.BACKGROUND
    check(view.DepthPeeling == 1 and view.DepthPeelingForVolumes == 1,
          "the view peels translucent geometry and volumes (ParaView's defaults)")
    T.start_view(view, rep, camera)
    yield 2.0
    ok = yield from refined_by_itself(rep, "translucent sphere, depth peeling")
    image = T.capture(view)
    T.write_png(image, os.path.join(OUTPUT, "GUIPeeling.png"))
    rep.Representation = "Volume"
    render()
    yield 0.5
    stock = T.capture(view)
    T.write_png(stock, os.path.join(OUTPUT, "GUIPeelingStockVolume.png"))
    worst, mean = T.difference(stock, image) if stock.shape == image.shape else (-1, 99.0)
    check(ok and mean <= 3.0, "the refined image is within a mean of 3 levels of the stock "
          "Volume: mean %.2f, max %d" % (mean, worst))


def scene_annotations():
    source, rep, camera = T.wavelet_scene(view)
    rep.SetScalarBarVisibility(view, True)
    bar = pvs.GetScalarBar(pvs.GetColorTransferFunction("RTData"), view)
    bar.WindowLocation = "Any Location"
    bar.Position = [0.85, 0.1]
    bar.ScalarBarLength = 0.5
    view.OrientationAxesVisibility = 1
    if "UseColorPaletteForBackground" in view.ListProperties():
        view.UseColorPaletteForBackground = 0
    view.Background = T.BACKGROUND
    T.start_view(view, rep, camera)
    yield 2.0
    frames = []

    def on_end(caller, event):
        # The image this render left in the view, read back without rendering.
        frames.append(T.capture(view))

    tag = view.SMProxy.AddObserver("EndEvent", on_end)
    yield from refined_by_itself(rep, "colour legend and orientation axes")
    view.SMProxy.RemoveObserver(tag)
    # The legend's bar sits at x 0.85 to about 0.9 of the view, y 0.1 to 0.6; the axes in the
    # lower left corner. Both are drawn in every frame (not in the volume's region).
    legend = [background_differs(f, (0.84, 0.95, 0.1, 0.6)) for f in frames]
    axes = [background_differs(f, (0.0, 0.12, 0.0, 0.15)) for f in frames]
    check(len(frames) >= 3 and min(legend) > 100 and min(axes) > 30,
          "every refinement frame shows the colour legend and the orientation axes (%d frames; "
          "legend pixels %s, axes pixels %s)" % (len(frames), legend, axes))
    if frames:
        T.write_png(frames[0], os.path.join(OUTPUT, "GUIAnnotationsFirstFrame.png"))


def scene_idle():
    source, rep, camera = T.wavelet_scene(view)
    T.start_view(view, rep, camera)
    yield 2.0
    yield from refined_by_itself(rep, "the wavelet")
    # Solid color: the volume draws nothing; nothing is left to refine. (ParaView's own renders
    # of the change are let pass first.)
    pvs.ColorBy(rep, None)
    view.CameraPosition = [-40.0, -30.0, 35.0]
    render()
    yield 1.0
    before = len(window_renders)
    yield 2.0
    check(len(window_renders) == before, "a SAVR Volume drawing nothing (solid color): %d renders "
          "of the window in 2 s (0 expected)" % (len(window_renders) - before))
    # Hidden while it refines: the refinement renders stop.
    pvs.ColorBy(rep, ("POINTS", "RTData"))
    view.CameraPosition = [-30.0, -48.0, 35.0]
    render()
    pvs.Hide(source, view)
    render()
    yield 1.0
    before = len(window_renders)
    yield 2.0
    check(len(window_renders) == before, "a SAVR Volume hidden while it refines: %d renders of "
          "the window in 2 s (0 expected)" % (len(window_renders) - before))


def scene_autoarray():
    source = pvs.Wavelet()
    rep = pvs.Show(source, view)
    render()
    yield 1.0
    check(rep.Representation == "Outline", "the wavelet shows as %s first" % rep.Representation)
    # What the GUI's representation list does; the array is chosen within the switch, before
    # any render (the GUI may show the colour legend right after).
    rep.SMProxy.SetRepresentationType("SAVR Volume")
    check(list(rep.ColorArrayName) == ["POINTS", "RTData"],
          "within the switch to SAVR Volume it is colored by %s" % list(rep.ColorArrayName))
    yield from refined_by_itself(rep, "the wavelet switched to SAVR Volume")
    colored = list(rep.ColorArrayName)
    check(colored == ["POINTS", "RTData"], "switched to SAVR Volume, it is colored by %s" % colored)
    image = T.capture(view)
    T.write_png(image, os.path.join(OUTPUT, "GUIAutoArray.png"))
    drawn = background_differs(image, (0.0, 1.0, 0.0, 1.0))
    check(drawn > 0.05 * image.shape[0] * image.shape[1],
          "the volume is drawn (%d pixels off the background)" % drawn)


def scene_amrfirst():
    """ParaView's AMR Gaussian Pulse Source switched to "SAVR Volume" as a new user does: it is
    coloured by the array the GUI picks (a vector array, "Centroid", by its magnitude), draws and
    refines by itself, with no message."""
    source = pvs.AMRGaussianPulseSource()
    rep = pvs.Show(source, view)
    view.ResetCamera()
    render()
    yield 1.0
    rep.SMProxy.SetRepresentationType("SAVR Volume")
    colored = list(rep.ColorArrayName)
    check(colored[1] != "", "switched to SAVR Volume, the pulse is coloured by %s" % colored)
    render()
    yield from refined_by_itself(rep, "the AMR pulse switched to SAVR Volume")
    image = T.capture(view)
    T.write_png(image, os.path.join(OUTPUT, "GUIAMRFirstUse.png"))
    drawn = background_differs(image, (0.0, 1.0, 0.0, 1.0))
    check(drawn > 0.05 * image.shape[0] * image.shape[1],
          "the pulse coloured by %s is drawn (%d pixels off the background)" % (colored[1], drawn))


def scene_drag():
    source, rep, camera = T.wavelet_scene(view)
    T.start_view(view, rep, camera)
    yield 2.0
    yield from refined_by_itself(rep, "the wavelet")
    # A drag: button down in the middle of the view, moves, button up, as Qt delivers them to
    # the interactor (the interactor style rotates and ParaView renders interactively).
    size = view.ViewSize
    before = len(renders)
    x, y = size[0] // 2, size[1] // 2
    interactor.SetEventInformationFlipY(x, y, 0, 0)
    interactor.InvokeEvent("LeftButtonPressEvent")
    for i in range(1, 8):
        interactor.SetEventInformationFlipY(x + 10 * i, y + 3 * i, 0, 0)
        interactor.InvokeEvent("MouseMoveEvent")
        yield 0.05
    mid = state(rep)
    interactor.InvokeEvent("LeftButtonReleaseEvent")
    check(len(renders) > before and mid["NumberOfFramesAccumulated"] <= 1,
          "during the drag the view renders (%d renders) single passes (%d frames stored)" % (
              len(renders) - before, mid["NumberOfFramesAccumulated"]))
    took = yield from wait_refined(rep, REFINE_DEADLINE)
    s = state(rep)
    check(took is not None, "after the drag the view refines by itself to %d of %d frames (%s)" % (
        s["NumberOfFramesAccumulated"], s["FrameLimit"],
        "%.2f s" % took if took is not None else "not within %g s" % REFINE_DEADLINE))


def scene_responsive():
    source = pvs.PointSource(NumberOfPoints=200000, Radius=0.5)
    elevation = pvs.Elevation(Input=source, LowPoint=[0, 0, -0.5], HighPoint=[0, 0, 0.5])
    rep = pvs.Show(elevation, view)
    view.ResetCamera()
    render()
    yield 0.5
    durations, stop_timing = time_renders()
    switched = time.time()
    rep.SMProxy.SetRepresentationType("SAVR Volume")
    render()
    first = time.time() - switched
    check(list(rep.ColorArrayName) == ["POINTS", "Elevation"],
          "switched to SAVR Volume, the cloud is colored by %s" % list(rep.ColorArrayName))
    # Watch the event loop while it refines: the gap between our 50 ms ticks is how long a
    # click would wait.
    ticks = []
    watch_start = time.time()
    while time.time() - watch_start < 6.0:
        ticks.append(time.time())
        yield 0.0
    gaps = np.diff(ticks) if len(ticks) > 1 else np.array([99.0])
    s = state(rep)
    rep.SMProxy.UpdatePropertyInformation()
    progress = rep.GetProperty("NumberOfFramesAccumulated").GetData()
    # A camera change during refinement (as a click or a drag's end makes one): drawn within
    # 0.5 s by the view's next render.
    before = len(renders)
    changed = time.time()
    view.CameraPosition = [p * 1.1 for p in view.CameraPosition]
    render()
    drawn = time.time() - changed
    stop_timing()
    print("savr_gui_scenes: 200,000 points: first render after the switch %.2f s; %d renders "
          "while refining, longest %.2f s, median %.2f s; %d frames done in 6 s; longest wait of "
          "a 50 ms timer %.2f s" % (first, len(durations), max(durations or [0]),
                                     float(np.median(durations or [0])), progress,
                                     float(gaps.max())), flush=True)
    check(first <= 1.5, "the first render after switching to SAVR Volume returns within 1.5 s "
          "(%.2f s)" % first)
    check(len(durations) >= 5 and max(durations) <= 0.5,
          "every render while refining returns within 0.5 s (%d renders, longest %.2f s)" % (
              len(durations), max(durations or [0])))
    check(float(gaps.max()) <= 0.5,
          "the event loop is never held for more than 0.5 s (longest wait %.2f s)" % gaps.max())
    check(drawn <= 0.5, "a camera change during refinement is drawn within 0.5 s (%.2f s)" % drawn)
    pvs.Delete(rep)
    pvs.Delete(elevation)
    pvs.Delete(source)


def drag_and_settle(rep, label, savr):
    """A mouse drag (8 moves 50 ms apart), then the wait for the final image: for SAVR until its
    refinement is complete, for the stock Volume until its still render after the release."""
    durations, stop_timing = time_renders()
    size = view.ViewSize
    x, y = size[0] // 2, size[1] // 2
    interactor.SetEventInformationFlipY(x, y, 0, 0)
    interactor.InvokeEvent("LeftButtonPressEvent")
    for i in range(1, 9):
        interactor.SetEventInformationFlipY(x + 6 * i, y + 2 * i, 0, 0)
        interactor.InvokeEvent("MouseMoveEvent")
        yield 0.05
    during = list(durations)
    released = time.time()
    interactor.InvokeEvent("LeftButtonReleaseEvent")
    if savr:
        took = yield from wait_refined(rep, 60.0)
    else:
        while len(durations) == len(during) and time.time() - released < 10.0:
            yield 0.02
        took = time.time() - released
    stop_timing()
    print("savr_gui_scenes: timings: %s: %d renders during the drag, median %.3f s; final image "
          "%s s after the release" % (label, len(during), float(np.median(during or [0])),
                                      "%.2f" % took if took is not None else "(none)"), flush=True)


def scene_timings():
    reader, rep, camera = T.head_scene(view, OUTPUT)
    T.set_camera(view, camera)
    render()
    yield from wait_refined(rep, 60.0)
    yield from drag_and_settle(rep, "MRI head, SAVR Volume", True)
    rep.Representation = "Volume"
    render()
    yield 1.0
    yield from drag_and_settle(rep, "MRI head, stock Volume", False)
    pvs.Hide(reader, view)
    source = pvs.Wavelet()
    cells = pvs.Tetrahedralize(Input=source)
    tets = pvs.Show(cells, view)
    tets.Representation = "SAVR Volume"
    pvs.ColorBy(tets, ("POINTS", "RTData"))
    view.ResetCamera()
    render()
    yield from wait_refined(tets, 60.0)
    yield from drag_and_settle(tets, "wavelet as tetrahedra, SAVR Volume", True)
    tets.Representation = "Volume"
    render()
    yield 1.0
    yield from drag_and_settle(tets, "wavelet as tetrahedra, stock Volume", False)


def scene_server():
    check(REMOTE, "the GUI is connected to a server")
    source, rep, camera = T.wavelet_scene(view)
    T.start_view(view, rep, camera)
    yield 2.0
    yield from refined_by_itself(rep, "the wavelet on a pvserver")
    image = T.capture(view)
    T.write_png(image, os.path.join(OUTPUT, "GUIServer.png"))
    drawn = background_differs(image, (0.0, 1.0, 0.0, 1.0))
    check(drawn > 0.05 * image.shape[0] * image.shape[1],
          "the client shows the server's image (%d pixels off the background)" % drawn)


def drawn_mean(image, box):
    """The mean colour of the box's pixels off the background (0 to 255 per channel)."""
    h, w = image.shape[:2]
    x0, x1, y0, y1 = int(box[0] * w), int(box[1] * w), int(box[2] * h), int(box[3] * h)
    region = image[y0:y1, x0:x1, :3].astype(np.int32)
    background = np.round(np.array(view.Background) * 255).astype(np.int32)
    drawn = np.abs(region - background).max(axis=2) > 40
    return region[drawn].mean(axis=0) if drawn.any() else background


def scene_density():
    # A point cloud in Solid Color: SAVR Volume draws the particles' density (a mean needs values;
    # a density does not) in Solid Color's color, a cloud brighter than the background in white,
    # with Particle Normalized off and with it on (the default) alike.
    source = pvs.PointSource(NumberOfPoints=20000, Radius=0.5)
    rep = pvs.Show(source, view)
    view.ResetCamera()
    rep.SMProxy.SetRepresentationType("SAVR Volume")
    rep.ColorArrayName = ["POINTS", ""]  # Solid Color
    rep.ParticleNormalized = 0
    render()
    yield from refined_by_itself(rep, "the cloud's density")
    image = T.capture(view)
    T.write_png(image, os.path.join(OUTPUT, "GUIDensity.png"))
    # Right of the orientation axes (lower left).
    drawn = background_differs(image, (0.25, 1.0, 0.0, 1.0))
    check(drawn > 0.05 * image.shape[0] * image.shape[1],
          "Solid Color, Particle Normalized off: the density is drawn (%d pixels off the "
          "background)" % drawn)
    mean = drawn_mean(image, (0.25, 1.0, 0.0, 1.0))
    background = np.array(view.Background) * 255
    check(mean.min() > background.max() + 40,
          "the density is drawn in Solid Color's white, brighter than the background (mean "
          "drawn color %s)" % np.round(mean).tolist())
    rep.DiffuseColor = [1.0, 0.5, 0.0]
    render()
    yield 0.5
    s = state(rep)
    check(s["NumberOfFramesAccumulated"] == s["FrameLimit"],
          "a new Solid Color re-blends the kept samples (%d of %d frames)" %
          (s["NumberOfFramesAccumulated"], s["FrameLimit"]))
    image = T.capture(view)
    mean = drawn_mean(image, (0.25, 1.0, 0.0, 1.0))
    check(mean[0] > mean[1] + 40 and mean[1] > mean[2] + 20,
          "the density follows Solid Color's color (orange: mean drawn color %s)" %
          np.round(mean).tolist())
    before = image
    rep.ParticleNormalized = 1
    render()
    yield from refined_by_itself(rep, "the cloud's density with Particle Normalized on")
    image = T.capture(view)
    worst, mean = T.difference(image, before)
    check(mean < 0.5, "Solid Color, Particle Normalized on: the same density is drawn (mean %.2f "
          "levels, max %d from it off; nothing was drawn before)" % (mean, worst))


SCENES = {"peeling": scene_peeling, "annotations": scene_annotations, "idle": scene_idle,
          "autoarray": scene_autoarray, "amrfirst": scene_amrfirst, "drag": scene_drag, "responsive": scene_responsive, "server": scene_server,
          "density": scene_density,
          "timings": scene_timings}
if SCENE not in SCENES:
    print("savr_gui_scenes: unknown scene %s (one of %s)" % (SCENE, ", ".join(SCENES)), flush=True)
    os._exit(2)
steps = SCENES[SCENE]()
timing = {"next": time.time(), "busy": False, "start": time.time()}


def tick(caller, event):
    # Re-entered while a step renders (the GUI processes events during renders): skip.
    if timing["busy"] or time.time() < timing["next"]:
        return
    if time.time() - timing["start"] > 240.0:
        print("savr_gui_scenes: FAILED: %s did not finish within 240 s" % SCENE, flush=True)
        os._exit(1)
    timing["busy"] = True
    try:
        delay = next(steps)
    except StopIteration:
        print("savr_gui_scenes: %s: %s" % (SCENE, "FAILED" if failed else "all passed"),
              flush=True)
        os._exit(1 if failed else 0)
    except Exception as error:  # a broken step ends the run instead of leaving the GUI open
        import traceback
        traceback.print_exc()
        print("savr_gui_scenes: FAILED: %s raised %s" % (SCENE, error), flush=True)
        os._exit(1)
    finally:
        timing["busy"] = False
    timing["next"] = time.time() + delay


interactor.AddObserver("TimerEvent", tick)
interactor.CreateRepeatingTimer(50)
