// Scene objects of the synthetic rig and their ray intersections: plane (finite or infinite, optional checkerboard
// albedo), box, sphere, cylinder (with caps), bowl (a spherical cap, seen from inside) and triangle mesh. Lengths in
// millimetres.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/brdf.h"

namespace rfrecon::sim {

enum class ShapeKind { kPlane, kBox, kSphere, kCylinder, kMesh, kBowl };
const char* to_string(ShapeKind kind);

// Checkerboard albedo on a plane: squares[0] x squares[1] squares of side square_size, centred on the plane origin,
// the square at the most negative (x, y) corner dark; outside the board the material's own diffuse albedo applies.
// The board's inner corners, (squares[0]-1) x (squares[1]-1), are what OpenCV detects.
struct Checkerboard {
  int squares_x = 10;
  int squares_y = 7;
  double square_size = 20.0;  // mm
  double dark_albedo = 0.05;
  double light_albedo = 0.8;
};

// A triangle soup in the object frame, with a bounding-volume hierarchy for intersection.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  struct Node {
    Eigen::AlignedBox3d bounds;
    int first = 0, count = 0;  // leaf: triangles [first, first + count) of `order`
    int left = -1, right = -1;
  };
  std::vector<Node> nodes;
  std::vector<int> order;
};

// Builds mesh.nodes / mesh.order (median split, leaves of <= 4 triangles).
void build_bvh(TriangleMesh& mesh);

struct Object {
  std::string name;
  ShapeKind kind = ShapeKind::kPlane;
  Eigen::Isometry3d world_from_object = Eigen::Isometry3d::Identity();
  // plane: [w, h] of a finite rectangle in the object's z = 0 plane (0 = infinite), normal +z;
  // box: [x, y, z] edge lengths, centred; sphere: [r]; cylinder: [r, height] along z, centred; bowl: [r, depth], the
  // part of the sphere of radius r about the origin with z <= depth - r, a thin shell open towards +z.
  std::vector<double> size;
  Brdf material;
  Eigen::Vector3d tangent_object{1.0, 0.0, 0.0};  // brushing direction, projected onto each surface's tangent plane
  std::optional<Checkerboard> checkerboard;       // planes only
  std::shared_ptr<const TriangleMesh> mesh;       // meshes only
  std::string mesh_file;                          // meshes only: absolute path
  double mesh_scale = 1.0;                        // meshes only: file units to mm
};

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
};

// A surface point seen along a ray, in the world frame.
struct Hit {
  double distance = 0.0;  // along the ray
  Eigen::Vector3d position;
  Eigen::Vector3d normal;   // unit, outward (planes: the side facing the ray origin)
  Eigen::Vector3d tangent;  // unit, perpendicular to normal
  double diffuse = 0.0;     // diffuse albedo at the point (checkerboard texture or material)
  int object = -1;
};

// Nearest intersection with distance in (min_distance, max_distance), if any.
std::optional<Hit> intersect(const Object& object, const Ray& ray, double min_distance, double max_distance);

// The diffuse albedo that a camera pixel integrates around `hit` on `object`: for a checkerboard, the board's albedo
// averaged exactly over the box in the board's plane that bounds the footprint with edge vectors `du`, `dv` (world
// frame, mm), centred on the hit (squares, and the material outside the board, by their area in the box), so edges
// come out as a sensor sees them, without the aliasing of point samples; other objects keep hit.diffuse.
double footprint_diffuse(const Object& object, const Hit& hit, const Eigen::Vector3d& du, const Eigen::Vector3d& dv);

// Loads a PLY or OBJ triangle mesh (read_mesh_file's checks, then assimp from memory; faces fan-triangulated;
// all meshes of the file, vertices scaled by `scale`).
// Throws InputError naming `field` and the file when it cannot be read or holds no triangles.
std::shared_ptr<const TriangleMesh> load_mesh(const std::string& file, double scale, const std::string& field);

// Characteristic size of an object in mm and how it is measured: box: longest edge; sphere: diameter (2 r);
// cylinder: the larger of diameter (2 r) and length; finite plane: longest side; mesh: longest edge of its
// axis-aligned bounding box in the object frame (scaled to mm); an infinite plane: 0, "none (infinite plane)".
std::pair<double, std::string> characteristic_size_mm(const Object& object);

}  // namespace rfrecon::sim
