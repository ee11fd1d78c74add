// The rig as a Python dict with rig.yaml's (OpenCV's) names, and back.
#pragma once

#include <pybind11/pybind11.h>

#include "rfrecon/rfrecon.h"

namespace rfrecon::python {

// An rfrecon.Rig (a dict): {"camera_size": (w, h), "camera_matrix": 3x3, "dist_coeffs", "projector_size",
// "projector_matrix", "projector_dist_coeffs", "R", "T" (projector from camera, mm), "E", "F", "R1", "R2", "P1", "P2",
// "Q", "rectified_camera_size", "rectified_projector_size", "rms", "per_view_errors", "board": (cols, rows,
// square_size), and the standard deviations "camera_intrinsics_std", ... when the rig has them}: float64 arrays,
// copies.
pybind11::dict rig_dict(const Rig& rig);

// The rig of such a dict: the measured keys are read (the derived ones are computed again, complete_rig). Throws
// InputError naming a missing or mis-shaped key.
Rig rig_of(const pybind11::dict& dict);

}  // namespace rfrecon::python
