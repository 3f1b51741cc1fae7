// Private to the module: what the renderer is doing when the mapper renders, as far as the
// mapper needs to know it: whether its depth buffer may hold geometry.
#ifndef vtkSAVRRenderState_h
#define vtkSAVRRenderState_h

class vtkRenderer;

namespace vtkSAVRRenderState
{
/// Whether the renderer's depth buffer may hold anything but its clear value when its volumes
/// render: opaque geometry of its own props, a depth buffer kept from an earlier renderer, or a
/// render pass (ParaView's among them) that may fill it its own way. When not, there is no need
/// to read it back.
bool DepthMayHoldGeometry(vtkRenderer* ren);
}

#endif
