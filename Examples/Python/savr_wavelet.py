#!/usr/bin/env python3
"""vtkSAVR from Python: the wavelet refining progressively.

    PYTHONPATH=build/python python3 Examples/Python/savr_wavelet.py [--headless out.png]

Interactive: drag to rotate; frames are single passes while you drag and accumulate when you
let go. With --headless, renders offscreen until refinement completes, prints each frame and
writes the PNG.
"""

import sys

import vtkmodules.vtkInteractionStyle  # noqa: F401 (default interactor style)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (OpenGL rendering)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401 (the image display helper)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkRenderWindowInteractor, vtkVolume, vtkVolumeProperty,
                                         vtkWindowToImageFilter)

import vtksavr


def build_scene(size=400):
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-20, 20, -20, 20, -20, 20)

    color = vtkColorTransferFunction()
    color.AddRGBPoint(37.0, 0.2, 0.2, 0.9)
    color.AddRGBPoint(150.0, 0.9, 0.9, 0.3)
    color.AddRGBPoint(276.0, 0.9, 0.2, 0.1)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(37.0, 0.0)
    opacity.AddPoint(120.0, 0.02)
    opacity.AddPoint(200.0, 0.3)
    opacity.AddPoint(276.0, 0.8)
    prop = vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()

    mapper = vtksavr.vtkSAVRVolumeMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtkRenderer()
    renderer.SetBackground(0.1, 0.1, 0.15)
    renderer.AddVolume(volume)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Azimuth(30.0)
    renderer.GetActiveCamera().Elevation(20.0)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.SetSize(size, size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    return window, renderer, mapper


def refine(window, mapper, report=print):
    """Renders until refinement completes; returns the number of renders."""
    renders = 0
    while True:
        window.Render()
        renders += 1
        report("frame %d: %d accumulated, %.1f ms, error estimate %.2e" %
               (renders, mapper.GetNumberOfFramesAccumulated(), 1e3 * mapper.GetLastFrameTime(),
                mapper.GetErrorEstimate()))
        if mapper.GetRefinementComplete() or renders > 10000:
            return renders


def save(window, path):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ShouldRerenderOff()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def main(argv):
    window, renderer, mapper = build_scene()
    if len(argv) > 2 and argv[1] == "--headless":
        window.SetOffScreenRendering(1)
        refine(window, mapper)
        save(window, argv[2])
        print("wrote", argv[2])
        return 0
    interactor = vtkRenderWindowInteractor()
    interactor.SetRenderWindow(window)
    window.Render()
    driver = vtksavr.vtkSAVRRefinementDriver()
    driver.SetMapper(mapper)
    driver.SetInteractor(interactor)
    interactor.Start()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
