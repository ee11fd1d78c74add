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

// The truth folder of `dir`: dir itself when it holds depth.tiff, else dir/truth. A depth.tiff that is not a
// regular file still names the folder: its reader then says what it is.
fs::path locate_truth(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir / "depth.tiff", ec)) return dir;
  if (fs::exists(dir / "truth" / "depth.tiff", ec)) return dir / "truth";
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

// objects[index].key of `file` as T (json_as: an integer out of range is refused, not converted).
template <typename T>
T object_field(const nlohmann::json& entry, const char* key, std::size_t index, const fs::path& file) {
  const std::string where = file.string() + ": objects[" + std::to_string(index) + "]." + key;
  if (!entry.is_object() || !entry.contains(key)) throw InputError(where + ": missing");
  std::string problem;
  auto value = json_as<T>(entry.at(key), problem);
  if (!value) throw InputError(where + ": must be " + problem);
  return std::move(*value);
}

std::vector<TruthObject> read_objects(const fs::path& file) {
  const auto json = read_json_file(file);
  if (!json.is_object() || !json.contains("objects") || !json.at("objects").is_array()) {
    throw InputError(file.string() + ": no \"objects\" array (not the objects.json of `rfrecon simulate`)");
  }
  std::vector<TruthObject> objects;
  const auto& entries = json.at("objects");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    TruthObject object;
    object.label = object_field<int>(entries[i], "label", i, file);
    object.name = object_field<std::string>(entries[i], "name", i, file);
    object.shape = object_field<std::string>(entries[i], "shape", i, file);
    object.size_mm = object_field<double>(entries[i], "size_mm", i, file);
    object.size_rule = object_field<std::string>(entries[i], "size_rule", i, file);
    objects.push_back(std::move(object));
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
