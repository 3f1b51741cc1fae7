"""vtkSAVR for Python: the progressive CPU volume mapper and its helpers.

    import vtksavr
    mapper = vtksavr.vtkSAVRVolumeMapper()
"""

# The wrapped module needs the VTK modules it derives from to be loaded first.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkRenderingCore  # noqa: F401
import vtkmodules.vtkRenderingVolume  # noqa: F401

from .vtkSAVR import (  # noqa: F401
    vtkSAVRAMRSampler,
    vtkSAVRImageSampler,
    vtkSAVRRefinementDriver,
    vtkSAVRUnstructuredSampler,
    vtkSAVRVolumeMapper,
)
