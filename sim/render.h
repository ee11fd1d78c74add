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

// Renders T and the ground truth with options.threads threads; deterministic for given scene and options.
// `progress` (optional) advances by one per camera row.
Transport render_transport(const Scene& scene, const RenderOptions& options, Progress* progress = nullptr);

// Convenience: scene.render as the options.
inline Transport render_transport(const Scene& scene) { return render_transport(scene, scene.render); }

}  // namespace rfrecon::sim
