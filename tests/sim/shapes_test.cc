// Geometry of the analytic shapes and meshes as rendered: surface points lie on the shape, normals are the shape's,
// a bowl is seen from inside, a triangle mesh of a box renders like the box, and one-bounce interreflection adds light
// only where surfaces see each other, as it does in the built-in concave scenes.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "sim/builtin_scenes.h"
#include "sim/render.h"
#include "tests/common/temp_dir.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon::sim {
namespace {

namespace fs = std::filesystem;
using testing::kLambert;
using testing::make_scene;
using testing::small_rig;

nlohmann::json object(const std::string& shape, std::vector<double> size, std::vector<double> position,
                      std::vector<double> rotation_deg) {
  return {{"name", shape},
          {"shape", shape},
          {"size", size},
          {"pose", {{"position", position}, {"rotation_deg", rotation_deg}}},
          {"material", kLambert}};
}

TEST(ShapesTest, SurfacePointsAndNormalsBelongToTheShape) {
  // Truth points are stored as float32 (~3e-5 mm at 600 mm): 1e-3 mm and 1e-4 on normals bound the storage error.
  const Scene sphere = make_scene(small_rig({object("sphere", {50.0}, {10.0, -5.0, 600.0}, {0, 0, 0})}));
  const auto s = render_transport(sphere, {1}).truth;
  const Eigen::Vector3d centre(10.0, -5.0, 600.0);
  int count = 0;
  for (int i = 0; i < s.points_mm.rows * s.points_mm.cols; ++i) {
    const cv::Vec3f p = s.points_mm.at<cv::Vec3f>(i), n = s.normals.at<cv::Vec3f>(i);
    if (!std::isfinite(p[0])) continue;
    const Eigen::Vector3d X(p[0], p[1], p[2]);
    EXPECT_NEAR((X - centre).norm(), 50.0, 1e-3);
    EXPECT_NEAR(((X - centre) / 50.0 - Eigen::Vector3d(n[0], n[1], n[2])).norm(), 0.0, 1e-4);
    ++count;
  }
  EXPECT_GT(count, 150);  // ~8 px radius at 80x60, f = 100

  // Cylinder along the object z axis, tilted: points on the side are at radius 40 from the axis, normals radial;
  // points on a cap are within the radius and have the axis as normal.
  const Scene cylinder = make_scene(small_rig({object("cylinder", {40.0, 100.0}, {0.0, 0.0, 600.0}, {60, 20, 0})}));
  const auto c = render_transport(cylinder, {1}).truth;
  const Eigen::Isometry3d object_from_world = cylinder.objects[0].world_from_object.inverse();
  count = 0;
  for (int i = 0; i < c.points_mm.rows * c.points_mm.cols; ++i) {
    const cv::Vec3f p = c.points_mm.at<cv::Vec3f>(i), n = c.normals.at<cv::Vec3f>(i);
    if (!std::isfinite(p[0])) continue;
    const Eigen::Vector3d X = object_from_world * Eigen::Vector3d(p[0], p[1], p[2]);
    const Eigen::Vector3d normal = object_from_world.linear() * Eigen::Vector3d(n[0], n[1], n[2]);
    const bool on_cap = std::abs(std::abs(X.z()) - 50.0) < 1e-3;
    if (on_cap) {
      EXPECT_LE(X.head<2>().norm(), 40.0 + 1e-3);
      EXPECT_NEAR(std::abs(normal.z()), 1.0, 1e-4);
    } else {
      EXPECT_NEAR(X.head<2>().norm(), 40.0, 1e-3);
      EXPECT_NEAR((Eigen::Vector3d(X.x(), X.y(), 0).normalized() - normal).norm(), 0.0, 1e-4);
    }
    ++count;
  }
  EXPECT_GT(count, 150);  // ~8 px radius at 80x60, f = 100
}

TEST(ShapesTest, TriangleMeshOfABoxRendersLikeTheBox) {
  // The same 60 mm box as 12 triangles (OBJ, loaded with assimp) and as the analytic box: identical depth wherever
  // both see it (1e-4 mm: two intersection formulas in double, stored as float32) and the same silhouette.
  const rfrecon::testing::TempDir temp("box_mesh");
  const fs::path file = temp.path() / "box.obj";
  {
    std::ofstream obj(file);
    for (int i = 0; i < 8; ++i)
      obj << "v " << (i & 1 ? 30 : -30) << " " << (i & 2 ? 30 : -30) << " " << (i & 4 ? 30 : -30) << "\n";
    for (const char* face : {"1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"})
      obj << "f " << face << "\n";
  }
  const std::vector<double> position{0.0, 0.0, 600.0}, rotation{25.0, 35.0, 0.0};
  auto mesh = object("mesh", {}, position, rotation);
  mesh.erase("size");
  mesh["file"] = file.string();
  const auto from_mesh = render_transport(make_scene(small_rig({mesh})), {1}).truth;
  const auto from_box =
      render_transport(make_scene(small_rig({object("box", {60, 60, 60}, position, rotation)})), {1}).truth;
  int both = 0, differ = 0;
  for (int i = 0; i < from_box.depth_mm.rows * from_box.depth_mm.cols; ++i) {
    const float a = from_mesh.depth_mm.at<float>(i), b = from_box.depth_mm.at<float>(i);
    if (std::isfinite(a) != std::isfinite(b)) ++differ;
    if (std::isfinite(a) && std::isfinite(b)) {
      EXPECT_NEAR(a, b, 1e-4);
      ++both;
    }
  }
  EXPECT_GT(both, 100);
  EXPECT_EQ(differ, 0);
}

TEST(ShapesTest, BowlIsTheInsideOfItsCap) {
  // A 50 mm sphere's cap 30 mm deep, open towards the camera (object +z turned to -z): every seen point lies on the
  // sphere and below the rim (object z <= depth - r = -20), its normal towards the camera; the bottom, 650 mm away,
  // is seen through the opening, 30 mm behind the rim.
  const Scene bowl = make_scene(small_rig({object("bowl", {50.0, 30.0}, {0.0, 0.0, 600.0}, {180, 0, 0})}));
  const auto truth = render_transport(bowl, {1}).truth;
  const Eigen::Vector3d centre(0.0, 0.0, 600.0);
  int count = 0;
  double deepest = 0.0;
  for (int i = 0; i < truth.points_mm.rows * truth.points_mm.cols; ++i) {
    const cv::Vec3f p = truth.points_mm.at<cv::Vec3f>(i), n = truth.normals.at<cv::Vec3f>(i);
    if (!std::isfinite(p[0])) continue;
    const Eigen::Vector3d X(p[0], p[1], p[2]);
    EXPECT_NEAR((X - centre).norm(), 50.0, 1e-3);
    EXPECT_GE(X.z() - centre.z(), 20.0 - 1e-3) << "in front of the rim";  // object z = -(world z - 600)
    EXPECT_LT(Eigen::Vector3d(n[0], n[1], n[2]).dot(X), 0.0) << "the normal faces the camera";
    deepest = std::max(deepest, X.z());
    ++count;
  }
  EXPECT_GT(count, 100);
  EXPECT_NEAR(deepest, 650.0, 0.5);
}

TEST(ShapesTest, InterreflectionOnlyWhereSurfacesSeeEachOther) {
  // A lone plane cannot light itself: T is identical with and without interreflection. In a concave corner of two
  // planes, light can only be added (every row sum >= its direct value) and some pixels gain.
  const auto plane = object("plane", {300.0, 300.0}, {0.0, 0.0, 600.0}, {0, 20, 0});
  auto lone = small_rig({plane});
  const auto direct = render_transport(make_scene(lone)).T;
  lone["render"] = {{"interreflection_samples", 4}};
  const auto with_bounce = render_transport(make_scene(lone)).T;
  EXPECT_EQ(0.0, (Eigen::SparseMatrix<float>(direct) - Eigen::SparseMatrix<float>(with_bounce)).norm());

  auto left = object("plane", {300.0, 300.0}, {-40.0, 0.0, 620.0}, {0, 45, 0});
  left["name"] = "left";
  auto right = object("plane", {300.0, 300.0}, {40.0, 0.0, 620.0}, {0, -45, 0});
  right["name"] = "right";
  auto corner = small_rig({left, right});
  const auto corner_direct = render_transport(make_scene(corner)).T;
  corner["render"] = {{"interreflection_samples", 4}};
  const auto corner_bounce = render_transport(make_scene(corner)).T;
  const Eigen::VectorXf ones = Eigen::VectorXf::Ones(corner_direct.cols());
  const Eigen::VectorXf a = corner_direct * ones, b = corner_bounce * ones;
  EXPECT_TRUE(((b - a).array() >= -1e-6f * a.array()).all());
  EXPECT_GT((b - a).maxCoeff(), 0.01f * a.maxCoeff());
}

TEST(ShapesTest, ConcaveBuiltinScenesLightThemselves) {
  // Each concave scene renders its interreflection by default, and there it adds light (at 64 x 51 pixels, one ray
  // per pixel): the concave object's pixels (not the wall's) gain at least 5 % in all, and no pixel loses any.
  for (const char* name : {"v-groove-ward", "corner-brushed", "bowl-ward"}) {
    SceneChanges changes;
    changes.camera_size = {64, 51};
    changes.supersample = 1;
    const Scene scene = resolve_scene(name, changes);
    ASSERT_GT(scene.render.interreflection_samples, 0) << name;
    const auto bounce = render_transport(scene);
    changes.interreflection = 0;  // simulate --interreflection 0
    const Scene without = resolve_scene(name, changes);
    ASSERT_EQ(without.render.interreflection_samples, 0) << name;
    const auto direct = render_transport(without).T;
    const Eigen::VectorXf ones = Eigen::VectorXf::Ones(direct.cols());
    const Eigen::VectorXf a = direct * ones, b = bounce.T * ones;
    EXPECT_TRUE(((b - a).array() >= -1e-6f * a.array()).all()) << name;
    const auto wall = static_cast<std::uint16_t>(scene.objects.size());  // the last object, labelled from 1
    double object_direct = 0.0, object_bounce = 0.0;
    for (int c = 0; c < static_cast<int>(a.size()); ++c) {
      const auto label = bounce.truth.object_id.at<std::uint16_t>(c);
      if (label == 0 || label == wall) continue;
      object_direct += a[c];
      object_bounce += b[c];
    }
    std::printf("%s: interreflection adds %.1f %% to the object's light\n", name,
                100.0 * (object_bounce / object_direct - 1.0));
    EXPECT_GT(object_bounce, 1.05 * object_direct) << name;
  }
}

TEST(CharacteristicSize, FollowsTheDocumentedRulePerShape) {
  Object o;
  o.kind = ShapeKind::kBox;
  o.size = {10.0, 70.0, 30.0};
  EXPECT_EQ(characteristic_size_mm(o).first, 70.0);
  o.kind = ShapeKind::kSphere;
  o.size = {25.0};  // radius
  EXPECT_EQ(characteristic_size_mm(o).first, 50.0);
  o.kind = ShapeKind::kCylinder;
  o.size = {20.0, 120.0};  // radius, length
  EXPECT_EQ(characteristic_size_mm(o).first, 120.0);
  o.size = {40.0, 30.0};
  EXPECT_EQ(characteristic_size_mm(o).first, 80.0);
  o.kind = ShapeKind::kPlane;
  o.size = {400.0, 300.0};
  EXPECT_EQ(characteristic_size_mm(o).first, 400.0);
  o.size = {0.0, 0.0};  // infinite
  EXPECT_EQ(characteristic_size_mm(o).first, 0.0);
  o.kind = ShapeKind::kBowl;
  o.size = {50.0, 20.0};  // radius, depth: the rim's diameter 2 sqrt(20 (100 - 20)) = 80
  EXPECT_NEAR(characteristic_size_mm(o).first, 80.0, 1e-9);
  o.size = {50.0, 70.0};  // deeper than the radius: the sphere's diameter
  EXPECT_EQ(characteristic_size_mm(o).first, 100.0);
  o.kind = ShapeKind::kMesh;
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{-5.0, 0.0, 0.0}, {5.0, 12.0, 0.0}, {0.0, 0.0, 3.0}};
  o.mesh = mesh;
  EXPECT_EQ(characteristic_size_mm(o).first, 12.0);
}

}  // namespace
}  // namespace rfrecon::sim
