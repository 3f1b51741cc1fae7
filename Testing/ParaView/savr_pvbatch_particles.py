"""The point-cloud scene of savr_pvbatch.py (see there): a vtkPolyData of particles shown as
"SAVR Volume", against its baseline and plain VTK's vtkSAVRVolumeMapper on the same points, and
the same points as an unstructured grid without cells."""
import os

import savr_paraview_testing as T
from paraview import simple as pvs

# SAVR Volume of the particles vs plain VTK's mapper on the same points and settings.
PARTICLES_MAX_LEVEL = 3
PARTICLES_MAX_MEAN = 0.05


def plain_vtk_particles(cloud, camera, vtksavr):
    """The refined image of `cloud` drawn by the vtkSAVRVolumeMapper of the module wrapped for
    ParaView's Python, in a plain VTK window of the view's size, camera and background, with the
    scene's kernel, radii and transfer functions set here from the same numbers."""
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer,
        vtkRenderWindow, vtkVolume, vtkVolumeProperty)
    mapper = vtksavr.vtkSAVRVolumeMapper()
    mapper.SetInputData(cloud)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectScalarArray("value")
    mapper.SetParticleRadiusArrayName("radius")
    mapper.SetParticleKernel(1)  # vtkSAVRParticleSampler::SPH_CUBIC
    mapper.SetParticleNormalized(True)
    colors = vtkColorTransferFunction()
    colors.SetColorSpaceToRGB()
    for i in range(0, len(T.PARTICLE_LUT), 4):
        colors.AddRGBPoint(*T.PARTICLE_LUT[i:i + 4])
    opacity = vtkPiecewiseFunction()
    for i in range(0, len(T.PARTICLE_OPACITY), 4):
        opacity.AddPoint(*T.PARTICLE_OPACITY[i:i + 4])
    prop = vtkVolumeProperty()
    prop.SetColor(colors)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(T.PARTICLE_UNIT_DISTANCE)
    prop.SetInterpolationTypeToLinear()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.SetBackground(T.BACKGROUND)
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*T.VIEW_SIZE)
    window.AddRenderer(renderer)
    vtk_camera = renderer.GetActiveCamera()
    vtk_camera.SetPosition(camera["position"])
    vtk_camera.SetFocalPoint(camera["focal"])
    vtk_camera.SetViewUp(camera["up"])
    vtk_camera.SetViewAngle(30.0)
    renderer.ResetCameraClippingRange()
    renders = 0
    while not mapper.GetRefinementComplete() and renders < 64:
        window.Render()
        renders += 1
    return T.capture_window(window), renders


def check_particles(view, args, failures, vtksavr, defaults):
    """A point cloud (a vtkPolyData of 2744 points made by a Programmable Source, with a value
    and a radius per point) offers "SAVR Volume"; shown so with the SPH cubic kernel, the radius
    array and normalization, the points reach vtkSAVRVolumeMapper with those settings, the image
    refines in 4 renders, matches its baseline and equals (within PARTICLES_MAX_MEAN) the same
    points drawn by plain VTK's vtkSAVRVolumeMapper (the module wrapped for ParaView's Python)
    with the same settings set there; the SAVR settings have `defaults`. A view of its own."""
    view = T.make_view()
    source, rep, camera = T.particles_scene(view, representation="Points")
    failures.check("SAVR Volume" in rep.GetProperty("Representation").Available,
        "'SAVR Volume' is offered for a point cloud (%s: %s)" % (
            rep.GetXMLName(), rep.GetProperty("Representation").Available))
    rep.Representation = "SAVR Volume"
    T.prepare(rep)
    for name, value in defaults.items():
        failures.check(rep.GetPropertyValue(name) == value,
            "particles: default %s = %r (is %r)" % (name, value, rep.GetPropertyValue(name)))
    failures.check(rep.ParticleRadius == 0.0 and rep.ParticleRadiusArray == "None" and
        rep.ParticleKernel == "Gaussian" and rep.ParticleNormalized == 1,
        "particles: default radius 0, radius array None, Gaussian kernel, normalized (%r, %r, %r, %r)"
        % (rep.ParticleRadius, rep.ParticleRadiusArray, rep.ParticleKernel, rep.ParticleNormalized))
    domain = rep.GetProperty("ParticleRadiusArray").Available
    failures.check("None" in domain and "radius" in domain and "value" in domain,
        "particles: the radius array is picked among the point arrays, or None (%s)" % domain)
    rep.ParticleRadiusArray = "radius"
    rep.ParticleKernel = "SPH Cubic"
    T.start_view(view, rep, camera)
    first, final, frames = T.refine(view, rep)
    T.print_frames("Particles", frames)
    last = frames[-1]
    failures.check(frames[0]["NumberOfFramesAccumulated"] == 1 and last["RefinementComplete"] == 1
        and last["NumberOfFramesAccumulated"] == last["FrameLimit"] == len(frames) == 4,
        "particles: one frame per render, complete after 4 renders (%d renders, %d/%d frames)" % (
            len(frames), last["NumberOfFramesAccumulated"], last["FrameLimit"]))
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    failures.check(len(volumes) == 1,
        "particles: one visible volume in the view is drawn by vtkSAVRVolumeMapper (%d)" % len(volumes))
    if volumes:
        mapper = volumes[0].GetMapper()
        data = mapper.GetInputDataObject(0, 0)
        points = data.GetNumberOfPoints() if data is not None else 0
        failures.check(data is not None and data.GetClassName() == "vtkPolyData" and
            points == 14 ** 3 and mapper.GetArrayName() == "value" and
            mapper.GetParticleRadiusArrayName() == "radius" and mapper.GetParticleKernel() == 1 and
            mapper.GetParticleNormalized() and mapper.GetParticleRadius() == 0.0,
            "particles: the mapper draws the %d points of a %s, array %r, radii %r, kernel %d, "
            "normalized %d" % (points, data.GetClassName() if data is not None else None,
                mapper.GetArrayName(), mapper.GetParticleRadiusArrayName(),
                mapper.GetParticleKernel(), mapper.GetParticleNormalized()))
    T.is_drawn(final, failures, "Particles")
    worst, mean = T.difference(first, final)
    failures.check(worst >= 5 and mean > 0.05,
        "particles: refinement changed the image (first frame vs final: max %d levels, mean %.3f)" % (
            worst, mean))
    T.compare_baseline(final, "ParaViewParticles", args.baselines, args.output, failures)
    cloud = pvs.servermanager.Fetch(source)
    expected, renders = plain_vtk_particles(cloud, camera, vtksavr)
    T.write_png(expected, os.path.join(args.output, "ParaViewParticlesPlainVTK.png"))
    worst, mean = T.difference(final, expected)
    failures.check(renders == 4 and worst <= PARTICLES_MAX_LEVEL and mean <= PARTICLES_MAX_MEAN,
        "particles: SAVR Volume vs plain VTK's vtkSAVRVolumeMapper on the same points (%d renders): "
        "max %d levels (at most %d), mean %.4f (at most %g)" % (
            renders, worst, PARTICLES_MAX_LEVEL, mean, PARTICLES_MAX_MEAN))
    # Shading (the coefficients are the surface's Lighting ones, shared) and the blend mode reach
    # the volume; a maximum intensity projection of the particles is drawn.
    rep.Shade = 1
    rep.Specular = 0.3
    rep.BlendMode = "Maximum Intensity"
    pvs.Render(view)
    volumes = T.find_volumes(view, "vtkSAVRVolumeMapper")
    if volumes:
        prop = volumes[0].GetProperty()
        failures.check(prop.GetShade() == 1 and prop.GetSpecular() == 0.3 and
            volumes[0].GetMapper().GetBlendMode() == 1,
            "particles: Shade, Specular and BlendMode reach the volume (%d, %g, %d)" % (
                prop.GetShade(), prop.GetSpecular(), volumes[0].GetMapper().GetBlendMode()))
    T.is_drawn(T.capture(view), failures, "particles, maximum intensity")
    rep.Shade = 0
    rep.Specular = 0.0
    rep.BlendMode = "Composite"
    if volumes:
        T.check_placement(view, rep, volumes[0], "particles", failures)
    # Another kernel starts over and changes the image.
    rep.ParticleKernel = "Gaussian"
    pvs.Render(view)
    failures.check(T.state(rep)["NumberOfFramesAccumulated"] == 1 and
        T.difference(T.capture(view), final)[1] > 0.05,
        "particles: a kernel change starts over with another image")
    check_vertex_grid(view, source, camera, final, failures)
    pvs.Delete(rep)
    pvs.Delete(source)
    pvs.Delete(view)


def check_vertex_grid(view, source, camera, expected, failures):
    """The same points as an unstructured grid without cells (Append Datasets) shown as "SAVR
    Volume" of unstructured grids, with the same particle settings there: drawn as particles, to
    the polydata's image."""
    pvs.Hide(source, view)
    grid = pvs.AppendDatasets(Input=source)
    rep = pvs.Show(grid, view)
    rep.Representation = "SAVR Volume"
    T.prepare(rep)
    T.color_particles(rep)
    rep.ParticleRadiusArray = "radius"
    rep.ParticleKernel = "SPH Cubic"
    T.start_view(view, rep, camera)
    _, final, frames = T.refine(view, rep)
    worst, mean = T.difference(final, expected)
    failures.check(rep.GetXMLName() == "UnstructuredGridRepresentation" and
        frames[-1]["RefinementComplete"] == 1 and worst <= PARTICLES_MAX_LEVEL and
        mean <= PARTICLES_MAX_MEAN,
        "particles as an unstructured grid without cells (%s, %d renders) vs the polydata: max %d "
        "levels, mean %.4f" % (rep.GetXMLName(), len(frames), worst, mean))
    pvs.Delete(rep)
    pvs.Delete(grid)
    pvs.Show(source, view)
