// Private to the module: what the renderer is doing when the mapper renders, as far as the
// mapper needs to know it: whether its depth buffer may hold geometry, and which stage of VTK's
// dual depth peeling calls the volume's Render.
#ifndef vtkSAVRRenderState_h
#define vtkSAVRRenderState_h

class vtkAbstractVolumeMapper;
class vtkRenderer;
class vtkVolume;

namespace vtkSAVRRenderState
{
/// Whether the renderer's depth buffer may hold anything but its clear value when its volumes
/// render: opaque geometry of its own props, a depth buffer kept from an earlier renderer, or a
/// render pass (ParaView's among them) that may fill it its own way. When not, there is no need
/// to read it back.
bool DepthMayHoldGeometry(vtkRenderer* ren);

enum class PeelingCall
{
  None,  // not inside dual depth peeling's volume stages
  First, // its first volume stage, before the peels
  Later  // a peel or the final blend
};

/// Which of VTK's dual depth peeling stages calls `mapper`'s Render for `volume`.
PeelingCall DualPeelingCall(vtkAbstractVolumeMapper* mapper, vtkVolume* volume);
}

#endif
