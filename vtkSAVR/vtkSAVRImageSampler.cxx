#include "vtkSAVRImageSampler.h"

#include "sampler/ComponentSampler.h"
#include "image/GridSampler.h"
#include "vtkSAVRConversions.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkSAVRImageSampler);

namespace
{
// The shortest of the image's three voxel edges once placed in the world by `volumeMatrix`.
double SmallestWorldEdge(vtkImageData* image, vtkMatrix4x4* volumeMatrix)
{
  double smallest = VTK_DOUBLE_MAX;
  const double* spacing = image->GetSpacing();
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  for (int a = 0; a < 3; ++a)
  {
    double edge[4] = { 0, 0, 0, 0 };
    for (int r = 0; r < 3; ++r)
    {
      edge[r] = direction->GetElement(r, a) * spacing[a];
    }
    double world[4];
    for (int r = 0; r < 4; ++r)
    {
      world[r] = volumeMatrix->GetElement(r, 0) * edge[0] +
                 volumeMatrix->GetElement(r, 1) * edge[1] +
                 volumeMatrix->GetElement(r, 2) * edge[2];
    }
    smallest = std::min(
      smallest, std::sqrt(world[0] * world[0] + world[1] * world[1] + world[2] * world[2]));
  }
  return smallest;
}
}

vtkSAVRImageSampler::vtkSAVRImageSampler() = default;
vtkSAVRImageSampler::~vtkSAVRImageSampler() = default;

bool vtkSAVRImageSampler::Build(vtkImageData* image, vtkDataArray* scalars, bool cellData,
  vtkMatrix4x4* volumeMatrix, int interpolationType, bool independentComponents)
{
  this->NumberOfComponents = 0;
  this->SmallestSpacing = 0.0;
  this->Sampler.reset();
  this->ErrorMessage.clear();
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  if (image)
  {
    image->GetExtent(extent);
  }
  // Counted from the extent in long double: vtkImageData's own counts overflow (signed 64 bits)
  // for images of 2^21 points per axis, and would let a short array through.
  long double points = 1.0L;
  long double cells = 1.0L;
  for (int a = 0; a < 3; ++a)
  {
    const long double n = static_cast<long double>(extent[2 * a + 1]) - extent[2 * a] + 1.0L;
    points *= std::max(n, 0.0L);
    cells *= std::max(n - 1.0L, 1.0L);
  }
  if (points == 0.0L)
  {
    this->ErrorMessage = "the input image is empty";
    return false;
  }
  if (!scalars)
  {
    this->ErrorMessage =
      "the input has no scalars to render (check the scalar mode and array name)";
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  if (components < 1 || components > 4)
  {
    std::ostringstream message;
    message << "the scalar array '" << (scalars->GetName() ? scalars->GetName() : "") << "' has "
            << components << " components; one to four components are supported";
    this->ErrorMessage = message.str();
    return false;
  }
  if (!independentComponents && components != 1 && components != 2 && components != 4)
  {
    std::ostringstream message;
    message << "dependent components must be two (luminance and alpha) or four (RGBA); the "
               "scalar array '"
            << (scalars->GetName() ? scalars->GetName() : "") << "' has " << components;
    this->ErrorMessage = message.str();
    return false;
  }
  savr::GridDescription grid;
  if (!vtkSAVRConversions::ToScalarType(scalars->GetDataType(), grid.Type))
  {
    this->ErrorMessage =
      std::string("scalars of type ") + scalars->GetDataTypeAsString() + " are not supported";
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    grid.Dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
  }
  if (static_cast<long double>(scalars->GetNumberOfTuples()) < (cellData ? cells : points))
  {
    std::ostringstream message;
    message << "the scalar array is shorter than the image (" << scalars->GetNumberOfTuples()
            << " tuples for " << static_cast<double>(cellData ? cells : points)
            << (cellData ? " cells)" : " points)");
    this->ErrorMessage = message.str();
    return false;
  }
  const double* spacing = image->GetSpacing();
  if (spacing[0] == 0.0 || spacing[1] == 0.0 || spacing[2] == 0.0 || !std::isfinite(spacing[0]) ||
      !std::isfinite(spacing[1]) || !std::isfinite(spacing[2]))
  {
    this->ErrorMessage = "the image's spacing is zero or not finite";
    return false;
  }

  // Array index -> world: volume matrix x image index-to-physical x shift by the extent's start.
  vtkNew<vtkMatrix4x4> arrayToWorld;
  arrayToWorld->DeepCopy(image->GetIndexToPhysicalMatrix());
  vtkNew<vtkMatrix4x4> shift;
  for (int a = 0; a < 3; ++a)
  {
    shift->SetElement(a, 3, extent[2 * a]);
  }
  vtkMatrix4x4::Multiply4x4(arrayToWorld, shift, arrayToWorld);
  if (volumeMatrix)
  {
    vtkMatrix4x4::Multiply4x4(volumeMatrix, arrayToWorld, arrayToWorld);
  }
  grid.WorldToIndex = Eigen::Affine3d(vtkSAVRConversions::ToEigen(arrayToWorld)).inverse();
  grid.Data = scalars->GetVoidPointer(0);
  grid.Components = components;
  grid.CellData = cellData;
  grid.Interpolation = interpolationType == VTK_NEAREST_INTERPOLATION ? savr::Interpolation::Nearest
                                                                      : savr::Interpolation::Linear;
  std::string error;
  this->Sampler = savr::MakeGridSampler(grid, error);
  if (!this->Sampler)
  {
    this->ErrorMessage = error;
    return false;
  }
  if (components > 1)
  {
    // Component c: the same grid, c elements further.
    std::vector<std::shared_ptr<const savr::Sampler>> parts = { this->Sampler };
    const char* first = static_cast<const char*>(grid.Data);
    for (int c = 1; c < components; ++c)
    {
      grid.Data = first + c * scalars->GetDataTypeSize();
      parts.push_back(savr::MakeGridSampler(grid, error));
      if (!parts.back())
      {
        this->Sampler.reset();
        this->ErrorMessage = error;
        return false;
      }
    }
    // Shading follows the components that set opacity: all of independent ones (VTK's mappers
    // light each by its own gradient; one normal is stored per sample, from the sum of their
    // gradients, which is each one's own at its surfaces), the last of dependent ones.
    this->Sampler = std::make_shared<savr::ComponentSampler>(std::move(parts),
      independentComponents ? savr::ComponentSampler::kAllGradients : components - 1);
  }
  // The sampler reads the array in place: it holds the array as long as anyone holds it.
  struct Holder
  {
    vtkSmartPointer<vtkDataArray> Array;
    std::shared_ptr<const savr::Sampler> Sampler;
  };
  auto holder = std::make_shared<Holder>(Holder{ scalars, std::move(this->Sampler) });
  this->Sampler = std::shared_ptr<const savr::Sampler>(holder, holder->Sampler.get());
  this->NumberOfComponents = components;
  vtkNew<vtkMatrix4x4> identity;
  this->SmallestSpacing = SmallestWorldEdge(image, volumeMatrix ? volumeMatrix : identity.Get());
  return true;
}

void vtkSAVRImageSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sampler: " << (this->Sampler ? "built" : "none") << "\n";
  os << indent << "SmallestSpacing: " << this->SmallestSpacing << "\n";
  os << indent << "ErrorMessage: " << this->ErrorMessage << "\n";
}
