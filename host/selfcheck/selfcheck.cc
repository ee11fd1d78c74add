// The self-check inputs, runs and comparison.
#include "host/selfcheck/selfcheck.h"

#include <stdexcept>
#include <string>

#include "host/selfcheck/axpy.h"

namespace rfrecon::selfcheck {

std::vector<SelfcheckResult> run_selfcheck(std::vector<cl::DeviceContext>& devices, std::size_t elements) {
  if (elements == 0 || elements > kMaxSelfcheckElements) {
    throw std::invalid_argument("run_selfcheck: elements must be in [1, " + std::to_string(kMaxSelfcheckElements) +
                                "]");
  }
  std::vector<float> x(elements);
  std::vector<float> y(elements);
  for (std::size_t i = 0; i < elements; ++i) {
    x[i] = static_cast<float>(i % 1000) * 0.25f;
    y[i] = 1.0f - static_cast<float>(i % 7);
  }
  const float a = 1.5f;
  const auto expected = axpy_reference(a, x, y);
  cl::ProgramCache programs;
  std::vector<SelfcheckResult> results;
  for (auto& device : devices) {
    for (const auto entry : {KernelEntry::kNdRange, KernelEntry::kSingleWorkItem}) {
      const auto got = axpy_opencl(device, programs, entry, a, x, y);
      SelfcheckResult result{&device.info(), entry, got.size(), 0};
      for (std::size_t i = 0; i < got.size(); ++i) result.mismatches += got[i] != expected[i] ? 1 : 0;
      results.push_back(result);
    }
  }
  return results;
}

}  // namespace rfrecon::selfcheck
