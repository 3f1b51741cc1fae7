#include "vtkSAVRRenderState.h"

#include "vtkCollection.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkVolume.h"

#include <string>

namespace vtkSAVRRenderState
{

bool DepthMayHoldGeometry(vtkRenderer* ren)
{
  if (ren->GetPass() || ren->GetPreserveDepthBuffer() || !ren->GetErase() ||
      !ren->GetRenderWindow()->GetErase())
  {
    return true;
  }
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    // Volumes drawn by this mapper test against depth but do not write it; of others (a GPU
    // mapper, say) this is not known.
    vtkVolume* volume = vtkVolume::SafeDownCast(prop);
    const bool savrVolume = volume && vtkSAVRVolumeMapper::SafeDownCast(volume->GetMapper());
    if (prop->GetVisibility() && !savrVolume)
    {
      return true;
    }
  }
  return false;
}


// Which of VTK's dual depth peeling stages calls Render, from the pass among the volume's
// render-pass keys: it declares the textures of the stage it is in when asked to fill in a
// shader, the previous front layer's only while peeling and a depth range only at the end.
PeelingCall DualPeelingCall(vtkAbstractVolumeMapper* mapper, vtkVolume* volume)
{
  vtkInformation* keys = volume->GetPropertyKeys();
  if (!keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    return PeelingCall::None;
  }
  for (int i = 0; i < keys->Length(vtkOpenGLRenderPass::RenderPasses()); ++i)
  {
    auto* pass =
      vtkDualDepthPeelingPass::SafeDownCast(keys->Get(vtkOpenGLRenderPass::RenderPasses(), i));
    if (!pass)
    {
      continue;
    }
    std::string vertex;
    std::string geometry;
    std::string fragment = "//VTK::DepthPeeling::Dec\n";
    pass->PreReplaceShaderValues(vertex, geometry, fragment, mapper, volume);
    if (fragment.find("lastFrontColorTex") != std::string::npos ||
        fragment.find("depthRangeTex") != std::string::npos)
    {
      return PeelingCall::Later;
    }
    // Not a volume stage (or one this does not know): drawn as usual.
    return fragment.find("innerDepthTex") != std::string::npos ? PeelingCall::First
                                                                : PeelingCall::None;
  }
  return PeelingCall::None;
}

} // namespace vtkSAVRRenderState
