// A capture's sequence and images, asked of its pattern family.
#include "host/capture/protocol.h"

#include "host/capture/pattern_family.h"
#include "host/core/errors.h"
#include "host/core/limits.h"

namespace rfrecon::capture {

void check_projector_size(cv::Size projector_size) {
  if (projector_size.width < 2 || projector_size.height < 2) {
    throw InputError("projector size must be at least 2x2, got " + std::to_string(projector_size.width) + "x" +
                     std::to_string(projector_size.height));
  }
  check_image_size(projector_size, "projector");
}

std::vector<Pattern> make_protocol(const ProtocolOptions& options) {
  const PatternFamily& family = pattern_family(options.family);
  check_projector_size(options.projector_size);
  check_family_parameters(family, options.parameters, "pattern family " + family.name());
  return family.sequence(options);
}

cv::Mat render_pattern(const Pattern& pattern, const ProtocolOptions& options) {
  return pattern_family(options.family).render(pattern, options);
}

}  // namespace rfrecon::capture
