// Analytic ray intersections (plane, box, sphere, cylinder, bowl), a BVH for triangle meshes, and mesh loading
// (assimp).
#include "sim/objects.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "host/core/errors.h"
#include "host/core/message_text.h"
#include "sim/mesh_file.h"

namespace rfrecon::sim {

namespace {
// The file system assimp sees: no file at all. The mesh itself comes from memory, already checked, and a file it
// names (an OBJ's "mtllib") is not opened: materials come from the scene, and a FIFO there would block.
class NoOtherFiles : public Assimp::IOSystem {
 public:
  bool Exists(const char* /*file*/) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* /*file*/, const char* /*mode*/) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

// An intersection in the object frame.
struct LocalHit {
  double distance;
  Eigen::Vector3d normal;  // unit, object frame, either orientation
};

std::optional<LocalHit> nearest(std::optional<LocalHit> a, std::optional<LocalHit> b) {
  if (!a) return b;
  if (!b) return a;
  return a->distance <= b->distance ? a : b;
}

std::optional<LocalHit> intersect_plane(const Object& o, const Ray& r, double t_min, double t_max) {
  if (std::abs(r.direction.z()) < 1e-15) return std::nullopt;
  const double t = -r.origin.z() / r.direction.z();
  if (!(t > t_min && t < t_max)) return std::nullopt;
  const Eigen::Vector3d p = r.origin + t * r.direction;
  if (o.size[0] > 0.0 && (std::abs(p.x()) > o.size[0] / 2 || std::abs(p.y()) > o.size[1] / 2)) return std::nullopt;
  return LocalHit{t, Eigen::Vector3d::UnitZ()};
}

std::optional<LocalHit> intersect_box(const Object& o, const Ray& r, double t_min, double t_max) {
  double t_near = -INFINITY, t_far = INFINITY;
  int near_axis = 0, far_axis = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double half = o.size[axis] / 2;
    if (std::abs(r.direction[axis]) < 1e-15) {
      if (std::abs(r.origin[axis]) > half) return std::nullopt;
      continue;
    }
    double t0 = (-half - r.origin[axis]) / r.direction[axis];
    double t1 = (half - r.origin[axis]) / r.direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_near) t_near = t0, near_axis = axis;
    if (t1 < t_far) t_far = t1, far_axis = axis;
  }
  if (t_near > t_far) return std::nullopt;
  const double t = t_near > t_min ? t_near : t_far;
  const int axis = t_near > t_min ? near_axis : far_axis;
  if (!(t > t_min && t < t_max)) return std::nullopt;
  return LocalHit{t, Eigen::Vector3d::Unit(axis)};
}

// Roots of a t^2 + 2 b t + c = 0 inside (t_min, t_max), nearest first.
std::optional<double> nearest_root(double a, double b, double c, double t_min, double t_max,
                                   const std::function<bool(double)>& accept) {
  const double disc = b * b - a * c;
  if (disc < 0.0 || a == 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  for (const double t : {(-b - s) / a, (-b + s) / a}) {
    if (t > t_min && t < t_max && accept(t)) return t;
  }
  return std::nullopt;
}

std::optional<LocalHit> intersect_sphere(const Object& o, const Ray& r, double t_min, double t_max) {
  const double radius = o.size[0];
  const auto t = nearest_root(1.0, r.origin.dot(r.direction), r.origin.squaredNorm() - radius * radius, t_min, t_max,
                              [](double) { return true; });
  if (!t) return std::nullopt;
  return LocalHit{*t, (r.origin + *t * r.direction).normalized()};
}

std::optional<LocalHit> intersect_bowl(const Object& o, const Ray& r, double t_min, double t_max) {
  const double radius = o.size[0];
  const double rim = o.size[1] - radius;
  const auto t = nearest_root(1.0, r.origin.dot(r.direction), r.origin.squaredNorm() - radius * radius, t_min, t_max,
                              [&](double t) { return r.origin.z() + t * r.direction.z() <= rim; });
  if (!t) return std::nullopt;
  return LocalHit{*t, (r.origin + *t * r.direction).normalized()};
}

std::optional<LocalHit> intersect_cylinder(const Object& o, const Ray& r, double t_min, double t_max) {
  const double radius = o.size[0];
  const double half = o.size[1] / 2;
  const Eigen::Vector2d po = r.origin.head<2>(), d = r.direction.head<2>();
  const auto t_side = nearest_root(d.squaredNorm(), po.dot(d), po.squaredNorm() - radius * radius, t_min, t_max,
                                   [&](double t) { return std::abs(r.origin.z() + t * r.direction.z()) <= half; });
  std::optional<LocalHit> hit;
  if (t_side) {
    const Eigen::Vector3d p = r.origin + *t_side * r.direction;
    hit = LocalHit{*t_side, Eigen::Vector3d(p.x(), p.y(), 0.0).normalized()};
  }
  if (std::abs(r.direction.z()) > 1e-15) {
    for (const double z : {-half, half}) {
      const double t = (z - r.origin.z()) / r.direction.z();
      if (t > t_min && t < t_max && (r.origin + t * r.direction).head<2>().squaredNorm() <= radius * radius) {
        hit = nearest(hit, LocalHit{t, Eigen::Vector3d::UnitZ()});
      }
    }
  }
  return hit;
}

bool ray_hits_box(const Eigen::AlignedBox3d& box, const Ray& r, const Eigen::Vector3d& inv_dir, double t_min,
                  double t_max) {
  for (int axis = 0; axis < 3; ++axis) {
    double t0 = (box.min()[axis] - r.origin[axis]) * inv_dir[axis];
    double t1 = (box.max()[axis] - r.origin[axis]) * inv_dir[axis];
    if (t0 > t1) std::swap(t0, t1);
    t_min = std::max(t_min, t0);
    t_max = std::min(t_max, t1);
    if (t_min > t_max) return false;
  }
  return true;
}

// Moeller-Trumbore.
std::optional<double> intersect_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                         const Ray& r) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = r.direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14) return std::nullopt;
  const Eigen::Vector3d s = r.origin - a;
  const double u = s.dot(p) / det;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = r.direction.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  return e2.dot(q) / det;
}

std::optional<LocalHit> intersect_mesh(const Object& o, const Ray& r, double t_min, double t_max) {
  const TriangleMesh& mesh = *o.mesh;
  const Eigen::Vector3d inv_dir = r.direction.cwiseInverse();
  std::optional<LocalHit> best;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const auto& node = mesh.nodes[stack[--top]];
    if (!ray_hits_box(node.bounds, r, inv_dir, t_min, best ? best->distance : t_max)) continue;
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Eigen::Vector3i& tri = mesh.triangles[mesh.order[i]];
        const auto t = intersect_triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], r);
        if (t && *t > t_min && *t < (best ? best->distance : t_max)) {
          const Eigen::Vector3d n =
              (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
          best = LocalHit{*t, n.normalized()};
        }
      }
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return best;
}

int build_node(TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& centroids, int first, int count, int depth) {
  const int index = static_cast<int>(mesh.nodes.size());
  mesh.nodes.emplace_back();
  Eigen::AlignedBox3d bounds, centroid_bounds;
  for (int i = first; i < first + count; ++i) {
    const auto& tri = mesh.triangles[mesh.order[i]];
    for (int k = 0; k < 3; ++k) bounds.extend(mesh.vertices[tri[k]]);
    centroid_bounds.extend(centroids[mesh.order[i]]);
  }
  mesh.nodes[index].bounds = bounds;
  if (count <= 4 || depth >= 30) {
    mesh.nodes[index].first = first;
    mesh.nodes[index].count = count;
    return index;
  }
  int axis = 0;
  centroid_bounds.sizes().maxCoeff(&axis);
  const int middle = first + count / 2;
  std::nth_element(mesh.order.begin() + first, mesh.order.begin() + middle, mesh.order.begin() + first + count,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  const int left = build_node(mesh, centroids, first, middle - first, depth + 1);
  const int right = build_node(mesh, centroids, middle, first + count - middle, depth + 1);
  mesh.nodes[index].left = left;
  mesh.nodes[index].right = right;
  return index;
}

// Integral over [0, t] of the square wave that is +1 on [2k, 2k + 1) and -1 on [2k + 1, 2k + 2): a triangle wave.
double square_wave_integral(double t) { return 1.0 - std::abs(t - 2.0 * std::floor(t / 2.0) - 1.0); }

// The square wave's integral over [lo, hi] clipped to the board's [0, squares] (0 when nothing is left) and the
// clipped length, in squares.
std::pair<double, double> clipped_square_wave(double lo, double hi, int squares) {
  lo = std::max(lo, 0.0);
  hi = std::min(hi, static_cast<double>(squares));
  if (hi <= lo) return {0.0, 0.0};
  return {square_wave_integral(hi) - square_wave_integral(lo), hi - lo};
}
}  // namespace

const char* to_string(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kPlane:
      return "plane";
    case ShapeKind::kBox:
      return "box";
    case ShapeKind::kSphere:
      return "sphere";
    case ShapeKind::kCylinder:
      return "cylinder";
    case ShapeKind::kMesh:
      return "mesh";
    case ShapeKind::kBowl:
      return "bowl";
  }
  return "?";
}

void build_bvh(TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> centroids;
  centroids.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    centroids.push_back((mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.0);
  }
  mesh.order.resize(mesh.triangles.size());
  std::iota(mesh.order.begin(), mesh.order.end(), 0);
  mesh.nodes.clear();
  build_node(mesh, centroids, 0, static_cast<int>(mesh.triangles.size()), 0);
}

std::optional<Hit> intersect(const Object& object, const Ray& ray, double min_distance, double max_distance) {
  const Eigen::Isometry3d object_from_world = object.world_from_object.inverse();
  const Ray local{object_from_world * ray.origin, object_from_world.linear() * ray.direction};
  std::optional<LocalHit> hit;
  switch (object.kind) {
    case ShapeKind::kPlane:
      hit = intersect_plane(object, local, min_distance, max_distance);
      break;
    case ShapeKind::kBox:
      hit = intersect_box(object, local, min_distance, max_distance);
      break;
    case ShapeKind::kSphere:
      hit = intersect_sphere(object, local, min_distance, max_distance);
      break;
    case ShapeKind::kCylinder:
      hit = intersect_cylinder(object, local, min_distance, max_distance);
      break;
    case ShapeKind::kMesh:
      hit = intersect_mesh(object, local, min_distance, max_distance);
      break;
    case ShapeKind::kBowl:
      hit = intersect_bowl(object, local, min_distance, max_distance);
      break;
  }
  if (!hit) return std::nullopt;
  Hit out;
  out.distance = hit->distance;
  out.object = -1;
  const Eigen::Vector3d p_local = local.origin + hit->distance * local.direction;
  const Eigen::Vector3d n_local = hit->normal.dot(local.direction) > 0.0 ? -hit->normal : hit->normal;
  Eigen::Vector3d t_local = object.tangent_object - object.tangent_object.dot(n_local) * n_local;
  if (t_local.norm() < 1e-9) t_local = n_local.unitOrthogonal();
  out.position = ray.origin + hit->distance * ray.direction;
  out.normal = object.world_from_object.linear() * n_local;
  out.tangent = object.world_from_object.linear() * t_local.normalized();
  out.diffuse = object.material.diffuse;
  if (object.checkerboard) {
    const Checkerboard& board = *object.checkerboard;
    const double ix = std::floor(p_local.x() / board.square_size + board.squares_x / 2.0);
    const double iy = std::floor(p_local.y() / board.square_size + board.squares_y / 2.0);
    if (ix >= 0 && iy >= 0 && ix < board.squares_x && iy < board.squares_y) {
      out.diffuse = (static_cast<long>(ix + iy) % 2 == 0) ? board.dark_albedo : board.light_albedo;
    }
  }
  return out;
}

double footprint_diffuse(const Object& object, const Hit& hit, const Eigen::Vector3d& du, const Eigen::Vector3d& dv) {
  if (!object.checkerboard) return hit.diffuse;
  const Checkerboard& board = *object.checkerboard;
  const Eigen::Isometry3d object_from_world = object.world_from_object.inverse();
  const Eigen::Vector3d centre = object_from_world * hit.position / board.square_size;
  const Eigen::Vector3d u = object_from_world.linear() * du / board.square_size;
  const Eigen::Vector3d v = object_from_world.linear() * dv / board.square_size;
  const double half_x = 0.5 * (std::abs(u.x()) + std::abs(v.x()));
  const double half_y = 0.5 * (std::abs(u.y()) + std::abs(v.y()));
  if (!(half_x > 0.0 && half_y > 0.0)) return hit.diffuse;
  // In squares from the board's corner, the albedo is mean - contrast * s(x) s(y) (dark where both are alike).
  const double x = centre.x() + board.squares_x / 2.0;
  const double y = centre.y() + board.squares_y / 2.0;
  const auto [integral_x, length_x] = clipped_square_wave(x - half_x, x + half_x, board.squares_x);
  const auto [integral_y, length_y] = clipped_square_wave(y - half_y, y + half_y, board.squares_y);
  const double area = 4.0 * half_x * half_y;
  const double on_board = length_x * length_y;
  const double mean = 0.5 * (board.dark_albedo + board.light_albedo);
  const double contrast = 0.5 * (board.light_albedo - board.dark_albedo);
  return (mean * on_board - contrast * integral_x * integral_y + object.material.diffuse * (area - on_board)) / area;
}

std::shared_ptr<const TriangleMesh> load_mesh(const std::string& file, double scale, const std::string& field) {
  const MeshFile checked = read_mesh_file(file, field);
  Assimp::Importer importer;
  importer.SetIOHandler(new NoOtherFiles);  // the importer owns it
  // Only ValidateDataStructure, which refuses a face index past the vertices (assimp's PLY reader does not check
  // them); faces are triangulated below, as assimp's Triangulate step aborts on some malformed polygons.
  const aiScene* scene = importer.ReadFileFromMemory(checked.bytes.data(), checked.bytes.size(),
                                                     aiProcess_ValidateDataStructure, checked.format.c_str());
  if (scene == nullptr) {
    throw InputError(field + ": cannot load mesh " + file + " (" +
                     excerpt(importer.GetErrorString(), 2 * kMaxQuotedChars) + ")");
  }
  auto mesh = std::make_shared<TriangleMesh>();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* part = scene->mMeshes[m];
    const int base = static_cast<int>(mesh->vertices.size());
    for (unsigned v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      mesh->vertices.emplace_back(scale * p.x, scale * p.y, scale * p.z);
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      for (unsigned corner = 2; corner < face.mNumIndices; ++corner) {  // a fan; points and lines make none
        mesh->triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[corner - 1],
                                     base + face.mIndices[corner]);
      }
    }
  }
  if (mesh->triangles.empty()) throw InputError(field + ": mesh " + file + " holds no triangles");
  build_bvh(*mesh);
  return mesh;
}

std::pair<double, std::string> characteristic_size_mm(const Object& object) {
  const auto& s = object.size;
  switch (object.kind) {
    case ShapeKind::kBox:
      return {*std::max_element(s.begin(), s.end()), "longest edge"};
    case ShapeKind::kSphere:
      return {2.0 * s[0], "diameter"};
    case ShapeKind::kCylinder:
      return {std::max(2.0 * s[0], s[1]), "larger of diameter and length"};
    case ShapeKind::kPlane:
      if (s[0] <= 0.0) return {0.0, "none (infinite plane)"};
      return {std::max(s[0], s[1]), "longest side"};
    case ShapeKind::kBowl:  // the rim's diameter, or the sphere's when the bowl is deeper than its radius
      return {s[1] < s[0] ? 2.0 * std::sqrt(s[1] * (2.0 * s[0] - s[1])) : 2.0 * s[0], "widest diameter"};
    case ShapeKind::kMesh: {
      Eigen::AlignedBox3d bounds;
      for (const auto& vertex : object.mesh->vertices) bounds.extend(vertex);
      return {bounds.sizes().maxCoeff(), "longest bounding-box edge"};
    }
  }
  throw std::logic_error("characteristic_size_mm: unknown shape");
}

}  // namespace rfrecon::sim
