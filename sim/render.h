// Exact sparse light transport T of a synthetic scene, with the ground truth seen by each camera pixel.
// T[c, p] (c = y * W_cam + x, p = y_p * W_proj + x_p) is the linear camera reading (full scale 1, black removed) at
// pixel c when projector pixel p is fully lit: the supersampled average over pixel c of
// gain * intensity * f_r(w_p, w_c) * (n.w_p) / d_p^2 * (fraction of the sample's footprint falling on p).
#pragma once

#include <Eigen/SparseCore>
#include <opencv2/core.hpp>

#include "host/common/progress.h"
#include "sim/scene.h"

namespace rfrecon::sim {

using TransportMatrix = Eigen::SparseMatrix<float, Eigen::RowMajor, int>;

// Per camera pixel, for the ray through the pixel centre. Camera frame, millimetres.
struct GroundTruth {
  cv::Mat depth_mm;        // CV_32F: z of the surface point, NaN where the ray hits nothing
  cv::Mat points_mm;       // CV_32FC3: X_cam of the surface point, NaN where none
  cv::Mat normals;         // CV_32FC3: unit surface normal facing the camera, NaN where none
  cv::Mat visible;         // CV_8U: 255 where the ray hits a surface
  cv::Mat shadow;          // CV_8U: 255 where visible but unlit (occluded toward the projector, facing away from it,
                           // or outside its image)
  cv::Mat correspondence;  // CV_32FC2: projector pixel (x, y) of the surface point (may lie outside the projector
                           // image), NaN where none or behind the projector
  cv::Mat object_id;       // CV_16U: 1 + index in scene.objects of the object seen, 0 where none
};

struct Transport {
  TransportMatrix T;  // rows: camera pixels, columns: projector pixels
  GroundTruth truth;
};

// Renders T and the ground truth with options.threads threads; deterministic for given scene and options.
// `progress` (optional) advances by one per camera row.
Transport render_transport(const Scene& scene, const RenderOptions& options, Progress* progress = nullptr);

// Convenience: scene.render as the options.
inline Transport render_transport(const Scene& scene) { return render_transport(scene, scene.render); }

}  // namespace rfrecon::sim
