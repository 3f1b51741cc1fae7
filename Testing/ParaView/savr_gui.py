"""ParaView GUI test of the SAVR plugin: the image refines by itself after interaction stops.

    SAVR_PLUGIN=.../SAVRPlugin.so \\
    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a paraview --script=Testing/ParaView/savr_gui.py

Runs inside the real GUI (its Qt event loop, its Qt interactor). The script shows the wavelet
with "SAVR Volume", lets the GUI settle (its own renders while the window appears), then moves
the camera and renders once (one frame, as the end of a drag does), and from then on only
watches: the representation has attached the refinement driver to the view's Qt interactor,
whose timer renders frame after frame until refinement is complete. The script never calls
Render() again. It exits with 0 once the mapper reports all frames, with 1 if that has not
happened 20 s after the camera change (or the view has no Qt interactor).
"""
import os
import time

from paraview import simple as pvs

plugin = os.environ.get("SAVR_PLUGIN",
    "build-paraview/lib/paraview-5.11/plugins/SAVRPlugin/SAVRPlugin.so")
pvs.LoadPlugin(plugin, remote=False, ns=globals())
view = pvs.GetActiveViewOrCreate("RenderView")
source = pvs.Wavelet()
rep = pvs.Show(source, view)
rep.Representation = "SAVR Volume"
pvs.ColorBy(rep, ("POINTS", "RTData"))
pvs.Render(view)


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
        os._exit(0)  # the GUI would otherwise run on
    if now - phase["moved"] > 20.0:
        print("savr_gui: FAILED: %d of %d frames 20 s after the camera change" % (
            s["NumberOfFramesAccumulated"], s["FrameLimit"]), flush=True)
        os._exit(1)


# Watch on every timer event of the interactor (the driver's included), and on a timer of our
# own (which renders nothing) so that the phases and the deadline run on their own.
interactor.AddObserver("TimerEvent", watch)
interactor.CreateRepeatingTimer(250)
