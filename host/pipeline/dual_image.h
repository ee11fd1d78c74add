// `rfrecon dual` as a library call: the dual image T^T 1 seen from the projector, or the primal image T 1, of a T.h5.
#pragma once

#include <filesystem>
#include <vector>

#include "host/transport/spmv_on_devices.h"

namespace rfrecon::pipeline {

struct DualImageRequest {
  std::filesystem::path transport;  // T.h5
  bool primal = false;              // T 1 (camera view) instead of T^T 1
  std::filesystem::path output;     // .tif/.tiff: float values of T's units; else 16-bit, the 99.9th percentile 65535
  std::filesystem::path summary;    // optional JSON of the timing and per-device shares
  bool force = false;               // replace existing output and summary files
};

struct DualImageRun {
  transport::ProductRun product;
  cv::Size size;
  float white = 0.0f;  // the value written as 65535 (16-bit outputs), 0 for TIFF
  double seconds = 0.0;
};

// T^T 1 (projector size) or, with `primal`, T 1 (camera size) of a transport in memory, on `devices` with the entry
// that suits each: the product and its image size, as dual_image computes them for its file.
DualImageRun view_product(const transport::CompressedTransport& transport, bool primal,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs);

// Throws UsageError (before reading) for an output check_output_file refuses or an extension other than .png, .pgm,
// .tif, .tiff; InputError naming the file for a bad T.h5; OutputError when an output cannot be written. The image
// and the summary are renamed into place only once both are written.
DualImageRun dual_image(const DualImageRequest& request, std::vector<cl::DeviceContext>& devices,
                        cl::ProgramCache& programs);

}  // namespace rfrecon::pipeline
