"""Writes two small scenes as files VTK reads, for the convergence report and the examples:

  tets.vtu     the wavelet on 24^3 points cut into tetrahedra (vtkDataSetTriangleFilter)
  pulse.vthb   VTK's Gaussian pulse as a two-level vtkOverlappingAMR hierarchy

Usage: python3 Utilities/write_scenes.py OUTPUT_FOLDER  (Debian's python3 with python3-vtk9)
"""
import os
import sys

from vtkmodules.vtkFiltersAMR import vtkAMRGaussianPulseSource
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOXML import vtkXMLUniformGridAMRWriter, vtkXMLUnstructuredGridWriter


def main(folder):
    os.makedirs(folder, exist_ok=True)

    wavelet = vtkRTAnalyticSource()
    wavelet.SetWholeExtent(-12, 11, -12, 11, -12, 11)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputConnection(wavelet.GetOutputPort())
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetInputConnection(tets.GetOutputPort())
    writer.SetFileName(os.path.join(folder, "tets.vtu"))
    if not writer.Write():
        return 1

    pulse = vtkAMRGaussianPulseSource()
    pulse.SetDimension(3)
    pulse.SetNumberOfLevels(2)
    pulse.SetRootSpacing(0.5)
    pulse.SetPulseOrigin(-0.4, -0.5, 1.2)
    pulse.SetPulseWidth(0.8, 0.8, 0.8)
    pulse.SetPulseAmplitude(1.0)
    amr_writer = vtkXMLUniformGridAMRWriter()
    amr_writer.SetInputConnection(pulse.GetOutputPort())
    amr_writer.SetFileName(os.path.join(folder, "pulse.vthb"))
    if not amr_writer.Write():
        return 1
    print("wrote", os.path.join(folder, "tets.vtu"), "and", os.path.join(folder, "pulse.vthb"))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
