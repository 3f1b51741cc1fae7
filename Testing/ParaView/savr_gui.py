"""ParaView GUI test of the SAVR plugin: the image refines by itself after interaction stops.

    SAVR_PLUGIN=.../SAVRPlugin.so \\
    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a paraview --script=Testing/ParaView/savr_gui.py

Runs inside the real GUI (its Qt event loop, its Qt interactor). The script shows the wavelet
with "SAVR Volume", lets the GUI settle (its own renders while the window appears), then moves
the camera and renders once (one frame, as the end of a drag does), and from then on only
watches: the representation has attached the refinement driver to the view's Qt interactor,
whose timer renders frame after frame until refinement is complete. The script never calls
Render() again. While the driver refines, the progress of its frames reaches the application:
the plugin opens the session's progress scope around each of the driver's renders, within which
the session's progress handler (whose events ParaView's progress manager passes on to the
progress bar) reports the frames' fractions, increasing up to completion (see check_progress), and the view then shows the refined image
(check_window_image). Then it saves screenshots at twice the view's size as the GUI's Save
Screenshot does (refined ones, and with RefineSavedImages off one frame; see
check_saved_images), into SAVR_OUTPUT (default build-paraview/Testing/Temporary). It exits with
0 once the mapper reports all frames and the screenshots are as expected, with 1 otherwise, or if
refinement has not completed 20 s after the camera change (or the view has no Qt interactor).
"""
import os
import sys
import time

from paraview import simple as pvs

# The tests' shared pieces (PNG reading, image differences); the GUI runs from the repository.
sys.path.insert(0, os.path.join("Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402

plugin = os.environ.get("SAVR_PLUGIN",
    "build-paraview/lib/paraview-5.11/plugins/SAVRPlugin/SAVRPlugin.so")
pvs.LoadPlugin(plugin, remote=False, ns=globals())
view = pvs.GetActiveViewOrCreate("RenderView")
source = pvs.Wavelet()
rep = pvs.Show(source, view)
rep.Representation = "SAVR Volume"
pvs.ColorBy(rep, ("POINTS", "RTData"))
pvs.Render(view)


# What the GUI's progress bar is told: pqProgressManager shows the bar on the handler's StartEvent,
# sets it on each of its ProgressEvents (LastProgress, in percent) and hides it on EndEvent. Every
# frame is reported (the handler otherwise drops events closer than 0.1 s: the driver's frames
# are, and whether the one that completes refinement is shown would be a matter of timing).
handler = pvs.servermanager.ActiveConnection.Session.GetProgressHandler()
handler.SetProgressInterval(0.01)
progress_log = []


def log_progress(caller, event):
    if phase["moved"] is not None:
        progress_log.append((event, handler.GetLastProgress() if event == "ProgressEvent" else None,
                             handler.GetLastProgressText() if event == "ProgressEvent" else None))


for name in ("StartEvent", "ProgressEvent", "EndEvent"):
    handler.AddObserver(name, log_progress)


def state():
    rep.SMProxy.UpdatePropertyInformation()
    return {name: rep.GetProperty(name).GetData()
            for name in ("NumberOfFramesAccumulated", "FrameLimit", "RefinementComplete")}


interactor = view.GetInteractor()
kind = interactor.GetClassName() if interactor else None
if kind != "QVTKInteractor":
    print("savr_gui: FAILED: the view has no Qt interactor (%s)" % kind, flush=True)
    os._exit(1)
start = time.time()
phase = {"moved": None}


def watch(caller, event):
    now = time.time()
    if phase["moved"] is None:
        # Let the GUI settle first (its own renders while the window appears), then move the
        # camera and render once, as the end of a drag does: one frame.
        if now - start < 3.0:
            return
        view.CameraPosition = [40, 30, 50]
        pvs.Render(view)
        s = state()
        print("savr_gui: after the camera change: %d of %d frames" % (
            s["NumberOfFramesAccumulated"], s["FrameLimit"]), flush=True)
        if s["NumberOfFramesAccumulated"] != 1:
            print("savr_gui: FAILED: expected one frame", flush=True)
            os._exit(1)
        phase["moved"] = now
        return
    s = state()
    if s["RefinementComplete"] and s["NumberOfFramesAccumulated"] == s["FrameLimit"] > 1:
        print("savr_gui: ok: the image refined by itself to %d of %d frames in %.2f s, with no "
              "Render() call" % (s["NumberOfFramesAccumulated"], s["FrameLimit"],
                                 now - phase["moved"]), flush=True)
        ok = check_progress(s["FrameLimit"]) & check_window_image()
        os._exit(0 if check_saved_images(s["FrameLimit"]) and ok else 1)  # else the GUI runs on
    if now - phase["moved"] > 20.0:
        print("savr_gui: FAILED: %d of %d frames 20 s after the camera change" % (
            s["NumberOfFramesAccumulated"], s["FrameLimit"]), flush=True)
        os._exit(1)


def check_progress(frames):
    """The driver's frames 2 to K (of K) reached the progress handler after the camera change,
    with no Render() call: each inside a scope opened and closed around it (StartEvent, then
    EndEvent), in percent k * 100 / K, increasing, the last 100."""
    values = [value for event, value, _ in progress_log if event == "ProgressEvent"]
    depth, nested = 0, True
    for event, _, _ in progress_log:
        depth += {"StartEvent": 1, "EndEvent": -1}.get(event, 0)
        nested = nested and (depth in (0, 1)) and (event != "ProgressEvent" or depth == 1)
    expected = [k * 100 // frames for k in range(2, frames + 1)]
    scopes = sum(1 for event, _, _ in progress_log if event == "StartEvent")
    ok = values == expected and nested and depth == 0 and scopes >= frames - 1
    texts = sorted(set(text for event, _, text in progress_log if event == "ProgressEvent"))
    print("savr_gui: %s: the refinement driver's frames reach the GUI's progress: %s percent "
          "(expected %s) from %s, in %d scopes%s" % (
              "ok" if ok else "FAILED", values, expected, texts or "nothing", scopes,
              "" if nested and depth == 0 else ", not each within an open scope"), flush=True)
    return ok


def check_window_image():
    """The image the driver's last frame left in the view (read back without rendering) is the
    refined one, as a screenshot at the view's size refines it: the GUI's answers to progress
    (the progress bar repainted before and during the driver's renders) do not spoil it."""
    shown = T.capture(view)
    path = os.path.join(os.environ.get("SAVR_OUTPUT", "build-paraview/Testing/Temporary"),
                        "GUIRefinedInView.png")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    pvs.SaveScreenshot(path, view, ImageResolution=list(shown.shape[1::-1]))
    saved = T.read_png(path)
    worst, mean = T.difference(shown, saved) if shown.shape == saved.shape else (-1, -1.0)
    ok = 0 <= worst <= 16 and mean <= 0.08
    print("savr_gui: %s: the view shows the refined image (%dx%d): against a screenshot, max %d "
          "levels (at most 16), mean %.3f (at most 0.08)" % (
              "ok" if ok else "FAILED", shown.shape[1], shown.shape[0], worst, mean), flush=True)
    return ok


def check_saved_images(frames):
    """Screenshots saved from the GUI at twice the view's size are refined at that size:
    RefineSavedImages (on) refines the capture to the frame limit K, whose image equals one frame
    at SampleDistance / K (the mapper takes the same samples); with RefineSavedImages off the
    capture is one frame at the base step, which differs from both."""
    output = os.environ.get("SAVR_OUTPUT", "build-paraview/Testing/Temporary")
    os.makedirs(output, exist_ok=True)
    size = view.ViewSize
    big = [2 * size[0], 2 * size[1]]
    step = rep.SampleDistance if rep.SampleDistance > 0 else 1.0  # the wavelet's spacing

    def shot(name):
        path = os.path.join(output, name)
        pvs.SaveScreenshot(path, view, ImageResolution=big)
        return T.read_png(path)

    refined = shot("GUISaved2x.png")
    rep.RefineSavedImages = 0
    one_frame = shot("GUISaved2xOneFrame.png")
    rep.SampleDistance = step / frames
    rep.MaximumNumberOfFrames = 1
    fine_pass = shot("GUISaved2xFinePass.png")
    ok = refined.shape == fine_pass.shape == one_frame.shape and refined.shape[1] == big[0]
    worst, mean = T.difference(refined, fine_pass) if ok else (-1, -1.0)
    ok_refined = ok and worst <= 16 and mean <= 0.08
    print("savr_gui: %s: the screenshot at %dx%d is the refined image: against one frame at "
          "SampleDistance / %d, max %d levels (at most 16), mean %.3f (at most 0.08)" % (
              "ok" if ok_refined else "FAILED", big[0], big[1], frames, worst, mean), flush=True)
    # One frame differs everywhere a little (measured: mean 0.16 to 0.21 levels); the refined
    # screenshot equals the fine pass exactly.
    one_mean = T.difference(one_frame, fine_pass)[1] if ok else -1.0
    ok_one = ok and one_mean > 0.05
    print("savr_gui: %s: with RefineSavedImages off the screenshot is one frame: mean %.3f "
          "levels from the refined one (more than 0.05)" % ("ok" if ok_one else "FAILED", one_mean),
          flush=True)
    return ok_refined and ok_one


# Watch on every timer event of the interactor (the driver's included), and on a timer of our
# own (which renders nothing) so that the phases and the deadline run on their own.
interactor.AddObserver("TimerEvent", watch)
interactor.CreateRepeatingTimer(250)
