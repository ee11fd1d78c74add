// libFuzzer target: a capture directory's manifest.json (capture::read_manifest), then each frame it lists
// (capture::load_frame). The frames the input names are written as one tiny 2x2 8-bit PNG, so that inputs get past
// the file checks. InputError is the documented rejection; any other exception, crash or sanitizer report is a finding.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/manifest.h"
#include "host/core/errors.h"
#include "tests/fuzz/fuzz_files.h"

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxFrameFiles = 64;

// Writes `png` as every plain file name (no directory part, not the manifest's) that the input lists as frames[i].file.
void write_listed_frames(const fs::path& dir, const std::uint8_t* data, std::size_t size,
                         const std::vector<std::uint8_t>& png) {
  const auto root = nlohmann::json::parse(data, data + size, nullptr, false);
  if (!root.is_object() || !root.contains("frames") || !root["frames"].is_array()) return;
  std::size_t written = 0;
  for (const auto& frame : root["frames"]) {
    if (written == kMaxFrameFiles) return;
    if (!frame.is_object() || !frame.contains("file") || !frame["file"].is_string()) continue;
    const auto name = frame["file"].get<std::string>();
    if (name.empty() || name == "." || name == ".." || name == rfrecon::capture::kManifestFileName ||
        fs::path(name).filename() != name) {
      continue;
    }
    rfrecon::fuzz::write_file(dir / name, png.data(), png.size());
    ++written;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rfrecon::fuzz::ScratchDir scratch;
  static const std::vector<std::uint8_t> png = [] {
    std::vector<std::uint8_t> bytes;
    cv::imencode(".png", cv::Mat(2, 2, CV_8U, cv::Scalar(128)), bytes);
    return bytes;
  }();
  const fs::path dir = scratch.path() / "capture";
  fs::remove_all(dir);
  fs::create_directory(dir);
  rfrecon::fuzz::write_file(dir / rfrecon::capture::kManifestFileName, data, size);
  write_listed_frames(dir, data, size, png);
  try {
    const auto manifest = rfrecon::capture::read_manifest(dir);
    for (std::size_t i = 0; i < manifest.frames.size(); ++i) (void)rfrecon::capture::load_frame(dir, manifest, i);
  } catch (const rfrecon::InputError&) {
  }
  return 0;
}
