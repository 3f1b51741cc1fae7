#include "vtkSAVRConversions.h"

#include "vtkColorTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkType.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <limits>

namespace vtkSAVRConversions
{
bool ToScalarType(int vtkType, savr::ScalarType& type)
{
  switch (vtkType)
  {
    case VTK_CHAR: // plain char is unsigned on some platforms (ARM, PowerPC)
      type =
        std::numeric_limits<char>::is_signed ? savr::ScalarType::Int8 : savr::ScalarType::UInt8;
      return true;
    case VTK_SIGNED_CHAR:
      type = savr::ScalarType::Int8;
      return true;
    case VTK_UNSIGNED_CHAR:
      type = savr::ScalarType::UInt8;
      return true;
    case VTK_SHORT:
      type = savr::ScalarType::Int16;
      return true;
    case VTK_UNSIGNED_SHORT:
      type = savr::ScalarType::UInt16;
      return true;
    case VTK_INT:
      type = savr::ScalarType::Int32;
      return true;
    case VTK_UNSIGNED_INT:
      type = savr::ScalarType::UInt32;
      return true;
    case VTK_ID_TYPE: // 32 bits when VTK is built without VTK_USE_64BIT_IDS
      type = sizeof(vtkIdType) == 8 ? savr::ScalarType::Int64 : savr::ScalarType::Int32;
      return true;
    case VTK_LONG:
    case VTK_LONG_LONG:
      type = sizeof(long) == 8 || vtkType != VTK_LONG ? savr::ScalarType::Int64
                                                      : savr::ScalarType::Int32;
      return true;
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG:
      type = sizeof(unsigned long) == 8 || vtkType != VTK_UNSIGNED_LONG ? savr::ScalarType::UInt64
                                                                        : savr::ScalarType::UInt32;
      return true;
    case VTK_FLOAT:
      type = savr::ScalarType::Float32;
      return true;
    case VTK_DOUBLE:
      type = savr::ScalarType::Float64;
      return true;
    default:
      return false;
  }
}

bool ToBlendMode(int vtkMode, savr::BlendMode& mode)
{
  switch (vtkMode)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      mode = savr::BlendMode::Composite;
      return true;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      mode = savr::BlendMode::Maximum;
      return true;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      mode = savr::BlendMode::Minimum;
      return true;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      mode = savr::BlendMode::Average;
      return true;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      mode = savr::BlendMode::Additive;
      return true;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      mode = savr::BlendMode::Isosurface;
      return true;
    case vtkVolumeMapper::SLICE_BLEND:
      mode = savr::BlendMode::Slice;
      return true;
    default:
      return false;
  }
}

bool ToPlanes(vtkPlaneCollection* planes, std::vector<Eigen::Vector4d>& out)
{
  if (!planes)
  {
    return true;
  }
  const auto finite = [](const double* v)
  { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
  planes->InitTraversal();
  while (vtkPlane* plane = planes->GetNextItem())
  {
    const double* n = plane->GetNormal();
    const double* o = plane->GetOrigin();
    if (!finite(n) || !finite(o))
    {
      return false;
    }
    out.emplace_back(n[0], n[1], n[2], -(n[0] * o[0] + n[1] * o[1] + n[2] * o[2]));
  }
  return true;
}

Eigen::Matrix4d ToEigen(vtkMatrix4x4* matrix)
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 4 && matrix; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m(r, c) = matrix->GetElement(r, c);
    }
  }
  return m;
}
} // namespace vtkSAVRConversions

vtkObject* vtkSAVRConversions::ColorFunction(vtkVolumeProperty* property, int c)
{
  return property->GetColorChannels(c) == 1
           ? static_cast<vtkObject*>(property->GetGrayTransferFunction(c))
           : static_cast<vtkObject*>(property->GetRGBTransferFunction(c));
}
