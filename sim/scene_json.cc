// Scene JSON: parsing with validation errors that name the field path, and serialisation of the resolved scene.
#include <algorithm>
#include <cmath>
#include <set>

#include "host/capture/pattern_family.h"
#include "host/core/errors.h"
#include "host/core/json_file.h"
#include "host/core/message_text.h"
#include "sim/builtin_rigs.h"
#include "sim/scene.h"

namespace rfrecon::sim {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Reads fields of one JSON document, naming the source and the field path in every error.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  // `path` holds keys of the file, so it is quoted cut to a readable length.
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + excerpt(path, 2 * kMaxQuotedChars) + ": " + what);
  }

  [[noreturn]] void fail(const std::string& message) const { throw InputError(source_ + ": " + message); }

  void check_keys(const json& object, const std::string& path, const std::set<std::string>& allowed) const {
    if (!object.is_object()) fail(path.empty() ? "(top level)" : path, "must be a JSON object");
    for (const auto& item : object.items()) {
      if (allowed.count(item.key()) == 0) fail(join(path, item.key()), "unknown field");
    }
  }

  template <typename T>
  T get(const json& object, const std::string& path, const std::string& key, const T& fallback) const {
    if (!object.contains(key)) return fallback;
    return get<T>(object, path, key);
  }

  template <typename T>
  T get(const json& object, const std::string& path, const std::string& key) const {
    if (!object.contains(key)) fail(join(path, key), "missing");
    std::string problem;
    auto value = json_as<T>(object.at(key), problem);
    if (!value) fail(join(path, key), "must be " + problem);
    return std::move(*value);
  }

  std::vector<double> numbers(const json& object, const std::string& path, const std::string& key,
                              std::size_t count) const {
    auto values = get<std::vector<double>>(object, path, key);
    if (values.size() != count) fail(join(path, key), "must hold " + std::to_string(count) + " numbers");
    for (const double v : values) {
      if (!std::isfinite(v)) fail(join(path, key), "must be finite");
    }
    return values;
  }

  double positive(const json& object, const std::string& path, const std::string& key, double fallback) const {
    const double value = get<double>(object, path, key, fallback);
    if (!(value > 0.0) || !std::isfinite(value)) fail(join(path, key), "must be > 0");
    return value;
  }

  double non_negative(const json& object, const std::string& path, const std::string& key, double fallback) const {
    const double value = get<double>(object, path, key, fallback);
    if (!(value >= 0.0) || !std::isfinite(value)) fail(join(path, key), "must be >= 0");
    return value;
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string source_;
};

Eigen::Vector3d vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

// position + one of rotation_deg (R = Rz Ry Rx), rotation_matrix (row-major 9) or look_at (+ up, default -y).
Eigen::Isometry3d parse_pose(const Reader& r, const json& pose, const std::string& path) {
  r.check_keys(pose, path, {"position", "rotation_deg", "rotation_matrix", "look_at", "up"});
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = vec3(r.numbers(pose, path, "position", 3));
  const int rotations = static_cast<int>(pose.contains("rotation_deg")) +
                        static_cast<int>(pose.contains("rotation_matrix")) + static_cast<int>(pose.contains("look_at"));
  if (rotations > 1) r.fail(path, "give only one of rotation_deg, rotation_matrix, look_at");
  if (pose.contains("rotation_deg")) {
    const auto deg = r.numbers(pose, path, "rotation_deg", 3);
    out.linear() = (Eigen::AngleAxisd(deg[2] * EIGEN_PI / 180, Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(deg[1] * EIGEN_PI / 180, Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(deg[0] * EIGEN_PI / 180, Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
  } else if (pose.contains("rotation_matrix")) {
    const auto m = r.numbers(pose, path, "rotation_matrix", 9);
    const Eigen::Matrix3d rotation = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.data());
    if (!(rotation.transpose() * rotation).isIdentity(1e-6) || rotation.determinant() < 0) {
      r.fail(Reader::join(path, "rotation_matrix"), "must be a rotation (orthonormal, determinant +1)");
    }
    out.linear() = rotation;
  } else if (pose.contains("look_at")) {
    const Eigen::Vector3d target = vec3(r.numbers(pose, path, "look_at", 3));
    const Eigen::Vector3d up = pose.contains("up") ? vec3(r.numbers(pose, path, "up", 3)) : -Eigen::Vector3d::UnitY();
    const Eigen::Vector3d z = (target - out.translation()).normalized();
    const Eigen::Vector3d x = z.cross(up);
    if (!((target - out.translation()).norm() > 0) || x.norm() < 1e-9) {
      r.fail(Reader::join(path, "look_at"), "must differ from position and not be along 'up'");
    }
    out.linear().col(0) = x.normalized();
    out.linear().col(1) = z.cross(x.normalized());
    out.linear().col(2) = z;
  }
  return out;
}

json pose_to_json(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> m = pose.linear();
  return {{"position", {pose.translation().x(), pose.translation().y(), pose.translation().z()}},
          {"rotation_matrix", std::vector<double>(m.data(), m.data() + 9)}};
}

Device parse_device(const Reader& r, const json& j, const std::string& path, bool has_pose) {
  std::set<std::string> keys{"size", "focal", "principal_point", "distortion"};
  if (has_pose) keys.insert("pose");
  r.check_keys(j, path, keys);
  Device d;
  const auto size = r.get<std::vector<int>>(j, path, "size");
  if (size.size() != 2 || size[0] <= 0 || size[1] <= 0 || size[0] > kMaxSimulatedSide || size[1] > kMaxSimulatedSide) {
    r.fail(Reader::join(path, "size"),
           "must be [width, height] with both in [1, " + std::to_string(kMaxSimulatedSide) + "]");
  }
  d.size = {size[0], size[1]};
  const auto focal = r.numbers(j, path, "focal", 2);
  if (!(focal[0] > 0 && focal[1] > 0)) r.fail(Reader::join(path, "focal"), "must be > 0");
  d.fx = focal[0];
  d.fy = focal[1];
  const auto pp = j.contains("principal_point") ? r.numbers(j, path, "principal_point", 2)
                                                : std::vector<double>{(size[0] - 1) / 2.0, (size[1] - 1) / 2.0};
  d.cx = pp[0];
  d.cy = pp[1];
  if (j.contains("distortion")) {
    const auto k = r.numbers(j, path, "distortion", 5);
    std::copy(k.begin(), k.end(), d.distortion.begin());
  }
  if (has_pose) {
    if (!j.contains("pose")) r.fail(Reader::join(path, "pose"), "missing");
    d.device_from_world = parse_pose(r, j.at("pose"), Reader::join(path, "pose")).inverse();
  }
  return d;
}

json device_to_json(const Device& d, bool with_pose) {
  json j{{"size", {d.size.width, d.size.height}},
         {"focal", {d.fx, d.fy}},
         {"principal_point", {d.cx, d.cy}},
         {"distortion", d.distortion}};
  if (with_pose) j["pose"] = pose_to_json(d.device_from_world.inverse());
  return j;
}

Brdf parse_material(const Reader& r, const json& j, const std::string& path) {
  r.check_keys(j, path, {"brdf", "diffuse", "specular", "exponent", "alpha_x", "alpha_y", "n_u", "n_v"});
  Brdf b;
  try {
    b.model = brdf_model_from_string(r.get<std::string>(j, path, "brdf"));
  } catch (const InputError& error) {
    r.fail(Reader::join(path, "brdf"), excerpt(error.what(), 2 * kMaxQuotedChars));
  }
  b.diffuse = r.get<double>(j, path, "diffuse", b.diffuse);
  b.specular = r.get<double>(j, path, "specular", b.specular);
  b.exponent = r.get<double>(j, path, "exponent", b.exponent);
  b.alpha_x = r.get<double>(j, path, "alpha_x", b.alpha_x);
  b.alpha_y = r.get<double>(j, path, "alpha_y", b.alpha_y);
  b.n_u = r.get<double>(j, path, "n_u", b.n_u);
  b.n_v = r.get<double>(j, path, "n_v", b.n_v);
  try {
    validate(b, path);
  } catch (const InputError& error) {
    r.fail(error.what());
  }
  return b;
}

json material_to_json(const Brdf& b) {
  return {{"brdf", to_string(b.model)}, {"diffuse", b.diffuse}, {"specular", b.specular}, {"exponent", b.exponent},
          {"alpha_x", b.alpha_x},       {"alpha_y", b.alpha_y}, {"n_u", b.n_u},           {"n_v", b.n_v}};
}

Checkerboard parse_checkerboard(const Reader& r, const json& j, const std::string& path) {
  r.check_keys(j, path, {"squares", "square_size", "dark_albedo", "light_albedo"});
  Checkerboard c;
  const auto squares = r.get<std::vector<int>>(j, path, "squares");
  if (squares.size() != 2 || squares[0] < 3 || squares[1] < 3) {
    r.fail(Reader::join(path, "squares"), "must be [nx, ny] with both >= 3");
  }
  c.squares_x = squares[0];
  c.squares_y = squares[1];
  c.square_size = r.positive(j, path, "square_size", c.square_size);
  c.dark_albedo = r.non_negative(j, path, "dark_albedo", c.dark_albedo);
  c.light_albedo = r.non_negative(j, path, "light_albedo", c.light_albedo);
  if (c.dark_albedo > 1.0 || c.light_albedo > 1.0) r.fail(path, "albedos must be in [0, 1]");
  return c;
}

ShapeKind shape_from_string(const Reader& r, const std::string& name, const std::string& path) {
  for (const auto kind : {ShapeKind::kPlane, ShapeKind::kBox, ShapeKind::kSphere, ShapeKind::kCylinder,
                          ShapeKind::kMesh, ShapeKind::kBowl}) {
    if (name == to_string(kind)) return kind;
  }
  r.fail(path, "unknown shape '" + excerpt(name) + "' (expected plane, box, sphere, cylinder, bowl or mesh)");
}

Object parse_object(const Reader& r, const json& j, const std::string& path, std::size_t index,
                    const fs::path& base_dir) {
  r.check_keys(j, path, {"name", "shape", "size", "pose", "material", "tangent", "checkerboard", "file", "scale"});
  Object o;
  o.name = r.get<std::string>(j, path, "name", "object" + std::to_string(index));
  o.kind = shape_from_string(r, r.get<std::string>(j, path, "shape"), Reader::join(path, "shape"));
  const std::string size_path = Reader::join(path, "size");
  const std::size_t size_count[] = {2, 3, 1, 2, 0, 2};
  const std::size_t count = size_count[static_cast<int>(o.kind)];
  if (count > 0) {
    if (o.kind == ShapeKind::kPlane && !j.contains("size")) {
      o.size = {0.0, 0.0};
    } else {
      o.size = r.numbers(j, path, "size", count);
    }
    for (const double s : o.size) {
      if (o.kind == ShapeKind::kPlane ? !(s >= 0.0) : !(s > 0.0)) {
        r.fail(size_path, o.kind == ShapeKind::kPlane ? "must be >= 0 (0 = infinite)" : "must be > 0");
      }
    }
    if (o.kind == ShapeKind::kPlane && (o.size[0] == 0.0) != (o.size[1] == 0.0)) {
      r.fail(size_path, "give both sides > 0, or both 0 for an infinite plane");
    }
    if (o.kind == ShapeKind::kBowl && o.size[1] > 2.0 * o.size[0]) {
      r.fail(size_path, "a bowl's depth must be at most its diameter");
    }
  } else if (j.contains("size")) {
    r.fail(size_path, "meshes take 'scale', not 'size'");
  }
  if (!j.contains("pose")) r.fail(Reader::join(path, "pose"), "missing");
  o.world_from_object = parse_pose(r, j.at("pose"), Reader::join(path, "pose"));
  if (!(o.world_from_object.translation().z() > 0.0)) {
    r.fail(Reader::join(path, "pose.position"),
           "object is behind the camera (z = " + std::to_string(o.world_from_object.translation().z()) +
               " mm; the camera looks along +z, z must be > 0)");
  }
  if (!j.contains("material")) r.fail(Reader::join(path, "material"), "missing");
  o.material = parse_material(r, j.at("material"), Reader::join(path, "material"));
  if (j.contains("tangent")) {
    o.tangent_object = vec3(r.numbers(j, path, "tangent", 3));
    if (o.tangent_object.norm() < 1e-9) r.fail(Reader::join(path, "tangent"), "must be non-zero");
    o.tangent_object.normalize();
  }
  if (j.contains("checkerboard")) {
    if (o.kind != ShapeKind::kPlane) r.fail(Reader::join(path, "checkerboard"), "only planes can have one");
    o.checkerboard = parse_checkerboard(r, j.at("checkerboard"), Reader::join(path, "checkerboard"));
  }
  if (o.kind == ShapeKind::kMesh) {
    const fs::path file = r.get<std::string>(j, path, "file");
    o.mesh_file = fs::absolute(file.is_absolute() ? file : base_dir / file).lexically_normal().string();
    o.mesh_scale = r.positive(j, path, "scale", 1.0);
    o.mesh = load_mesh(o.mesh_file, o.mesh_scale, Reader::join(path, "file"));
  } else if (j.contains("file") || j.contains("scale")) {
    r.fail(Reader::join(path, "file"), "only meshes load a file");
  }
  return o;
}

json object_to_json(const Object& o) {
  json j{{"name", o.name},
         {"shape", to_string(o.kind)},
         {"pose", pose_to_json(o.world_from_object)},
         {"material", material_to_json(o.material)},
         {"tangent", {o.tangent_object.x(), o.tangent_object.y(), o.tangent_object.z()}}};
  if (o.kind != ShapeKind::kMesh) j["size"] = o.size;
  if (o.kind == ShapeKind::kMesh) {
    j["file"] = o.mesh_file;
    j["scale"] = o.mesh_scale;
  }
  if (o.checkerboard) {
    const auto& c = *o.checkerboard;
    j["checkerboard"] = {{"squares", {c.squares_x, c.squares_y}},
                         {"square_size", c.square_size},
                         {"dark_albedo", c.dark_albedo},
                         {"light_albedo", c.light_albedo}};
  }
  return j;
}

CaptureSettings parse_capture(const Reader& r, const json& j, const std::string& path) {
  r.check_keys(j, path,
               {"family", "parameters", "dot_spacing", "bit_depth", "black_level", "response_gamma", "ambient",
                "full_well_electrons", "read_noise_dn", "format"});
  CaptureSettings c;
  c.family = r.get<std::string>(j, path, "family", c.family);
  const auto families = capture::pattern_family_names();
  if (std::find(families.begin(), families.end(), c.family) == families.end()) {
    std::string names;
    for (const auto& name : families) names += (names.empty() ? "" : ", ") + name;
    r.fail(Reader::join(path, "family"), "must be a pattern family (" + names + ")");
  }
  if (j.contains("parameters")) {
    const json& parameters = j.at("parameters");
    if (!parameters.is_object()) r.fail(Reader::join(path, "parameters"), "must be a JSON object");
    for (const auto& item : parameters.items()) {
      c.parameters[item.key()] = r.get<int>(parameters, Reader::join(path, "parameters"), item.key());
    }
    try {
      capture::check_family_parameters(capture::pattern_family(c.family), c.parameters, "parameters");
    } catch (const InputError& error) {
      r.fail(Reader::join(path, "parameters"), error.what());
    }
  }
  c.dot_spacing = r.get<int>(j, path, "dot_spacing", c.dot_spacing);
  if (c.dot_spacing < 0 || c.dot_spacing == 1) r.fail(Reader::join(path, "dot_spacing"), "must be 0 or >= 2");
  c.bit_depth = r.get<int>(j, path, "bit_depth", c.bit_depth);
  if (c.bit_depth != 8 && c.bit_depth != 10 && c.bit_depth != 12 && c.bit_depth != 16) {
    r.fail(Reader::join(path, "bit_depth"), "must be 8, 10, 12 or 16");
  }
  c.black_level = r.non_negative(j, path, "black_level", c.black_level);
  if (c.black_level >= std::ldexp(1.0, c.bit_depth) - 1.0) {
    r.fail(Reader::join(path, "black_level"), "must be below the full scale 2^bit_depth - 1");
  }
  c.response_gamma = r.positive(j, path, "response_gamma", c.response_gamma);
  c.ambient = r.non_negative(j, path, "ambient", c.ambient);
  c.full_well_electrons = r.non_negative(j, path, "full_well_electrons", c.full_well_electrons);
  c.read_noise_dn = r.non_negative(j, path, "read_noise_dn", c.read_noise_dn);
  c.format = r.get<std::string>(j, path, "format", c.format);
  if (c.format != "png" && c.format != "tiff") r.fail(Reader::join(path, "format"), "must be \"png\" or \"tiff\"");
  return c;
}

RenderOptions parse_render(const Reader& r, const json& j, const std::string& path) {
  r.check_keys(
      j, path,
      {"supersample", "jitter", "interreflection_samples", "projector_defocus_px", "camera_defocus_px", "seed"});
  RenderOptions o;
  o.supersample = r.get<int>(j, path, "supersample", o.supersample);
  if (o.supersample < 1 || o.supersample > 32) r.fail(Reader::join(path, "supersample"), "must be in [1, 32]");
  o.jitter = r.get<bool>(j, path, "jitter", o.jitter);
  o.interreflection_samples = r.get<int>(j, path, "interreflection_samples", o.interreflection_samples);
  if (o.interreflection_samples < 0) r.fail(Reader::join(path, "interreflection_samples"), "must be >= 0");
  o.projector_defocus_px = r.non_negative(j, path, "projector_defocus_px", o.projector_defocus_px);
  o.camera_defocus_px = r.non_negative(j, path, "camera_defocus_px", o.camera_defocus_px);
  o.seed = r.get<unsigned long long>(j, path, "seed", o.seed);
  return o;
}
}  // namespace

Scene scene_from_json(const json& root, const std::string& source, const fs::path& base_dir) {
  const Reader r(source);
  r.check_keys(root, "", {"name", "rig", "camera", "projector", "radiometry", "capture", "render", "objects", "views"});
  Scene scene;
  scene.name = r.get<std::string>(root, "", "name", "scene");
  json devices = root;
  if (root.contains("rig")) {
    if (root.contains("camera") || root.contains("projector")) r.fail("rig", "give either rig or camera and projector");
    const auto rig = r.get<std::string>(root, "", "rig");
    try {
      devices = builtin_rig(rig);
    } catch (const InputError& error) {
      r.fail("rig", excerpt(error.what(), 2 * kMaxQuotedChars));
    }
  }
  if (!devices.contains("camera")) r.fail("camera", "missing (or name a built-in rig with 'rig')");
  scene.camera = parse_device(r, devices.at("camera"), "camera", false);
  if (!devices.contains("projector")) r.fail("projector", "missing");
  scene.projector = parse_device(r, devices.at("projector"), "projector", true);
  if (root.contains("radiometry")) {
    const json& j = root.at("radiometry");
    r.check_keys(j, "radiometry", {"gain", "intensity"});
    scene.gain = r.positive(j, "radiometry", "gain", scene.gain);
    scene.intensity = r.positive(j, "radiometry", "intensity", scene.intensity);
  }
  if (root.contains("capture")) scene.capture = parse_capture(r, root.at("capture"), "capture");
  if (root.contains("render")) scene.render = parse_render(r, root.at("render"), "render");
  const json objects = r.get<json>(root, "", "objects");
  if (!objects.is_array() || objects.empty()) r.fail("objects", "must be a non-empty array");
  for (std::size_t i = 0; i < objects.size(); ++i) {
    scene.objects.push_back(parse_object(r, objects[i], "objects[" + std::to_string(i) + "]", i, base_dir));
  }
  if (root.contains("views")) {
    const json views = r.get<json>(root, "", "views");
    if (!views.is_array() || views.empty()) r.fail("views", "must be a non-empty array");
    for (std::size_t v = 0; v < views.size(); ++v) {
      const std::string path = "views[" + std::to_string(v) + "]";
      if (!views[v].is_object()) r.fail(path, "must map object names to poses");
      std::map<std::string, Eigen::Isometry3d> view;
      for (const auto& item : views[v].items()) {
        const bool known = std::any_of(scene.objects.begin(), scene.objects.end(),
                                       [&](const Object& o) { return o.name == item.key(); });
        if (!known) r.fail(Reader::join(path, item.key()), "no object has this name");
        view[item.key()] = parse_pose(r, item.value(), Reader::join(path, item.key()));
        if (!(view[item.key()].translation().z() > 0.0)) {
          r.fail(Reader::join(path, item.key()) + ".position", "object is behind the camera (z must be > 0)");
        }
      }
      scene.views.push_back(std::move(view));
    }
  }
  return scene;
}

Scene load_scene_file(const fs::path& file) {
  return scene_from_json(read_json_file(file), file.string(), file.parent_path());
}

json scene_to_json(const Scene& scene) {
  const auto& c = scene.capture;
  const auto& o = scene.render;
  json root{{"name", scene.name},
            {"camera", device_to_json(scene.camera, false)},
            {"projector", device_to_json(scene.projector, true)},
            {"radiometry", {{"gain", scene.gain}, {"intensity", scene.intensity}}},
            {"capture",
             {{"family", c.family},
              {"parameters", c.parameters},
              {"dot_spacing", c.dot_spacing},
              {"bit_depth", c.bit_depth},
              {"black_level", c.black_level},
              {"response_gamma", c.response_gamma},
              {"ambient", c.ambient},
              {"full_well_electrons", c.full_well_electrons},
              {"read_noise_dn", c.read_noise_dn},
              {"format", c.format}}},
            {"render",
             {{"supersample", o.supersample},
              {"jitter", o.jitter},
              {"interreflection_samples", o.interreflection_samples},
              {"projector_defocus_px", o.projector_defocus_px},
              {"camera_defocus_px", o.camera_defocus_px},
              {"seed", o.seed}}},
            {"objects", json::array()}};
  for (const auto& object : scene.objects) root["objects"].push_back(object_to_json(object));
  if (!scene.views.empty()) {
    root["views"] = json::array();
    for (const auto& view : scene.views) {
      json j = json::object();
      for (const auto& [name, pose] : view) j[name] = pose_to_json(pose);
      root["views"].push_back(j);
    }
  }
  return root;
}

Scene scene_for_view(const Scene& scene, std::size_t view) {
  Scene out = scene;
  out.views.clear();
  for (auto& object : out.objects) {
    const auto found = scene.views.at(view).find(object.name);
    if (found != scene.views.at(view).end()) object.world_from_object = found->second;
  }
  return out;
}

Scene swap_devices(const Scene& scene) {
  Scene out = scene;
  const Eigen::Isometry3d proj_from_cam = scene.projector.device_from_world;
  out.camera = scene.projector;
  out.camera.device_from_world = Eigen::Isometry3d::Identity();
  out.projector = scene.camera;
  out.projector.device_from_world = proj_from_cam.inverse();
  for (auto& object : out.objects) object.world_from_object = proj_from_cam * object.world_from_object;
  for (auto& view : out.views) {
    for (auto& [name, pose] : view) pose = proj_from_cam * pose;
  }
  return out;
}

void resize_device(Device& device, cv::Size size) {
  if (size.width < 1 || size.height < 1 || size.width > kMaxSimulatedSide || size.height > kMaxSimulatedSide) {
    throw InputError("a simulated device's size must be in [1, " + std::to_string(kMaxSimulatedSide) +
                     "] a side, got " + std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  const double sx = static_cast<double>(size.width) / device.size.width;
  const double sy = static_cast<double>(size.height) / device.size.height;
  device.fx *= sx;
  device.fy *= sx;
  device.cx = (device.cx + 0.5) * sx - 0.5;
  device.cy = (device.cy + 0.5) * sy - 0.5;
  device.size = size;
}

}  // namespace rfrecon::sim
