// T, T^T 1 and the white frame of one capture.
#include "host/transport/capture_views.h"

#include "host/capture/manifest.h"
#include "host/transport/compute_transport.h"
#include "host/transport/spmv.h"
#include "host/transport/spmv_on_devices.h"

namespace rfrecon::transport {

CaptureViews view_capture(const std::filesystem::path& capture_dir, const CaptureSource& source,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  return view_capture(
      capture_dir,
      open_capture(capture_dir, source.layout, source.projector_size, source.frame_paths, source.bit_depth), devices,
      programs);
}

CaptureViews view_capture(const capture::FrameSource& frames, const capture::CaptureManifest& manifest,
                          std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  CaptureViews views;
  TransportSetup setup;
  // The board's dark squares (albedo about 0.05) read below the default black threshold and would count as shadow:
  // without T entries, T^T 1 would have them speckled and partly unreached, and filling those gaps pulls bright
  // values into the dark tips at every corner (0.095 px RMS projector corner error on checkerboard-poses, against
  // 0.029 px with every board pixel lit). A board pose has no shadow to reject: lit means above the noise.
  setup.thresholds.black = default_noise_threshold(manifest.bit_depth);
  const auto run = compute_transport_on_devices(frames, manifest, setup, devices, programs, cl::EntryChoice());
  views.schedule = run.schedule;
  views.checks = run.checks;
  const auto& transport = run.transport;

  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    if (manifest.frames[i].pattern.kind == capture::pattern_kind::kWhite) {
      auto with_size = manifest;
      with_size.camera_size = transport.setup.camera_size;
      views.camera_image = frames.load(with_size, i);
    }
  }
  const std::vector<float> ones(transport.camera_pixels(), 1.0f);
  const auto transposed = transpose(transport);
  auto product = dual_on_devices(devices, programs, cl::EntryChoice(), transposed, ones);
  views.schedule.push_back(product.report);
  views.dual_image = cv::Mat(transport.setup.projector_size, CV_32F, product.image.data()).clone();
  views.dual_reached = cv::Mat(transport.setup.projector_size, CV_8U);
  for (int q = 0; q < static_cast<int>(views.dual_reached.total()); ++q) {
    views.dual_reached.data[q] = transposed.row_start[q + 1] > transposed.row_start[q] ? 255 : 0;
  }
  views.correspondence =
      cv::Mat(transport.setup.camera_size, CV_32FC2, const_cast<float*>(transport.correspondence.data())).clone();
  return views;
}

}  // namespace rfrecon::transport
