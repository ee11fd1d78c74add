// OpenCV's Gray-code pipeline (bench/opencv_graycode.h) as a reconstruction directory that `rfrecon evaluate` scores,
// so that the accuracy tables set OpenCV's decoding beside rfrecon's methods on the same pixels.
//
//   build/bench/opencv_graycode_reconstruct CAPTURE_DIR RIG.yaml OUT_DIR [--force]
//
// OUT_DIR gets depth.tiff and points.tiff (each decoded camera pixel's triangulated point, its z as depth), normals
// NaN and confidence 1 where there is a point, points.ply and summary.json, as `rfrecon reconstruct` writes them.
// Exit codes: 0 done, 2 usage (an OUT_DIR that holds an input, or exists without --force), 3 bad input (the message
// names the file), 6 nothing decoded, 1 a bug.
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/opencv_graycode.h"
#include "host/core/errors.h"
#include "host/core/output_path.h"
#include "host/outputs/reconstruction_files.h"

namespace {

using namespace rfrecon;

int run(const std::string& capture_dir, const std::string& rig_file, const std::string& out_dir, bool force) {
  check_output_directory({out_dir, "OUT_DIR", force}, {capture_dir, rig_file});  // before any work
  const calib::StereoRig rig = calib::read_rig(rig_file);
  const bench::OpencvGrayFrames frames = bench::opencv_gray_frames(capture_dir);
  const bench::OpencvCorrespondences decoded = bench::opencv_gray_decode(frames, 10, 5);
  if (decoded.camera_px.empty()) throw ProcessingError(capture_dir + ": OpenCV decodes no pixel");
  const std::vector<cv::Point3f> points = bench::opencv_triangulate(rig, decoded);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const cv::Size size = frames.white.size();
  outputs::Reconstruction maps;
  maps.depth_mm = cv::Mat(size, CV_32F, cv::Scalar(nan));
  maps.points_mm = cv::Mat(size, CV_32FC3, cv::Scalar::all(nan));
  maps.normals = cv::Mat(size, CV_32FC3, cv::Scalar::all(nan));
  maps.confidence = cv::Mat(size, CV_32F, cv::Scalar(0.0f));
  int reconstructed = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cv::Point3f& x = points[i];
    if (!(x.z > 0.0f) || !std::isfinite(x.x) || !std::isfinite(x.y)) continue;
    const auto u = static_cast<int>(decoded.camera_px[i].x), v = static_cast<int>(decoded.camera_px[i].y);
    maps.depth_mm.at<float>(v, u) = x.z;
    maps.points_mm.at<cv::Vec3f>(v, u) = {x.x, x.y, x.z};
    maps.confidence.at<float>(v, u) = 1.0f;
    ++reconstructed;
  }
  const nlohmann::json summary = {{"method", "opencv-graycode"},
                                  {"decoder", "cv::structured_light::GrayCodePattern, black 10 DN, white 5 DN"},
                                  {"decoded_pixels", decoded.camera_px.size()},
                                  {"reconstructed_pixels", reconstructed}};
  outputs::write_reconstruction(maps, summary, out_dir, force);
  std::printf("opencv-graycode: %d of %d camera pixels, wrote %s\n", reconstructed, size.area(), out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const bool force = argc == 5 && std::string(argv[4]) == "--force";
  if (argc != 4 && !force) {
    std::fprintf(stderr, "usage: %s CAPTURE_DIR RIG.yaml OUT_DIR [--force]\n", argv[0]);
    return 2;
  }
  try {
    return run(argv[1], argv[2], argv[3], force);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const ProcessingError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 6;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bug: %s\n", e.what());
    return 1;
  }
}
