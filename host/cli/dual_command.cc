// `rfrecon dual`: the dual image T^T 1 (projector view) or, with --primal, the primal image T 1 of a T.h5.
#include <algorithm>
#include <chrono>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "host/cl/device_selection.h"
#include "host/cli/commands.h"
#include "host/common/atomic_file.h"
#include "host/common/errors.h"
#include "host/sched/spmv_on_devices.h"
#include "host/transport/spmv.h"
#include "host/transport/transport_file.h"

namespace rfrecon::cli {

namespace {
struct DualOptions {
  std::filesystem::path input;
  std::filesystem::path output;
  std::filesystem::path summary;
  bool primal = false;
  std::string devices;
};

// .tif/.tiff: 32-bit float values of T's units. Otherwise 16-bit, the 99.9th percentile mapped to 65535.
std::vector<unsigned char> encode(const cv::Mat& image, const std::filesystem::path& output) {
  std::string extension = output.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  std::vector<unsigned char> bytes;
  if (extension == ".tif" || extension == ".tiff") {
    cv::imencode(".tiff", image, bytes);
    return bytes;
  }
  std::vector<float> values(image.begin<float>(), image.end<float>());
  const auto rank = static_cast<std::ptrdiff_t>(0.999 * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  const double white = std::max(values[static_cast<std::size_t>(rank)], 1e-12f);
  cv::Mat scaled;
  image.convertTo(scaled, CV_16U, 65535.0 / white);
  spdlog::info("dual: {} scaled so that {:.6g} (99.9th percentile) is 65535", output.string(), white);
  if (!cv::imencode(extension.empty() ? ".png" : extension, scaled, bytes)) {
    throw InputError(output.string() + ": cannot encode an image with extension '" + extension + "'");
  }
  return bytes;
}

void run_dual(const DualOptions& options) {
  const auto transport = transport::read_transport(options.input);
  auto devices = cl::open_devices(options.devices);
  cl::ProgramCache programs;
  const auto entry = transport::KernelEntry::kNdRange;
  const auto start = std::chrono::steady_clock::now();
  sched::ProductRun run;
  cv::Mat image;
  if (options.primal) {
    const std::vector<float> light(transport.projector_pixels(), 1.0f);
    image = cv::Mat(transport.setup.camera_size, CV_32F);
    run = sched::primal_on_devices(devices, programs, entry, transport, light);
  } else {
    const std::vector<float> light(transport.camera_pixels(), 1.0f);
    image = cv::Mat(transport.setup.projector_size, CV_32F);
    run = sched::dual_on_devices(devices, programs, entry, transport::transpose(transport), light);
  }
  std::copy(run.image.begin(), run.image.end(), image.begin<float>());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sched::log_reports({run.report});
  const auto bytes = encode(image, options.output);
  write_file_atomically(options.output, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  spdlog::info("{}: wrote {} image {}x{} to {}", options.primal ? "primal" : "dual",
               options.primal ? "camera" : "projector", image.cols, image.rows, options.output.string());
  if (!options.summary.empty()) {
    const nlohmann::json summary = {{"command", options.primal ? "primal" : "dual"},
                                    {"output", options.output.string()},
                                    {"kernel_seconds", seconds},
                                    {"schedule", nlohmann::json::array({run.report})}};
    write_file_atomically(options.summary, summary.dump(2) + "\n");
  }
}
}  // namespace

void add_dual_command(CLI::App& app) {
  auto options = std::make_shared<DualOptions>();
  auto* command = app.add_subcommand("dual", "Dual image T^T 1 seen from the projector (or primal T 1) of a T.h5");
  command->add_option("transport", options->input, "Compressed light transport (T.h5)")->required();
  command->add_option("-o,--output", options->output, "Image: .png (16-bit, scaled) or .tiff (float)")->required();
  command->add_flag("--primal", options->primal, "Write the primal image T 1 (camera view) instead");
  command->add_option("--summary", options->summary, "Also write the timing and per-device shares to this JSON");
  add_devices_option(command, options->devices);
  command->callback([options] { run_dual(*options); });
}

}  // namespace rfrecon::cli
