// A whole scan, from camera frames to the fused point cloud, at a real rig's size (camera 1280x1024, projector
// 1024x768, the full protocol: white, black, Gray code, 8 x 8 dots): every stage timed, the transport's bytes against
// the minimal bytes and the memory roofline, peak resident memory, and the peer: the Gray-code-only triangulation
// against OpenCV's (GrayCodePattern decode plus cv::triangulatePoints) on the same frames. docs/performance.md.
//
//   build/bench/pipeline_bench [--scan=DIR] [--camera=WxH] [--benchmark_out=FILE --benchmark_out_format=json]
//
// --camera renders the scan at another camera size (default 1280x1024; the projector stays 1024x768): how time and
// memory grow with the camera's pixels. A DIR that holds a scan is reused at its own size.
// The scan (cube-anisotropic rendered by sim::simulate, about 40 s) is written to DIR when DIR has none, and reused;
// without --scan it goes to a temporary directory, removed at exit. BM_FusedScan takes the frames from memory, as a
// camera SDK hands them over (capture::FrameSource::from_callback over the decoded 16-bit frames), so that
// pipeline_seconds counts their linearisation but no file, and each scan's transport reuses the memory of the one
// before, in a process that keeps the memory it frees (keep_freed_memory), as a scanner's loop does;
// BM_FusedScanFromFiles reads the capture's files (simulate's default format, uncompressed TIFF) on the default reader
// threads and allocates its transport anew, as `rfrecon transport` does (in the same process), and
// BM_FusedScanFromPngFiles the same frames from a PNG copy of the capture (DIR/capture-png, made once);
// BM_Decode*Frames decode either copy's frames on one thread, the PNGs also by cv::imread. Counters are medians over
// the iterations.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench/bench_common.h"
#include "bench/opencv_graycode.h"
#include "calib/rig.h"
#include "host/capture/frame_source.h"
#include "host/capture/manifest.h"
#include "host/cl/device_selection.h"
#include "host/core/freed_memory.h"
#include "host/core/image_file.h"
#include "host/depth/reconstruct_depth.h"
#include "host/transport/compute_transport.h"
#include "host/transport/transport_file.h"
#include "sim/builtin_scenes.h"
#include "sim/simulate.h"

namespace {

using namespace rfrecon;
namespace fs = std::filesystem;

const cv::Size kProjector(1024, 768);

cv::Size& camera_size() {  // the size a scan is rendered at (--camera)
  static cv::Size size(1280, 1024);
  return size;
}

fs::path& scan_dir() {
  static fs::path dir;
  return dir;
}
fs::path capture_dir() { return scan_dir() / "capture"; }
fs::path png_capture_dir() { return scan_dir() / "capture-png"; }

// The modes of this program run as a child process (a fresh copy of it, so that its memory high-water mark and its
// threads are its own): render the scan, or run one fused scan.
constexpr const char* kRenderMode = "--child-render";
constexpr const char* kScanMode = "--child-scan";

// Runs this program in `mode` on scan_dir() and returns the child's peak resident memory in MB.
double run_child(const char* mode) {
  const std::string scan = "--scan=" + scan_dir().string();
  const std::string camera =
      "--camera=" + std::to_string(camera_size().width) + "x" + std::to_string(camera_size().height);
  const pid_t child = fork();
  if (child == 0) {
    execl("/proc/self/exe", "pipeline_bench", scan.c_str(), camera.c_str(), mode, static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(std::string("pipeline_bench: the child ") + mode + " failed");
  }
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

void render_scan() {
  sim::Scene scene = sim::builtin_scene("cube-anisotropic");
  sim::resize_device(scene.camera, camera_size());
  sim::resize_device(scene.projector, kProjector);
  sim::simulate(scene, scan_dir(), sim::SimulateOptions{});  // refuses a directory that holds anything else
}

// Renders the scan into scan_dir() unless it holds one.
void prepare_scan() {
  if (fs::exists(capture_dir() / capture::kManifestFileName)) return;
  std::printf("rendering the scan into %s (about 40 s)...\n", scan_dir().c_str());
  std::fflush(stdout);
  run_child(kRenderMode);
}

// Copies the capture into png_capture_dir() as 16-bit PNGs (OpenCV's default compression) unless it holds one.
void prepare_png_copy() {
  if (fs::exists(png_capture_dir() / capture::kManifestFileName)) return;
  capture::CaptureManifest manifest = capture::read_manifest(capture_dir());
  const fs::path staging = scan_dir() / "capture-png.partial";
  fs::remove_all(staging);
  fs::create_directories(staging);
  for (auto& frame : manifest.frames) {
    const cv::Mat raw = cv::imread((capture_dir() / frame.file).string(), cv::IMREAD_UNCHANGED);
    frame.file = fs::path(frame.file).replace_extension(".png").string();
    if (raw.empty() || !cv::imwrite((staging / frame.file).string(), raw)) {
      throw std::runtime_error("pipeline_bench: cannot copy " + frame.file + " into " + staging.string());
    }
  }
  capture::write_manifest(manifest, staging);
  fs::rename(staging, png_capture_dir());
}

// Figures one benchmark needs from another or from main (benchmarks run in the order registered below).
struct SharedFigures {
  double opencv_decode_seconds = 0.0;
  double peak_rss_mb = 0.0;
};
SharedFigures& shared() {
  static SharedFigures figures;
  return figures;
}

std::vector<rfrecon::cl::DeviceContext>& devices() {
  static std::vector<rfrecon::cl::DeviceContext> instance = rfrecon::cl::open_devices("");
  return instance;
}
rfrecon::cl::ProgramCache& programs() {
  static rfrecon::cl::ProgramCache cache;
  return cache;
}

// The manifest of the capture in `dir`; gray_only drops the dot frames (what a Gray-code scanner captures).
capture::CaptureManifest manifest(bool gray_only, const fs::path& dir = capture_dir()) {
  capture::CaptureManifest m = capture::read_manifest(dir);
  if (gray_only) {
    std::vector<capture::Frame> kept;
    for (const auto& frame : m.frames) {
      if (frame.pattern.kind != capture::pattern_kind::kDot) kept.push_back(frame);
    }
    m.frames = kept;
    m.dot_spacing = 0;
  }
  return m;
}

// One scan through transport and reconstruct on every device, with the stage timings both report.
struct ScanRun {
  std::map<std::string, double> seconds;  // per stage, transport's and reconstruct's
  double total_seconds = 0.0;             // every stage
  double usable_rows_pixels = 0.0;        // rectified samples carrying the ODE (integration's items)
  std::size_t transport_bytes = 0;        // T's indices and weights
};

// The rig and the depth stage's geometry of it, computed once, as a scanner does after its calibration: not part of
// a scan (counter rig_geometry_seconds).
struct RigSetup {
  calib::StereoRig rig;
  depth::Rectification rectification;
  double seconds = 0.0;
};
const RigSetup& rig_setup() {
  static const RigSetup setup = [] {
    RigSetup result;
    result.rig = calib::read_rig(scan_dir() / "truth" / "rig.yaml");
    const auto start = std::chrono::steady_clock::now();
    result.rectification = depth::depth_rectification(result.rig, "truth/rig.yaml");
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }();
  return setup;
}

// With `storage`, the transport reuses its memory and leaves its own there for the next scan, as a scanner's loop
// does (compute_transport_on_devices). `dir` holds the manifest that names the frames.
ScanRun run_scan(const capture::FrameSource& frames, bool gray_only, const std::string& method,
                 transport::CompressedTransport* storage = nullptr, const fs::path& dir = capture_dir()) {
  const RigSetup& rig = rig_setup();
  ScanRun run;
  auto transport = transport::compute_transport_on_devices(
      frames, manifest(gray_only, dir), {}, devices(), programs(), rfrecon::cl::KernelEntry::kNdRange,
      transport::kDefaultReaders, storage != nullptr ? std::move(*storage) : transport::CompressedTransport{});
  for (const auto& timing : transport.timings) run.seconds[timing.stage] += timing.seconds;
  depth::DepthOptions options;
  options.method = method;
  const auto depth = depth::reconstruct_depth(transport.transport, rig.rig, rig.rectification, "truth/rig.yaml",
                                              options, devices(), programs());
  for (const auto& timing : depth.summary.at("timings")) {
    run.seconds[timing.at("stage").get<std::string>()] += timing.at("seconds").get<double>();
  }
  for (const auto& [stage, seconds] : run.seconds) {
    run.total_seconds += seconds;
  }
  if (depth.summary.contains("segmentation")) {
    run.usable_rows_pixels = depth.summary.at("segmentation").at("usable_pixels").get<double>();
  }
  run.transport_bytes =
      transport.transport.indices.size() * sizeof(std::int32_t) + transport.transport.weights.size() * sizeof(float);
  if (storage != nullptr) *storage = std::move(transport.transport);
  return run;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0.0 : n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The scans of a benchmark's iterations but the first (which builds the programs and allocates), each stage's seconds
// and the whole's their medians (so the stages need not add up to the whole); the rest from the last scan.
ScanRun median_scan(const std::vector<ScanRun>& runs) {
  if (runs.size() < 2) throw std::runtime_error("pipeline_bench: a benchmark needs two iterations at least");
  ScanRun result = runs.back();
  const auto later = [&](const auto& figure) {
    std::vector<double> values;
    for (std::size_t i = 1; i < runs.size(); ++i) values.push_back(figure(runs[i]));
    return median(values);
  };
  for (auto& entry : result.seconds) {
    const std::string& stage = entry.first;
    entry.second =
        later([&](const ScanRun& run) { return run.seconds.count(stage) != 0 ? run.seconds.at(stage) : 0.0; });
  }
  result.total_seconds = later([](const ScanRun& run) { return run.total_seconds; });
  return result;
}

std::size_t frame_count(bool gray_only) { return manifest(gray_only).frames.size(); }
// The camera's 16-bit samples, as the kernels read them (white and black aside, made linear once on the host).
double frame_bytes() { return static_cast<double>(manifest(false).camera_size.area()) * sizeof(std::uint16_t); }

// The frames of manifest(gray_only) as the camera gave them (16-bit samples), decoded once, handed over by a
// callback.
capture::FrameSource frames_in_memory(bool gray_only) {
  static std::map<bool, std::vector<cv::Mat>> raw;
  if (raw[gray_only].empty()) {
    for (const auto& frame : manifest(gray_only).frames) {
      raw[gray_only].push_back(
          cv::imread((capture_dir() / frame.file).string(), cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH));
    }
  }
  const std::vector<cv::Mat>& frames = raw[gray_only];
  return capture::FrameSource::from_callback([&frames](std::size_t i) { return frames.at(i); }, "frames in memory");
}

// Fused pipeline from frames in memory. Counters, medians over the iterations but the first (median_scan): each
// stage's seconds, pipeline_seconds (all of them; the rig's geometry, computed once before, is rig_geometry_seconds),
// the transport's minimal bytes (every frame's 16-bit samples read once, T written once) against the roofline,
// compression's fraction of it and of the read-only roofline (dot frames' bytes / compress seconds), the
// integration's Mpx/s.
void BM_FusedScan(benchmark::State& state) {
  const capture::FrameSource frames = frames_in_memory(false);
  std::vector<ScanRun> runs;
  transport::CompressedTransport storage;
  for (auto _ : state) runs.push_back(run_scan(frames, false, "fused", &storage));
  ScanRun run = median_scan(runs);
  for (const auto& [stage, seconds] : run.seconds) state.counters[stage + "_seconds"] = seconds;
  state.counters["pipeline_seconds"] = run.total_seconds;
  const double roofline = bench::host_stream_bytes_per_second();
  const double minimal_bytes = static_cast<double>(frame_count(false)) * frame_bytes() + run.transport_bytes;
  const double transport_seconds = run.seconds["decode"] + run.seconds["compress"] + run.seconds["finalize"];
  state.counters["transport_minimal_bytes"] = minimal_bytes;
  state.counters["transport_roofline_fraction"] = minimal_bytes / transport_seconds / roofline;
  const double dot_bytes = static_cast<double>(frame_count(false) - frame_count(true)) * frame_bytes();
  state.counters["compress_roofline_fraction"] = dot_bytes / run.seconds["compress"] / roofline;
  state.counters["compress_read_roofline_fraction"] =
      dot_bytes / run.seconds["compress"] / bench::host_read_bytes_per_second();
  state.counters["integrate_mpx_per_s"] = run.usable_rows_pixels / run.seconds["integrate"] / 1e6;
  state.counters["peak_rss_mb"] = shared().peak_rss_mb;
  state.counters["rig_geometry_seconds"] = rig_setup().seconds;
}

// The same scan from the capture's files in `dir`, read on transport::kDefaultReaders threads while the devices work.
void scan_files(benchmark::State& state, const fs::path& dir) {
  std::vector<ScanRun> runs;
  for (auto _ : state) runs.push_back(run_scan(dir, false, "fused", nullptr, dir));
  const ScanRun run = median_scan(runs);
  for (const auto& [stage, seconds] : run.seconds) state.counters[stage + "_seconds"] = seconds;
  state.counters["pipeline_with_reading_seconds"] = run.total_seconds;
}
void BM_FusedScanFromFiles(benchmark::State& state) { scan_files(state, capture_dir()); }
void BM_FusedScanFromPngFiles(benchmark::State& state) { scan_files(state, png_capture_dir()); }

// Decoding every frame of the capture in `dir` one after another on one thread, as a reader thread does: by
// decode_image (rfrecon's reads), or by cv::imread (the peer). ms_per_frame: the median over the iterations.
void decode_frames(benchmark::State& state, const fs::path& dir, bool opencv) {
  const capture::CaptureManifest frames = manifest(false, dir);
  const int flags = cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH;
  std::vector<double> ms_per_frame;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    for (const auto& frame : frames.frames) {
      const fs::path file = dir / frame.file;
      const cv::Mat image = opencv ? cv::imread(file.string(), flags) : decode_image(file, flags);
      benchmark::DoNotOptimize(image.data);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ms_per_frame.push_back(seconds * 1e3 / static_cast<double>(frames.frames.size()));
  }
  state.counters["ms_per_frame"] = median(ms_per_frame);
}
void BM_DecodeTiffFrames(benchmark::State& state) { decode_frames(state, capture_dir(), false); }
void BM_DecodePngFrames(benchmark::State& state) { decode_frames(state, png_capture_dir(), false); }
void BM_DecodePngFramesOpenCV(benchmark::State& state) { decode_frames(state, png_capture_dir(), true); }

// rfrecon's Gray-code-only triangulation (decode, sub-pixel refinement, triangulation) on the scan's Gray frames, in
// memory as OpenCV's are.
void BM_GrayTriangulation(benchmark::State& state) {
  const capture::FrameSource frames = frames_in_memory(true);
  std::vector<ScanRun> runs;
  transport::CompressedTransport storage;
  for (auto _ : state) runs.push_back(run_scan(frames, true, "triangulate", &storage));
  ScanRun run = median_scan(runs);
  for (const auto& [stage, seconds] : run.seconds) state.counters[stage + "_seconds"] = seconds;
  state.counters["pipeline_seconds"] = run.total_seconds;
  state.counters["decode_speedup_vs_opencv"] = shared().opencv_decode_seconds / run.seconds["decode"];
}

// OpenCV's pipeline on the same Gray frames (loaded once, 8-bit): GrayCodePattern::getProjPixel per lit pixel
// (integer projector pixels), then cv::undistortPoints and cv::triangulatePoints through the true rig
// (bench/opencv_graycode.h).
void BM_GrayTriangulationOpenCV(benchmark::State& state) {
  static const bench::OpencvGrayFrames frames = bench::opencv_gray_frames(capture_dir());
  const calib::StereoRig rig = calib::read_rig(scan_dir() / "truth" / "rig.yaml");
  std::size_t points = 0;
  std::vector<double> decode_seconds, pipeline_seconds;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const bench::OpencvCorrespondences decoded = bench::opencv_gray_decode(frames, 10, 5);  // rfrecon's thresholds
    decode_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const std::vector<cv::Point3f> triangulated = bench::opencv_triangulate(rig, decoded);
    points = triangulated.size();
    benchmark::DoNotOptimize(triangulated.data());
    pipeline_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["pipeline_seconds"] = median(pipeline_seconds);
  state.counters["decode_seconds"] = median(decode_seconds);
  shared().opencv_decode_seconds = median(decode_seconds);
}

// Wall-clock time throughout (the devices' work runs in PoCL's threads). Each iteration is a whole scan of seconds;
// the counters are medians over the iterations (but the first, for rfrecon's: median_scan).
BENCHMARK(BM_GrayTriangulationOpenCV)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_GrayTriangulation)->Unit(benchmark::kMillisecond)->Iterations(6)->UseRealTime();
BENCHMARK(BM_FusedScan)->Unit(benchmark::kMillisecond)->Iterations(6)->UseRealTime();
BENCHMARK(BM_FusedScanFromFiles)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_FusedScanFromPngFiles)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_DecodeTiffFrames)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_DecodePngFrames)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_DecodePngFramesOpenCV)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> arguments;
  bool temporary = true;
  std::string mode;
  for (int i = 0; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument.rfind("--scan=", 0) == 0) {
      scan_dir() = argument.substr(7);
      temporary = false;
    } else if (argument.rfind("--camera=", 0) == 0) {
      int width = 0, height = 0;
      if (std::sscanf(argument.c_str() + 9, "%dx%d", &width, &height) != 2 || width < 64 || height < 64) {
        std::fprintf(stderr, "pipeline_bench: --camera takes WxH, at least 64x64: %s\n", argument.c_str());
        return 2;
      }
      camera_size() = cv::Size(width, height);
    } else if (argument == kRenderMode || argument == kScanMode) {
      mode = argument;
    } else {
      arguments.push_back(argv[i]);
    }
  }
  if (mode == kRenderMode) {
    try {
      render_scan();
    } catch (const std::exception& error) {
      std::fprintf(stderr, "pipeline_bench: %s\n", error.what());
      return 3;
    }
    return 0;
  }
  if (mode == kScanMode) {
    run_scan(capture_dir(), false, "fused");
    return 0;
  }
  if (temporary) scan_dir() = fs::temp_directory_path() / ("rfrecon_pipeline_bench_" + std::to_string(getpid()));
  int count = static_cast<int>(arguments.size());
  benchmark::Initialize(&count, arguments.data());
  if (benchmark::ReportUnrecognizedArguments(count, arguments.data())) return 1;
  try {
    prepare_scan();
    prepare_png_copy();
    shared().peak_rss_mb = run_child(kScanMode);
  } catch (const std::exception& error) {  // the child has said why
    std::fprintf(stderr, "%s\n", error.what());
    return 3;
  }
  // The benchmarks' process scans again and again, as a scanner does: it keeps the memory it frees (the child that
  // measured the peak resident memory above did not, as `rfrecon` does not).
  const cv::Size camera = manifest(false).camera_size;
  const double pixels = static_cast<double>(camera.area());
  benchmark::AddCustomContext("camera", std::to_string(camera.width) + "x" + std::to_string(camera.height));
  benchmark::AddCustomContext("peak_rss_bytes_per_pixel", std::to_string(shared().peak_rss_mb * 1048576.0 / pixels));
  benchmark::AddCustomContext("keep_freed_memory", keep_freed_memory() ? "yes" : "no (malloc is not glibc's)");
  rfrecon::bench::add_run_context();
  rfrecon::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  const double opencv = reporter.counter("BM_GrayTriangulationOpenCV", "pipeline_seconds");
  std::printf(
      "\nfused scan: %.3f s from frames in memory, %.3f s from TIFF files, %.3f s from PNG files, peak resident "
      "memory %.0f MB\n",
      reporter.counter("BM_FusedScan", "pipeline_seconds"),
      reporter.counter("BM_FusedScanFromFiles", "pipeline_with_reading_seconds"),
      reporter.counter("BM_FusedScanFromPngFiles", "pipeline_with_reading_seconds"), shared().peak_rss_mb);
  std::printf("camera %dx%d: %.1f ns and %.0f bytes of peak memory per camera pixel (from frames in memory)\n",
              camera.width, camera.height, reporter.counter("BM_FusedScan", "pipeline_seconds") / pixels * 1e9,
              shared().peak_rss_mb * 1048576.0 / pixels);
  std::printf("Gray-code triangulation: rfrecon %.3f s, OpenCV %.3f s: %.1fx; decoding alone %.1fx\n",
              reporter.counter("BM_GrayTriangulation", "pipeline_seconds"), opencv,
              ratio(opencv, reporter.counter("BM_GrayTriangulation", "pipeline_seconds")),
              reporter.counter("BM_GrayTriangulation", "decode_speedup_vs_opencv"));
  const double png_ms = reporter.counter("BM_DecodePngFrames", "ms_per_frame");
  std::printf("decoding a frame on one thread: TIFF %.2f ms, PNG %.2f ms, OpenCV's imread of the PNG %.2f ms: %.1fx\n",
              reporter.counter("BM_DecodeTiffFrames", "ms_per_frame"), png_ms,
              reporter.counter("BM_DecodePngFramesOpenCV", "ms_per_frame"),
              ratio(reporter.counter("BM_DecodePngFramesOpenCV", "ms_per_frame"), png_ms));
  std::printf("roofline %.2f GB/s: transport %.3f of it on minimal bytes, compression %.3f; integration %.1f Mpx/s\n",
              rfrecon::bench::host_stream_bytes_per_second() / 1e9,
              reporter.counter("BM_FusedScan", "transport_roofline_fraction"),
              reporter.counter("BM_FusedScan", "compress_roofline_fraction"),
              reporter.counter("BM_FusedScan", "integrate_mpx_per_s"));
  std::printf("read-only roofline %.2f GB/s: compression %.3f of it\n",
              rfrecon::bench::host_read_bytes_per_second() / 1e9,
              reporter.counter("BM_FusedScan", "compress_read_roofline_fraction"));
  benchmark::Shutdown();
  if (temporary) fs::remove_all(scan_dir());
  return 0;
}
