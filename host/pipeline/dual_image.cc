// T.h5 to a primal or dual image file.
#include "host/pipeline/dual_image.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/output_path.h"
#include "host/core/percentile.h"
#include "host/core/stage_clock.h"
#include "host/transport/spmv.h"
#include "host/transport/transport_file.h"

namespace rfrecon::pipeline {

namespace {
// .tif/.tiff: 32-bit float. Otherwise 16-bit with `white` (the 99.9th percentile) mapped to 65535.
std::vector<unsigned char> encode(const cv::Mat& image, const std::filesystem::path& output, float& white) {
  const std::string extension = lowercase_extension(output);
  std::vector<unsigned char> bytes;
  if (extension == ".tif" || extension == ".tiff") {
    cv::imencode(".tiff", image, bytes);
    return bytes;
  }
  const float percentile = finite_percentile(image, 0.999);
  white = std::isnan(percentile) ? 1.0f : std::max(percentile, 1e-12f);
  cv::Mat scaled;
  image.convertTo(scaled, CV_16U, 65535.0 / white);
  if (!cv::imencode(extension, scaled, bytes)) {
    throw UsageError("--output " + output.string() + ": cannot encode an image with extension '" + extension + "'");
  }
  return bytes;
}

// The output's extension is one OpenCV writes 16-bit images as, or a TIFF (float).
void check_image_extension(const std::filesystem::path& output) {
  const std::string extension = lowercase_extension(output);
  if (extension != ".png" && extension != ".tif" && extension != ".tiff" && extension != ".pgm") {
    throw UsageError("--output " + output.string() +
                     ": the extension must be .png, .pgm (16-bit) or .tif/.tiff (float)");
  }
}
}  // namespace

DualImageRun view_product(const transport::CompressedTransport& transport, bool primal,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  const cl::EntryChoice entries;  // auto: each device on the entry that suits it
  DualImageRun run;
  StageClock clock;
  clock.time("kernels", [&] {
    if (primal) {
      run.size = transport.setup.camera_size;
      run.product = transport::primal_on_devices(devices, programs, entries, transport,
                                                 std::vector<float>(transport.projector_pixels(), 1.0f));
    } else {
      run.size = transport.setup.projector_size;
      run.product = transport::dual_on_devices(devices, programs, entries, transport::transpose(transport),
                                               std::vector<float>(transport.camera_pixels(), 1.0f));
    }
  });
  run.seconds = clock.total_seconds();
  return run;
}

DualImageRun dual_image(const DualImageRequest& request, std::vector<cl::DeviceContext>& devices,
                        cl::ProgramCache& programs) {
  const OutputPath output{request.output, "--output", request.force};
  const OutputPath summary_output{request.summary, "--summary", request.force};
  check_output_file(output, {request.transport});
  check_image_extension(request.output);
  if (!request.summary.empty()) check_output_file(summary_output, {request.transport});
  check_distinct_outputs({output, summary_output});
  const auto transport = transport::read_transport(request.transport);
  DualImageRun run = view_product(transport, request.primal, devices, programs);
  const cv::Mat image(run.size, CV_32F, run.product.image.data());
  const auto bytes = encode(image, request.output, run.white);
  AtomicFile image_file(request.output);
  image_file.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  std::optional<AtomicFile> summary_file;
  if (!request.summary.empty()) {
    const nlohmann::json summary = {{"command", request.primal ? "primal" : "dual"},
                                    {"output", request.output.string()},
                                    {"kernel_seconds", run.seconds},
                                    {"schedule", nlohmann::json::array({run.product.report})}};
    summary_file.emplace(request.summary);
    summary_file->write(summary.dump(2) + "\n");
  }
  image_file.commit();
  if (summary_file) summary_file->commit();
  return run;
}

}  // namespace rfrecon::pipeline
