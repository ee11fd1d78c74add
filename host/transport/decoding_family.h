// The transport stage's side of a pattern family (host/capture/pattern_family.h): how a capture of it streams into a
// compressed T. A family plans the accumulator calls, makes its accumulators (the C++ reference, and on an OpenCL
// device with the programs it names) and may complete T on the host afterwards. compute_transport is the driver.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/manifest.h"
#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/transport/accumulator.h"
#include "host/transport/gray_decision.h"
#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// Host work on the whole camera image after the accumulators, fed every step's frames as they are read.
class TransportRefinement {
 public:
  virtual ~TransportRefinement() = default;
  // `frames` as the accumulators take them (setup.frame_depth).
  virtual void add(const TransportStep& step, const std::vector<cv::Mat>& frames) = 0;
  // Completes T; for families that decode Gray code, how its pixels were decided.
  virtual std::optional<GrayDecisionCounts> refine(CompressedTransport& transport) = 0;
};

class DecodingFamily {
 public:
  virtual ~DecodingFamily() = default;
  // The pattern family's name.
  virtual std::string name() const = 0;
  // The accumulator calls for a validated manifest of the family, in order, ending with a kFinishStep.
  virtual std::vector<TransportStep> plan(const capture::CaptureManifest& manifest) const = 0;
  // The OpenCL programs of its device accumulators for `entry`, built on every device before the first frame.
  virtual std::vector<cl::ProgramRequest> programs(const TransportSetup& setup, KernelEntry entry) const = 0;
  // An accumulator of a camera row block (setup.camera_size has the block's rows) on the host.
  virtual std::unique_ptr<TransportAccumulator> make_reference(const TransportSetup& setup) const = 0;
  // The same on a device; `storage`: an earlier transport whose memory it may reuse (make_empty_decoding).
  virtual std::unique_ptr<TransportAccumulator> make_device(const TransportSetup& setup, cl::DeviceContext& device,
                                                            cl::ProgramCache& programs, KernelEntry entry,
                                                            CompressedTransport storage) const = 0;
  // The refinement of a whole capture, or none.
  virtual std::unique_ptr<TransportRefinement> refinement(const TransportSetup& setup, const cv::Mat& white,
                                                          const cv::Mat& black) const = 0;
};

// The family called `name`; InputError listing the registered ones when there is none.
const DecodingFamily& decoding_family(const std::string& name);

// Adds a family (its patterns go to capture::register_pattern_family); std::invalid_argument when the name is taken.
void register_decoding_family(std::shared_ptr<const DecodingFamily> family);

}  // namespace rfrecon::transport
