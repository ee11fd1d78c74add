// Built-in scenes, defined as scene JSON so they go through the same validation as scene files.
#include "sim/builtin_scenes.h"

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>

#include "host/capture/pattern_family.h"
#include "host/core/errors.h"
#include "host/core/json_file.h"
#include "host/core/message_text.h"
#include "sim/builtin_rigs.h"

namespace rfrecon::sim {

using nlohmann::json;

namespace {
// Every built-in scene uses the same rig (kDefaultRig unless `--rig` says otherwise), so that a rig calibrated from
// `checkerboard-poses` fits the object scenes, as in the paper, where the same rig captured the boards and the cube.
json lab_rig(json scene) {
  scene["rig"] = kDefaultRig;
  return scene;
}

json wall(double z) {
  return {{"name", "wall"},
          {"shape", "plane"},
          {"pose", {{"position", {0.0, 0.0, z}}}},
          {"material", {{"brdf", "lambert"}, {"diffuse", 0.5}}}};
}

json cube_anisotropic() {
  json scene = lab_rig({{"name", "cube-anisotropic"}});
  scene["radiometry"] = {{"intensity", 2.0e6}};
  scene["objects"] = {
      {{"name", "cube"},
       {"shape", "box"},
       {"size", {60.0, 60.0, 60.0}},
       {"pose", {{"position", {0.0, 0.0, 600.0}}, {"rotation_deg", {25.0, 35.0, 0.0}}}},
       {"material", {{"brdf", "ward"}, {"diffuse", 0.2}, {"specular", 0.5}, {"alpha_x", 0.08}, {"alpha_y", 0.3}}},
       {"tangent", {1.0, 2.0, 3.0}}},
      wall(800.0)};
  return scene;
}

json sphere_ward() {
  json scene = lab_rig({{"name", "sphere-ward"}});
  scene["radiometry"] = {{"intensity", 2.0e6}};
  scene["objects"] = {
      {{"name", "sphere"},
       {"shape", "sphere"},
       {"size", {50.0}},
       {"pose", {{"position", {0.0, 0.0, 600.0}}}},
       {"material", {{"brdf", "ward"}, {"diffuse", 0.3}, {"specular", 0.4}, {"alpha_x", 0.1}, {"alpha_y", 0.25}}},
       {"tangent", {0.0, 1.0, 0.0}}},
      wall(800.0)};
  return scene;
}

json cylinder_brushed() {
  json scene = lab_rig({{"name", "cylinder-brushed"}});
  scene["radiometry"] = {{"intensity", 2.0e6}};
  scene["objects"] = {
      {{"name", "cylinder"},
       {"shape", "cylinder"},
       {"size", {40.0, 120.0}},
       {"pose", {{"position", {0.0, 0.0, 600.0}}, {"rotation_deg", {70.0, 0.0, 0.0}}}},
       {"material",
        {{"brdf", "ashikhmin-shirley"}, {"diffuse", 0.3}, {"specular", 0.4}, {"n_u", 10.0}, {"n_v", 200.0}}},
       {"tangent", {0.0, 0.0, 1.0}}},
      wall(800.0)};
  return scene;
}

// A concave scene, which lights itself: one bounce of interreflection, 16 cosine-weighted rays per camera sample.
json concave_scene(const char* name) {
  json scene = lab_rig({{"name", name}});
  scene["radiometry"] = {{"intensity", 2.0e6}};
  scene["render"] = {{"interreflection_samples", 16}};
  return scene;
}

json ward_brushed() {
  return {{"brdf", "ward"}, {"diffuse", 0.2}, {"specular", 0.5}, {"alpha_x", 0.08}, {"alpha_y", 0.3}};
}

// A pose of world_from_object rotation `rotation`, as scene JSON's row-major rotation_matrix.
json pose_of(const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation) {
  json matrix = json::array();
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) matrix.push_back(rotation(row, column));
  }
  return {{"position", {position.x(), position.y(), position.z()}}, {"rotation_matrix", matrix}};
}

// A 90-degree groove along y, its bottom line 620 mm away: two 60 x 90 mm faces of brushed metal (brushed across the
// groove), each 45 degrees to the line of sight, so that each face sees the other.
json v_groove() {
  json scene = concave_scene("v-groove-ward");
  const double half = 30.0 * std::sqrt(0.5);  // half a face's width, along x and along z
  for (const int side : {-1, 1}) {
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(side * EIGEN_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
    scene["objects"].push_back({{"name", side < 0 ? "left face" : "right face"},
                                {"shape", "plane"},
                                {"size", {60.0, 90.0}},
                                {"pose", pose_of({side * half, 0.0, 620.0 - half}, rotation)},
                                {"material", ward_brushed()},
                                {"tangent", {1.0, 0.0, 0.0}}});
  }
  scene["objects"].push_back(wall(800.0));
  return scene;
}

// The inside corner of a box: three mutually perpendicular 70 x 70 mm faces meeting 650 mm away, the corner's diagonal
// along the line of sight (turned 15 degrees about it), brushed (Ashikhmin-Shirley) along each face's first edge.
json inside_corner() {
  json scene = concave_scene("corner-brushed");
  const Eigen::Matrix3d corner_frame =
      (Eigen::AngleAxisd(EIGEN_PI / 12, Eigen::Vector3d::UnitZ()) *
       Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::Ones().normalized(), -Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  const Eigen::Vector3d corner(0.0, 0.0, 650.0);
  const double side = 70.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = corner_frame.col((k + 1) % 3), v = corner_frame.col((k + 2) % 3);
    Eigen::Matrix3d rotation;
    rotation << u, v, u.cross(v);
    scene["objects"].push_back(
        {{"name", "face " + std::to_string(k + 1)},
         {"shape", "plane"},
         {"size", {side, side}},
         {"pose", pose_of(corner + 0.5 * side * (u + v), rotation)},
         {"material",
          {{"brdf", "ashikhmin-shirley"}, {"diffuse", 0.3}, {"specular", 0.4}, {"n_u", 10.0}, {"n_v", 200.0}}},
         {"tangent", {1.0, 0.0, 0.0}}});
  }
  scene["objects"].push_back(wall(800.0));
  return scene;
}

// A hemispherical bowl of 60 mm radius and 45 mm depth, open towards the camera, its bottom 660 mm away, tilted 20
// degrees about x so that the projector above sees into it; Ward anisotropic.
json bowl() {
  json scene = concave_scene("bowl-ward");
  scene["objects"] = {
      {{"name", "bowl"},
       {"shape", "bowl"},
       {"size", {60.0, 45.0}},
       {"pose", {{"position", {0.0, 0.0, 600.0}}, {"rotation_deg", {160.0, 0.0, 0.0}}}},
       {"material", {{"brdf", "ward"}, {"diffuse", 0.3}, {"specular", 0.4}, {"alpha_x", 0.1}, {"alpha_y", 0.25}}},
       {"tangent", {1.0, 0.0, 0.0}}},
      wall(800.0)};
  return scene;
}

json plane_lambert() {
  json scene = lab_rig({{"name", "plane-lambert"}});
  scene["objects"] = {{{"name", "plane"},
                       {"shape", "plane"},
                       {"size", {400.0, 300.0}},
                       {"pose", {{"position", {0.0, 0.0, 600.0}}, {"rotation_deg", {0.0, 20.0, 0.0}}}},
                       {"material", {{"brdf", "lambert"}, {"diffuse", 0.6}}}}};
  return scene;
}

// A 15 x 10-square board (14 x 9 inner corners, 20 mm squares: 126 corners, where a 9 x 6 board of 30 mm squares
// over about the same area has 54) at 16 poses as docs/calibration.md asks of a user:
// tilted by 29 to 45 degrees from the camera's line of sight about different axes (normals spanning 89 degrees), at
// 530 to 720 mm, placed so that the printed patterns cover 67% of the camera image and 98% of the projector's (in
// calibrate's coverage grid; the poses were chosen by a search over random poses that keeps every board inside both
// images of the default and side-by-side rigs).
// Seen by a camera and a projector with mild lens distortion and an off-centre projector principal point, as a real
// calibration would face. The capture includes the dot grid, so the dual images T^T 1 are built from full transport
// rows (as in dual photography), not from Gray code alone. Each ray carries the board's albedo averaged over its
// cell (sim/objects.h), as a sensor integrates it: point samples would alias the square edges to the rays' lattice.
json checkerboard_poses() {
  json scene = lab_rig({{"name", "checkerboard-poses"}});
  scene["radiometry"] = {{"intensity", 8.0e5}};
  scene["capture"] = {{"dot_spacing", 8}};
  scene["objects"] = {{{"name", "board"},
                       {"shape", "plane"},
                       {"size", {360.0, 270.0}},
                       {"pose", {{"position", {0.0, 0.0, 600.0}}}},
                       {"material", {{"brdf", "lambert"}, {"diffuse", 0.8}}},
                       {"checkerboard", {{"squares", {15, 10}}, {"square_size", 20.0}}}}};
  // x, y, z (mm), then rotation about x, y, z (degrees).
  const double poses[16][6] = {{9, -24, 534, -14, -24, 1},   {0, 75, 652, -43, 5, -6},     {22, -63, 537, -30, -3, 3},
                               {-60, -18, 591, -8, -40, 7},  {46, 5, 567, 13, 34, 1},      {66, -34, 672, -8, 33, -5},
                               {-80, 29, 633, -29, -34, 7},  {-119, -44, 708, 21, 19, 3},  {-77, 56, 663, -14, 19, -15},
                               {-25, -18, 575, -17, -42, 8}, {-90, 82, 719, -37, -42, 12}, {-57, -44, 683, -37, 9, 9},
                               {4, 21, 692, -6, 35, 5},      {60, 16, 643, 1, 42, -11},    {-7, 19, 645, 17, 35, -10},
                               {-107, -6, 690, 24, 15, 14}};
  scene["views"] = json::array();
  for (const auto& p : poses) {
    scene["views"].push_back({{"board", {{"position", {p[0], p[1], p[2]}}, {"rotation_deg", {p[3], p[4], p[5]}}}}});
  }
  return scene;
}

// A coarser board (10 x 7 squares of 30 mm, on the calibration board's plate) alone at a pose none of
// checkerboard-poses has, for flatness and scale checks of a rig: its wide squares leave most pixels away from edges.
json board_plane() {
  json scene = checkerboard_poses();
  scene["name"] = "board-plane";
  scene.erase("views");
  scene["objects"][0]["checkerboard"] = {{"squares", {10, 7}}, {"square_size", 30.0}};
  scene["objects"][0]["pose"] = {{"position", {15.0, 5.0, 620.0}}, {"rotation_deg", {15.0, -20.0, 5.0}}};
  return scene;
}

struct BuiltinScene {
  const char* name;
  const char* description;
  json (*make)();
};

const BuiltinScene kBuiltins[] = {
    {"cube-anisotropic", "60 mm cube at 600 mm, Ward anisotropic brushed metal, three faces visible; wall behind",
     cube_anisotropic},
    {"sphere-ward", "50 mm radius sphere at 600 mm, Ward anisotropic; wall behind", sphere_ward},
    {"cylinder-brushed", "40 mm radius cylinder, brushed along its axis (Ashikhmin-Shirley); wall behind",
     cylinder_brushed},
    {"plane-lambert", "Lambertian plane at 600 mm tilted 20 degrees", plane_lambert},
    {"v-groove-ward", "90-degree groove of two 60 mm faces, Ward brushed metal, with one-bounce interreflection",
     v_groove},
    {"corner-brushed", "inside corner of three 70 mm faces, brushed (Ashikhmin-Shirley), with interreflection",
     inside_corner},
    {"bowl-ward", "60 mm radius bowl, 45 mm deep, Ward anisotropic, with one-bounce interreflection", bowl},
    {"checkerboard-poses", "14x9-corner checkerboard (20 mm squares) at 16 poses, for calibration", checkerboard_poses},
    {"board-plane", "a 9x6-corner checkerboard (30 mm squares) at a pose not among checkerboard-poses, for flatness",
     board_plane},
};

// The built-in scene names, comma-separated, for messages.
std::string known_scenes() {
  std::string known;
  for (const auto& b : kBuiltins) known += known.empty() ? b.name : std::string(", ") + b.name;
  return known;
}

}  // namespace

std::vector<BuiltinSceneInfo> builtin_scenes() {
  std::vector<BuiltinSceneInfo> out;
  for (const auto& b : kBuiltins) out.push_back({b.name, b.description});
  return out;
}

Scene builtin_scene(const std::string& name, const std::string& rig) {
  for (const auto& b : kBuiltins) {
    if (name == b.name)
      return scene_from_json(rig.empty() ? b.make() : with_rig(b.make(), rig), "scene '" + name + "'", {});
  }
  throw InputError("unknown scene '" + excerpt(name) + "' (built-in scenes: " + known_scenes() + ")");
}

Scene resolve_scene(const std::string& name_or_file, const std::string& rig) {
  for (const auto& b : kBuiltins) {
    if (name_or_file == b.name) return builtin_scene(name_or_file, rig);
  }
  std::error_code ec;
  if (std::filesystem::exists(name_or_file, ec)) {  // read_json_file refuses a FIFO or a directory by name
    const std::filesystem::path file(name_or_file);
    const json scene = read_json_file(file);
    return scene_from_json(rig.empty() ? scene : with_rig(scene, rig), file.string(), file.parent_path());
  }
  throw InputError("scene '" + excerpt(name_or_file) + "' is neither a built-in scene (" + known_scenes() +
                   ") nor a scene file");
}

Scene resolve_scene(const std::string& name_or_file, const SceneChanges& changes) {
  Scene scene = resolve_scene(name_or_file, changes.rig);
  if (!changes.camera_size.empty()) resize_device(scene.camera, changes.camera_size);
  if (!changes.projector_size.empty()) resize_device(scene.projector, changes.projector_size);
  if (changes.supersample) scene.render.supersample = *changes.supersample;
  if (changes.interreflection) scene.render.interreflection_samples = *changes.interreflection;
  if (!changes.family.empty()) {
    (void)capture::pattern_family(changes.family);  // InputError listing the families for an unknown one
    scene.capture.family = changes.family;
    if (changes.family != capture::kDefaultFamily) scene.capture.dot_spacing = 0;
    scene.capture.parameters.clear();
  }
  for (const auto& [name, value] : changes.parameters) scene.capture.parameters[name] = value;
  capture::check_family_parameters(capture::pattern_family(scene.capture.family), scene.capture.parameters, "simulate");
  if (changes.dot_spacing) {
    if (*changes.dot_spacing == 1) throw InputError("--dot-spacing must be 0 (no dot grid) or at least 2");
    scene.capture.dot_spacing = *changes.dot_spacing;
  }
  if (changes.seed) scene.render.seed = *changes.seed;
  if (!changes.format.empty()) scene.capture.format = changes.format;
  return scene;
}

std::vector<std::filesystem::path> scene_files(const std::string& name_or_file) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(name_or_file, ec)) return {name_or_file};
  return {};
}

}  // namespace rfrecon::sim
