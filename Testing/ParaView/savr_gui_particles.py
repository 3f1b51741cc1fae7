"""Scene of the ParaView GUI's Properties panel test for point clouds (savr_gui_particles.xml):
the particle cloud of the pvbatch test (a vtkPolyData of points with a value and a radius array)
shown as "SAVR Volume", colored by its value, the active source of the panel. Run as
savr_gui_panel.py is (see there), with --test-script=Testing/ParaView/savr_gui_particles.xml,
from the repository's root.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.getcwd(), "Testing", "ParaView"))
import savr_paraview_testing as T  # noqa: E402

T.RENDER_TIME_BOUND = None  # the GUI keeps the default bound of a render's time
from paraview import simple as pvs  # noqa: E402

plugin = os.environ.get("SAVR_PLUGIN", T.DEFAULT_PLUGIN)
pvs.LoadPlugin(plugin, remote=False, ns=globals())
view = pvs.GetActiveViewOrCreate("RenderView")
# Active before it runs: the programmable source's script runs in __main__ (this script's
# namespace), whose names its star import of numpy_interface.algorithms replaces.
cloud_proxy = T.particles_source()
pvs.SetActiveSource(cloud_proxy)
representation = pvs.Show(cloud_proxy, view)
representation.Representation = "SAVR Volume"
T.color_particles(representation)
pvs.Render(view)
print("savr_gui_particles: the cloud is shown as SAVR Volume; playing the panel checks", flush=True)
