// Exact sparse light transport T of a synthetic scene, with the ground truth seen by each camera pixel.
// T[c, p] (c = y * W_cam + x, p = y_p * W_proj + x_p) is the linear camera reading (full scale 1, black removed) at
// pixel c when projector pixel p is fully lit: the supersampled average over pixel c of
// gain * intensity * f_r(w_p, w_c) * (n.w_p) / d_p^2 * (fraction of the sample's footprint falling on p).
#pragma once

#include <Eigen/SparseCore>
#include <opencv2/core.hpp>

#include "host/core/progress.h"
#include "host/truth/ground_truth.h"
#include "sim/scene.h"

namespace rfrecon::sim {

using TransportMatrix = Eigen::SparseMatrix<float, Eigen::RowMajor, int>;

struct Transport {
  TransportMatrix T;  // rows: camera pixels, columns: projector pixels
  truth::TruthMaps truth;
};

// The rays render_transport traces: the undistorted normalised coordinates of every camera pixel's n x n sub-pixel
// rays, then its centre (n = options.supersample), row by row. They depend on the camera and the supersampling only,
// without jitter (with it, on the seed too): views of a scene in front of one camera can share them, and their
// undistortion is most of the rendering's time.
struct CameraRays {
  std::vector<Eigen::Vector2d> normalized;
};
CameraRays camera_rays(const Device& camera, const RenderOptions& options);

// Renders T and the ground truth with options.threads threads; deterministic for given scene and options. `rays`
// (optional) are camera_rays(scene.camera, options), computed here row by row when absent; rays of another camera
// size or supersampling throw std::invalid_argument. `progress` (optional) advances by one per camera row.
Transport render_transport(const Scene& scene, const RenderOptions& options, const CameraRays* rays = nullptr,
                           Progress* progress = nullptr);

// Convenience: scene.render as the options.
inline Transport render_transport(const Scene& scene) { return render_transport(scene, scene.render); }

}  // namespace rfrecon::sim
