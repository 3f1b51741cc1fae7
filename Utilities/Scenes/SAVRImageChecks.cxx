#include "SAVRImageChecks.h"

#include "vtkDataArray.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sys/stat.h>

namespace savr_scenes
{

vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(grab->GetOutput());
  return copy;
}

unsigned char* Bytes(vtkImageData* image)
{
  return static_cast<unsigned char*>(image->GetPointData()->GetScalars()->GetVoidPointer(0));
}

double CoveredFraction(vtkImageData* image, const double background[3])
{
  const vtkIdType n = image->GetNumberOfPoints();
  const unsigned char* p = Bytes(image);
  vtkIdType covered = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(p[3 * i + c] - background[c] * 255.0) > 8.0)
      {
        ++covered;
        break;
      }
    }
  }
  return n > 0 ? static_cast<double>(covered) / n : 0.0;
}

Difference Compare(vtkImageData* a, vtkImageData* b)
{
  Difference d;
  const vtkIdType n = a->GetNumberOfPoints() * 3;
  if (n != b->GetNumberOfPoints() * 3)
  {
    d.Max = d.Mean = 255.0;
    return d;
  }
  const unsigned char* pa = Bytes(a);
  const unsigned char* pb = Bytes(b);
  double sum = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double e = std::abs(static_cast<int>(pa[i]) - static_cast<int>(pb[i]));
    d.Max = std::max(d.Max, e);
    sum += e;
  }
  d.Mean = n > 0 ? sum / n : 0.0;
  return d;
}

void Expectations::operator()(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++this->Failures;
  }
}

void WritePNG(vtkImageData* image, const std::string& file)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputData(image);
  writer->Write();
}

bool MatchesBaseline(
  vtkRenderWindow* window, int argc, char* argv[], double maxLevels, double meanLevels)
{
  std::string baseline;
  std::string output = ".";
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "-V")
      baseline = argv[i + 1];
    if (std::string(argv[i]) == "-T")
      output = argv[i + 1];
  }
  vtkSmartPointer<vtkImageData> image = Capture(window);
  const std::string name = baseline.substr(baseline.find_last_of('/') + 1);
  const std::string written = output + "/" + (name.empty() ? std::string("image.png") : name);
  struct stat info;
  if (baseline.empty() || stat(baseline.c_str(), &info) != 0)
  {
    WritePNG(image, written);
    std::cerr << "no baseline '" << baseline << "'; wrote " << written << "\n";
    return false;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkImageData* expected = reader->GetOutput();
  if (expected->GetNumberOfScalarComponents() != 3)
  {
    std::cerr << "baseline " << baseline << " is not RGB\n";
    return false;
  }
  const Difference d = Compare(image, expected);
  std::cout << "against baseline: max " << d.Max << " mean " << d.Mean << " levels\n";
  if (d.Max <= maxLevels && d.Mean <= meanLevels)
  {
    return true;
  }
  WritePNG(image, written);
  std::cerr << "differs from the baseline; wrote " << written;
  int size[3];
  image->GetDimensions(size);
  int expectedSize[3];
  expected->GetDimensions(expectedSize);
  if (std::equal(size, size + 3, expectedSize))
  {
    // Every channel's absolute difference, unforgiving: no threshold, no shifted pixels.
    vtkNew<vtkImageDifference> difference;
    difference->SetInputData(image);
    difference->SetImageData(expected);
    difference->SetThreshold(0);
    difference->AllowShiftOff();
    difference->AveragingOff();
    difference->Update();
    const std::string diff = written.substr(0, written.size() - 4) + ".diff.png";
    WritePNG(difference->GetOutput(), diff);
    std::cerr << " and the difference " << diff;
  }
  std::cerr << "\n";
  return false;
}

ImageError ErrorAgainst(
  const std::vector<float>& image, const std::vector<float>& reference, bool alpha)
{
  ImageError e;
  double sum = 0.0;
  std::size_t compared = 0;
  for (std::size_t i = 0; i < image.size() && i < reference.size(); ++i)
  {
    if (alpha || i % 4 != 3)
    {
      const double d = static_cast<double>(image[i]) - reference[i];
      sum += d * d;
      e.Max = std::max(e.Max, std::abs(d));
      ++compared;
    }
  }
  e.Rmse = std::sqrt(sum / std::max<std::size_t>(compared, 1));
  return e;
}

std::vector<float> FloatRGBA(vtkImageData* image)
{
  const vtkIdType n = image->GetNumberOfPoints();
  const unsigned char* rgb = Bytes(image);
  std::vector<float> rgba(4 * n, 0.0f);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[4 * i + c] = rgb[3 * i + c] / 255.0f;
    }
  }
  return rgba;
}

} // namespace savr_scenes
