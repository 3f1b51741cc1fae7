#include "vtkSAVRRenderState.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkCollection.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
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
    const bool savrVolume =
      volume && volume->GetMapper() && volume->GetMapper()->IsA("vtkSAVRVolumeMapper");
    if (prop->GetVisibility() && !savrVolume)
    {
      return true;
    }
  }
  return false;
}

} // namespace vtkSAVRRenderState
