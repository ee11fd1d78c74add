// A camera pixel's correspondence is its footprint's brightness-weighted mean, so on albedo and shadow edges it sits
// toward the brighter side; this moves it back, from the white frame's relative gradient (docs/method.md#edge-pixels).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace rfrecon::depth {

// `correspondence`: projector x, y per camera pixel (2 floats each, row-major on `camera_size`, NaN where none);
// `white`: the linear white frame, one float per camera pixel. `footprint_px2`: the second moment of a camera pixel's
// footprint along any direction, camera px^2 (1/12 for a sharp square pixel, plus the variance of the optics' blur).
// For a footprint whose brightness varies as the white frame w does, the weighted mean lies footprint_px2 grad(w) / w
// camera px from the pixel's centre (at most half the footprint's width, sqrt(3 footprint_px2)); each correspondence
// moves back by that offset through the local camera -> projector Jacobian, which is taken from the neighbours'
// correspondences (central differences averaged over 9 x 9 pixels). Pixels without a correspondence, or without
// enough neighbours for the Jacobian, keep theirs. Returns the corrected correspondences; 0 returns them unchanged.
std::vector<float> correct_edge_bias(const std::vector<float>& correspondence, const std::vector<float>& white,
                                     cv::Size camera_size, double footprint_px2);

}  // namespace rfrecon::depth
