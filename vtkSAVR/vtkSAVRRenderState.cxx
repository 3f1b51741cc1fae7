#include "vtkSAVRRenderState.h"

#include "vtkCollection.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkVolume.h"

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

} // namespace vtkSAVRRenderState
