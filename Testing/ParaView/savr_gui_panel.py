"""Scene of the ParaView GUI's Properties panel test (savr_gui_panel.xml): the wavelet shown as
"SAVR Volume", colored by RTData, the active source of the panel.

    SAVR_PLUGIN=.../SAVRPlugin.so DASHBOARD_TEST_FROM_CTEST=1 \\
    PYTHONPATH=build-paraview/python3-paraview/usr/lib/python3/dist-packages \\
      xvfb-run -a paraview --dr --script=Testing/ParaView/savr_gui_panel.py \\
        --test-script=Testing/ParaView/savr_gui_panel.xml --exit

`paraview` runs this script first, then plays the checks of savr_gui_panel.xml against its own
widgets (Qt's QtTesting playback: each <pqcheck> compares a property of a named widget, here
whether the panel shows it and what a read-only field reads) and, with --exit, quits with 1 at
the first failed check, 0 when all pass. --dr leaves the user's settings out (and with them the
welcome dialog); DASHBOARD_TEST_FROM_CTEST answers ParaView's "Are you sure?" prompt when the
checks switch the representation to the stock "Volume", as in ParaView's own GUI tests.
"""
import os
import sys

from paraview import simple as pvs

# The tests' shared pieces (where the plugin is built); the GUI runs from the repository.
sys.path.insert(0, os.path.join("Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402

plugin = os.environ.get("SAVR_PLUGIN", T.DEFAULT_PLUGIN)
pvs.LoadPlugin(plugin, remote=False, ns=globals())
view = pvs.GetActiveViewOrCreate("RenderView")
source = pvs.Wavelet()
rep = pvs.Show(source, view)
rep.Representation = "SAVR Volume"
pvs.ColorBy(rep, ("POINTS", "RTData"))
pvs.SetActiveSource(source)
pvs.Render(view)
# The panel's labels say what 0 means and what unit the budget is in.
labels = {name: rep.GetProperty(name).SMProperty.GetXMLLabel()
          for name in ("SampleDistance", "MaximumNumberOfFrames", "MemoryBudget")}
expected = {"SampleDistance": "Sample Distance (0 = auto)",
            "MaximumNumberOfFrames": "Frames (0 = auto)", "MemoryBudget": "Memory Budget (MiB)"}
if labels != expected:
    print("savr_gui_panel: FAILED: the labels are %s (expected %s)" % (labels, expected), flush=True)
    os._exit(1)
print("savr_gui_panel: the wavelet is shown as SAVR Volume; playing the panel checks", flush=True)
