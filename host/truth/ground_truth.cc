// Ground-truth maps as OpenCV images, the points as binary PLY, the objects as JSON.
#include "host/truth/ground_truth.h"

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/json_file.h"
#include "host/core/ply.h"

namespace rfrecon::truth {

namespace fs = std::filesystem;

namespace {
constexpr const char* kObjectsFile = "objects.json";

// The truth folder of `dir`: dir itself when it holds depth.tiff, else dir/truth.
fs::path locate_truth(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_regular_file(dir / "depth.tiff", ec)) return dir;
  if (fs::is_regular_file(dir / "truth" / "depth.tiff", ec)) return dir / "truth";
  if (fs::is_directory(dir / "truth" / "pose_00", ec) || fs::is_directory(dir / "pose_00", ec)) {
    throw InputError(dir.string() +
                     ": a multi-view rendering (one truth folder per view); name one view's folder, "
                     "e.g. " +
                     (dir / "truth" / "pose_00").string());
  }
  throw InputError(dir.string() +
                   ": neither a truth folder (depth.tiff, normals.tiff, object_id.png, objects.json) "
                   "nor a `rfrecon simulate` output directory holding one in truth/");
}

std::vector<TruthObject> read_objects(const fs::path& file) {
  const auto json = read_json_file(file);
  std::vector<TruthObject> objects;
  try {
    for (const auto& entry : json.at("objects")) {
      TruthObject object;
      object.label = entry.at("label").get<int>();
      object.name = entry.at("name").get<std::string>();
      object.shape = entry.at("shape").get<std::string>();
      object.size_mm = entry.at("size_mm").get<double>();
      object.size_rule = entry.at("size_rule").get<std::string>();
      objects.push_back(std::move(object));
    }
  } catch (const nlohmann::json::exception& error) {
    throw InputError(file.string() + ": " + error.what());
  }
  return objects;
}
}  // namespace

void write_truth_points(const fs::path& file, const TruthMaps& maps) {
  write_point_cloud_ply(file, "rfrecon synthetic ground truth, camera frame, mm", maps.points_mm, maps.normals);
}

void write_truth(const fs::path& dir, const TruthMaps& maps, const std::vector<TruthObject>& objects) {
  write_image(dir / "depth.tiff", maps.depth_mm);
  write_image(dir / "normals.tiff", maps.normals);
  write_image(dir / "visibility.png", maps.visible);
  write_image(dir / "shadow.png", maps.shadow);
  // cv::imwrite cannot write 2-channel images: the (x, y) pair is padded with a zero third channel.
  cv::Mat padded;
  cv::merge(std::vector<cv::Mat>{maps.correspondence, cv::Mat::zeros(maps.correspondence.size(), CV_32FC1)}, padded);
  write_image(dir / "correspondences.tiff", padded);
  write_image(dir / "object_id.png", maps.object_id);
  write_truth_points(dir / "points.ply", maps);
  nlohmann::ordered_json json{
      {"format", "rfrecon-truth-objects"}, {"version", 1}, {"objects", nlohmann::json::array()}};
  for (const auto& object : objects) {
    json["objects"].push_back({{"label", object.label},
                               {"name", object.name},
                               {"shape", object.shape},
                               {"size_mm", object.size_mm},
                               {"size_rule", object.size_rule}});
  }
  write_file_atomically(dir / kObjectsFile, json.dump(2) + "\n");
}

TruthView read_truth(const fs::path& dir) {
  TruthView view;
  view.dir = locate_truth(dir);
  view.maps.depth_mm = read_image(view.dir / "depth.tiff", CV_32FC1);
  view.maps.normals = read_image(view.dir / "normals.tiff", CV_32FC3);
  view.maps.object_id = read_image(view.dir / "object_id.png", CV_16UC1);
  for (const auto& [map, name] :
       {std::pair{&view.maps.normals, "normals.tiff"}, std::pair{&view.maps.object_id, "object_id.png"}}) {
    if (map->size() != view.maps.depth_mm.size()) {
      throw InputError((view.dir / name).string() + ": " + size_text(map->size()) + ", expected " +
                       size_text(view.maps.depth_mm.size()) + " (the size of depth.tiff)");
    }
  }
  view.objects = read_objects(view.dir / kObjectsFile);
  return view;
}

}  // namespace rfrecon::truth
