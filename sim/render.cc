// Ray-traced transport: per camera pixel, N x N sub-pixel rays; each hit point lit by the projector deposits its
// reflected reading (texture averaged over the ray's cell) on the projector pixels under its footprint; optional
// defocus and one-bounce interreflection.
#include "sim/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <thread>

namespace rfrecon::sim {

namespace {

struct Entry {
  int column;
  float value;
};
using Row = std::vector<Entry>;

class Tracer {
 public:
  explicit Tracer(const Scene& scene) : scene_(scene) {}

  std::optional<Hit> nearest(const Ray& ray, double min_distance, double max_distance) const {
    std::optional<Hit> best;
    for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
      auto hit = intersect(scene_.objects[i], ray, min_distance, best ? best->distance : max_distance);
      if (hit) {
        best = hit;
        best->object = static_cast<int>(i);
      }
    }
    return best;
  }

 private:
  const Scene& scene_;
};

// A surface point as the projector lights it.
struct Lighting {
  Eigen::Vector2d projector_px;  // distorted projector pixel coordinates
  Eigen::Vector3d w_p;           // unit, from the point to the projector centre
  double irradiance;             // gain * intensity * cos(theta_p) / d_p^2
};

// Offset for secondary rays, relative to the distance from the origin (double precision leaves ~1e-13).
double ray_epsilon(const Eigen::Vector3d& point) { return 1e-7 * (1.0 + point.norm()); }

// How the projector lights `hit`: nothing when the point faces away, lies behind the projector or is occluded.
std::optional<Lighting> light_at(const Scene& scene, const Tracer& tracer, const Hit& hit) {
  const Eigen::Vector3d to_projector = scene.projector.centre_world() - hit.position;
  const double d_p = to_projector.norm();
  const Eigen::Vector3d w_p = to_projector / d_p;
  const double cos_p = hit.normal.dot(w_p);
  if (cos_p <= 0.0) return std::nullopt;
  const Eigen::Vector3d X_proj = scene.projector.device_from_world * hit.position;
  if (X_proj.z() <= 0.0) return std::nullopt;
  const double eps = ray_epsilon(hit.position);
  if (tracer.nearest({hit.position + eps * hit.normal, w_p}, 0.0, d_p - eps)) return std::nullopt;
  return Lighting{project_device_point(scene.projector, X_proj), w_p,
                  scene.gain * scene.intensity * cos_p / (d_p * d_p)};
}

// f_r at `hit` for unit world directions `w_in` (toward the light) and `w_out`.
double brdf_at(const Scene& scene, const Hit& hit, const Eigen::Vector3d& w_in, const Eigen::Vector3d& w_out) {
  const Eigen::Vector3d bitangent = hit.normal.cross(hit.tangent);
  const auto local = [&](const Eigen::Vector3d& w) {
    return Eigen::Vector3d(w.dot(hit.tangent), w.dot(bitangent), w.dot(hit.normal));
  };
  return evaluate(scene.objects[hit.object].material, hit.diffuse, local(w_in), local(w_out));
}

// Spreads `weight` uniformly over the projector-image box [u - h, u + h] (pixel i covers [i - 0.5, i + 0.5]);
// the part outside the projector image is dropped (no light comes from there).
void deposit_box(Row& row, cv::Size projector, const Eigen::Vector2d& u, const Eigen::Vector2d& half, double weight) {
  int lo[2], hi[2];
  for (int a = 0; a < 2; ++a) {
    lo[a] = static_cast<int>(std::floor(u[a] - half[a] + 0.5));
    hi[a] = static_cast<int>(std::floor(u[a] + half[a] + 0.5));
  }
  const auto overlap = [&](int a, int i) {
    if (half[a] < 1e-9) return 1.0;
    const double l = std::max(u[a] - half[a], i - 0.5);
    const double h = std::min(u[a] + half[a], i + 0.5);
    return std::max(0.0, h - l) / (2.0 * half[a]);
  };
  for (int y = std::max(lo[1], 0); y <= std::min(hi[1], projector.height - 1); ++y) {
    const double wy = overlap(1, y);
    for (int x = std::max(lo[0], 0); x <= std::min(hi[0], projector.width - 1); ++x) {
      const double w = weight * wy * overlap(0, x);
      if (w > 0.0) row.push_back({y * projector.width + x, static_cast<float>(w)});
    }
  }
}

void merge(Row& row) {
  std::sort(row.begin(), row.end(), [](const Entry& a, const Entry& b) { return a.column < b.column; });
  std::size_t out = 0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (out > 0 && row[out - 1].column == row[i].column) {
      row[out - 1].value += row[i].value;
    } else {
      row[out++] = row[i];
    }
  }
  row.resize(out);
}

std::vector<double> gaussian_kernel(double sigma) {
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<double> kernel(2 * radius + 1);
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) sum += kernel[i + radius] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (auto& k : kernel) k /= sum;
  return kernel;
}

// Projector defocus: the light of projector pixel p lands where pixels p + d would, with Gaussian weights.
void blur_projector(Row& row, cv::Size projector, const std::vector<double>& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
  Row out;
  out.reserve(row.size() * kernel.size() * kernel.size());
  for (const Entry& e : row) {
    const int px = e.column % projector.width, py = e.column / projector.width;
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
        const int x = px + dx, y = py + dy;
        if (x < 0 || y < 0 || x >= projector.width || y >= projector.height) continue;
        out.push_back(
            {y * projector.width + x, static_cast<float>(e.value * kernel[dx + radius] * kernel[dy + radius])});
      }
    }
  }
  merge(out);
  row.swap(out);
}

// Camera defocus: pixel c reads a Gaussian-weighted mix of its neighbours' sharp rows.
std::vector<Row> blur_camera(const std::vector<Row>& rows, cv::Size camera, const std::vector<double>& kernel) {
  const int radius = static_cast<int>(kernel.size() / 2);
  std::vector<Row> out(rows.size());
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      Row& row = out[y * camera.width + x];
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= camera.width || sy >= camera.height) continue;
          const double w = kernel[dx + radius] * kernel[dy + radius];
          for (const Entry& e : rows[sy * camera.width + sx])
            row.push_back({e.column, static_cast<float>(e.value * w)});
        }
      }
      merge(row);
    }
  }
  return out;
}

// The undistorted normalised coordinates of camera row y's rays: per pixel, n x n sub-pixel rays, then its centre.
std::vector<Eigen::Vector2d> row_rays(const Device& camera, const RenderOptions& options, int y) {
  const int n = options.supersample, per_pixel = n * n + 1;
  std::vector<cv::Point2d> pixels;
  pixels.reserve(static_cast<std::size_t>(camera.size.width) * per_pixel);
  std::uniform_real_distribution<double> in_cell(0.0, 1.0);
  for (int x = 0; x < camera.size.width; ++x) {
    // A grid of cells regularly placed aliases straight edges to 1/N px; a point drawn in each cell does not.
    std::mt19937_64 placement(options.seed * 0xD1B54A32D192ED03ULL + static_cast<unsigned long long>(y) * 65536ULL +
                              static_cast<unsigned long long>(x));
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double u = options.jitter ? in_cell(placement) : 0.5;
        const double v = options.jitter ? in_cell(placement) : 0.5;
        pixels.emplace_back(x - 0.5 + (i + u) / n, y - 0.5 + (j + v) / n);
      }
    }
    pixels.emplace_back(x, y);
  }
  return undistort_pixels(camera, pixels);
}

// Runs work(y) for every camera row on `threads` threads (0: every core), rows taken in turn.
template <typename Work>
void for_each_camera_row(int height, int threads, const Work& work) {
  std::atomic<int> next_row{0};
  const auto run = [&] {
    for (int y = next_row++; y < height; y = next_row++) work(y);
  };
  const int count = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 1; i < count; ++i) pool.emplace_back(run);
  run();
  for (auto& thread : pool) thread.join();
}

class RowRenderer {
 public:
  RowRenderer(const Scene& scene, const RenderOptions& options)
      : scene_(scene), options_(options), tracer_(scene), n_(options.supersample) {}

  // Renders camera row y into rows[y * W ...] and the ground truth of that row, tracing `rays` when given (all rows'
  // rays, camera_rays), else the row's rays computed here.
  void render_row(int y, const CameraRays* rays, std::vector<Row>& rows, truth::TruthMaps& truth) const {
    const cv::Size camera = scene_.camera.size;
    const int per_pixel = n_ * n_ + 1;
    std::vector<Eigen::Vector2d> computed;
    if (rays == nullptr) computed = row_rays(scene_.camera, options_, y);
    const Eigen::Vector2d* normalized =
        rays != nullptr ? rays->normalized.data() + static_cast<std::size_t>(y) * camera.width * per_pixel
                        : computed.data();
    for (int x = 0; x < camera.width; ++x) {
      const int c = y * camera.width + x;
      std::mt19937_64 rng(options_.seed * 0x9E3779B97F4A7C15ULL + static_cast<unsigned long long>(c));
      Row& row = rows[c];
      for (int s = 0; s < n_ * n_; ++s) sample(normalized[x * per_pixel + s], rng, row);
      merge(row);
      record_truth(normalized[x * per_pixel + n_ * n_], x, y, truth);
    }
  }

 private:
  // One sub-pixel ray through undistorted normalised camera coordinates `xy`.
  void sample(const Eigen::Vector2d& xy, std::mt19937_64& rng, Row& row) const {
    const Eigen::Vector3d direction = Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
    const auto hit = tracer_.nearest({Eigen::Vector3d::Zero(), direction}, 0.0, INFINITY);
    if (!hit) return;
    const double weight = 1.0 / (n_ * n_);
    const Eigen::Vector3d w_c = -direction;
    const CellEdges edges = cell_edges(xy, *hit);
    Hit cell = *hit;
    cell.diffuse = footprint_diffuse(scene_.objects[hit->object], *hit, edges.du, edges.dv);
    if (const auto light = light_at(scene_, tracer_, cell)) {
      const double reading = light->irradiance * brdf_at(scene_, cell, light->w_p, w_c) * weight;
      if (reading > 0.0) deposit_box(row, scene_.projector.size, light->projector_px, footprint(edges, cell), reading);
    }
    if (options_.interreflection_samples > 0) interreflect(*hit, w_c, rng, weight, row);
  }

  // One sub-pixel cell's footprint on the tangent plane at its hit (world frame, mm): the neighbouring sub-pixel
  // rays intersected with that plane, less the hit.
  struct CellEdges {
    Eigen::Vector3d du, dv;
  };
  CellEdges cell_edges(const Eigen::Vector2d& xy, const Hit& hit) const {
    const double plane = hit.normal.dot(hit.position);
    const auto on_plane = [&](const Eigen::Vector2d& n_xy) {
      const Eigen::Vector3d ray(n_xy.x(), n_xy.y(), 1.0);
      return Eigen::Vector3d(ray * (plane / hit.normal.dot(ray)) - hit.position);
    };
    return {on_plane(xy + Eigen::Vector2d(1.0 / (n_ * scene_.camera.fx), 0.0)),
            on_plane(xy + Eigen::Vector2d(0.0, 1.0 / (n_ * scene_.camera.fy)))};
  }

  // Half extents, in projector pixels, of the box bounding the projector-image footprint of one sub-pixel cell.
  Eigen::Vector2d footprint(const CellEdges& edges, const Hit& hit) const {
    const auto project = [&](const Eigen::Vector3d& X) {
      return project_device_point(scene_.projector, scene_.projector.device_from_world * X);
    };
    const Eigen::Vector2d centre = project(hit.position);
    const Eigen::Vector2d du = project(hit.position + edges.du) - centre;
    const Eigen::Vector2d dv = project(hit.position + edges.dv) - centre;
    const Eigen::Vector2d half = 0.5 * (du.cwiseAbs() + dv.cwiseAbs());
    return half.allFinite() ? half : Eigen::Vector2d::Zero();
  }

  // One bounce: cosine-weighted directions from the first hit; the lit second hit's reflected light reaches the
  // camera via the first hit's BRDF. Deposited at the projector pixel of the second hit.
  void interreflect(const Hit& hit, const Eigen::Vector3d& w_c, std::mt19937_64& rng, double weight, Row& row) const {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const Eigen::Vector3d bitangent = hit.normal.cross(hit.tangent);
    const int m = options_.interreflection_samples;
    for (int k = 0; k < m; ++k) {
      const double u1 = uniform(rng), u2 = uniform(rng);
      const double r = std::sqrt(u1), phi = 2.0 * EIGEN_PI * u2;
      const Eigen::Vector3d w_in = r * std::cos(phi) * hit.tangent + r * std::sin(phi) * bitangent +
                                   std::sqrt(std::max(0.0, 1.0 - u1)) * hit.normal;
      const double eps = ray_epsilon(hit.position);
      const auto second = tracer_.nearest({hit.position + eps * hit.normal, w_in}, 0.0, INFINITY);
      if (!second) continue;
      const auto light = light_at(scene_, tracer_, *second);
      if (!light) continue;
      // radiance of the second point toward the first, times f_r1 * cos1 / pdf with pdf = cos1 / pi
      const double reading = light->irradiance * brdf_at(scene_, *second, light->w_p, -w_in) *
                             brdf_at(scene_, hit, w_in, w_c) * EIGEN_PI * weight / m;
      if (reading > 0.0) deposit_box(row, scene_.projector.size, light->projector_px, Eigen::Vector2d::Zero(), reading);
    }
  }

  void record_truth(const Eigen::Vector2d& xy, int x, int y, truth::TruthMaps& truth) const {
    const Eigen::Vector3d direction = Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
    const auto hit = tracer_.nearest({Eigen::Vector3d::Zero(), direction}, 0.0, INFINITY);
    if (!hit) return;
    truth.depth_mm.at<float>(y, x) = static_cast<float>(hit->position.z());
    truth.points_mm.at<cv::Vec3f>(y, x) = cv::Vec3f(hit->position.x(), hit->position.y(), hit->position.z());
    truth.normals.at<cv::Vec3f>(y, x) = cv::Vec3f(hit->normal.x(), hit->normal.y(), hit->normal.z());
    truth.visible.at<uchar>(y, x) = 255;
    truth.object_id.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(hit->object + 1);
    const Eigen::Vector3d X_proj = scene_.projector.device_from_world * hit->position;
    if (X_proj.z() > 0.0) {
      const Eigen::Vector2d u = project_device_point(scene_.projector, X_proj);
      truth.correspondence.at<cv::Vec2f>(y, x) = cv::Vec2f(u.x(), u.y());
    }
    const auto light = light_at(scene_, tracer_, *hit);
    const cv::Size projector = scene_.projector.size;
    const bool inside = light && light->projector_px.x() >= -0.5 && light->projector_px.y() >= -0.5 &&
                        light->projector_px.x() < projector.width - 0.5 &&
                        light->projector_px.y() < projector.height - 0.5;
    truth.shadow.at<uchar>(y, x) = inside ? 0 : 255;
  }

  const Scene& scene_;
  const RenderOptions& options_;
  Tracer tracer_;
  int n_;
};

truth::TruthMaps empty_truth(cv::Size size) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return {cv::Mat(size, CV_32F, cv::Scalar(nan)),
          cv::Mat(size, CV_32FC3, cv::Scalar::all(nan)),
          cv::Mat(size, CV_32FC3, cv::Scalar::all(nan)),
          cv::Mat::zeros(size, CV_8U),
          cv::Mat::zeros(size, CV_8U),
          cv::Mat(size, CV_32FC2, cv::Scalar::all(nan)),
          cv::Mat::zeros(size, CV_16U)};
}

TransportMatrix assemble(const std::vector<Row>& rows, int columns) {
  TransportMatrix T(static_cast<int>(rows.size()), columns);
  std::size_t nnz = 0;
  for (const auto& row : rows) nnz += row.size();
  T.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  std::size_t k = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    T.outerIndexPtr()[r] = static_cast<int>(k);
    for (const Entry& e : rows[r]) {
      T.innerIndexPtr()[k] = e.column;
      T.valuePtr()[k++] = e.value;
    }
  }
  T.outerIndexPtr()[rows.size()] = static_cast<int>(k);
  return T;
}
}  // namespace

CameraRays camera_rays(const Device& camera, const RenderOptions& options) {
  CameraRays rays;
  const int per_pixel = options.supersample * options.supersample + 1;
  const auto row_size = static_cast<std::size_t>(camera.size.width) * per_pixel;
  rays.normalized.resize(row_size * static_cast<std::size_t>(camera.size.height));
  for_each_camera_row(camera.size.height, options.threads, [&](int y) {
    const auto row = row_rays(camera, options, y);
    std::copy(row.begin(), row.end(), rays.normalized.begin() + static_cast<std::ptrdiff_t>(row_size * y));
  });
  return rays;
}

Transport render_transport(const Scene& scene, const RenderOptions& options, const CameraRays* rays,
                           Progress* progress) {
  const cv::Size camera = scene.camera.size;
  const int per_pixel = options.supersample * options.supersample + 1;
  if (rays != nullptr &&
      rays->normalized.size() != static_cast<std::size_t>(camera.area()) * static_cast<std::size_t>(per_pixel)) {
    throw std::invalid_argument("render_transport: the camera rays are of another camera size or supersampling");
  }
  std::vector<Row> rows(static_cast<std::size_t>(camera.area()));
  Transport out;
  out.truth = empty_truth(camera);
  const RowRenderer renderer(scene, options);
  const std::vector<double> projector_kernel =
      options.projector_defocus_px > 0.0 ? gaussian_kernel(options.projector_defocus_px) : std::vector<double>{};
  for_each_camera_row(camera.height, options.threads, [&](int y) {
    renderer.render_row(y, rays, rows, out.truth);
    if (!projector_kernel.empty()) {
      for (int x = 0; x < camera.width; ++x)
        blur_projector(rows[y * camera.width + x], scene.projector.size, projector_kernel);
    }
    if (progress != nullptr) progress->advance();
  });
  if (options.camera_defocus_px > 0.0) rows = blur_camera(rows, camera, gaussian_kernel(options.camera_defocus_px));
  out.T = assemble(rows, scene.projector.size.area());
  return out;
}

}  // namespace rfrecon::sim
