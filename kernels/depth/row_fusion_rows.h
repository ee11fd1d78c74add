// The function of row_fusion.h that reads rows, for rows in address space RF_ROW_SPACE, named RF_ROW_FN(name).
// No include guard: row_fusion.h includes this file once per address space (depth/row_space.h).

// The forward sweep at pixel u of a run (state reset at the run's first pixel): z and z_next are the current depths
// at u and u + 1 (z_next unused at the run's last pixel), t the triangulated depth at u (NaN where none). Leaves the
// sweep's coefficients at u in state->c and state->d and the link from u to u + 1 in the rest of the state.
RF_INLINE void RF_ROW_FN(rf_fuse_forward)(RfRectifiedRig rig, float beta, int u, int run_ends, int proj_width,
                                          RfFusionWeights weights, RF_ROW_SPACE const float* e_cam_row,
                                          RF_ROW_SPACE const float* e_proj_row, float z, float z_next, float t,
                                          RfSweepState* state) {
  const float sigma_z = z * z * weights.depth_noise_scale;
  const float lambda = t == t ? 1.0f / (sigma_z * sigma_z) : 0.0f;
  float mu_next = 0.0f, a = 0.0f, r = 0.0f;  // the link from u to u + 1
  if (!run_ends) {
    int ok = 1;
    const float dz = RF_FUSION_DIFF_STEP * z;
    const float h = RF_ROW_FN(rf_rk4_increment)(rig, beta, u, z, e_cam_row, e_proj_row, proj_width, &ok);
    const float h_shifted = RF_ROW_FN(rf_rk4_increment)(rig, beta, u, z + dz, e_cam_row, e_proj_row, proj_width, &ok);
    if (ok) {
      mu_next = weights.mu;
      a = 1.0f + (h_shifted - h) / dz;
      r = z_next - z - h;
    }
  }
  const float lower = -state->mu * state->a;
  const float upper = -mu_next * a;
  const float diagonal = lambda + state->mu + mu_next * a * a;
  const float rhs = (t == t ? lambda * (t - z) : 0.0f) - state->mu * state->r + mu_next * a * r;
  const float pivot = diagonal - lower * state->c;
  state->c = upper / pivot;
  state->d = (rhs - lower * state->d) / pivot;
  state->mu = mu_next;
  state->a = a;
  state->r = r;
}
