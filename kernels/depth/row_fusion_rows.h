// The functions of row_fusion.h, for the kind of row of depth/row_kind_*.h, named RF_ROW_FN(name). No include
// guard: row_fusion.h includes this file once per kind of row (depth/row_space.h).

RF_INLINE void RF_ROW_FN(rf_sweep_state_init)(RF_LANE_TYPE(RfSweepState) * state) {
  state->mu = 0.0f;
  state->a = 0.0f;
  state->r = 0.0f;
  state->c = 0.0f;
  state->d = 0.0f;
}

// Run structure at a pixel (not masked) from its code and its neighbours' (prev_code, next_code; RF_RUN_MASKED where
// the neighbour is outside the row): a run starts after a masked pixel or at RF_RUN_START, and ends before a pixel
// that does not continue it.
RF_INLINE RF_INT RF_ROW_FN(rf_fusion_run_starts)(RF_INT code, RF_INT prev_code) {
  return (prev_code == RF_RUN_MASKED) | (code != RF_RUN_CONTINUE);
}
RF_INLINE RF_INT RF_ROW_FN(rf_fusion_run_ends)(RF_INT next_code) { return next_code != RF_RUN_CONTINUE; }

// The run code of pixel u - 1, RF_RUN_MASKED before the row's start.
RF_INLINE RF_INT RF_ROW_FN(rf_prev_code)(RF_ROW_SPACE const unsigned char* run_row, int u) {
  RF_INT code = RF_RUN_MASKED;
  if (u > 0) code = RF_LOAD_CODE(run_row, u - 1);
  return code;
}

// The run code of pixel u + 1, RF_RUN_MASKED past the row's end.
RF_INLINE RF_INT RF_ROW_FN(rf_next_code)(RF_ROW_SPACE const unsigned char* run_row, int u, int width) {
  RF_INT code = RF_RUN_MASKED;
  if (u + 1 < width) code = RF_LOAD_CODE(run_row, u + 1);
  return code;
}

// The backward sweep at a pixel: the update of z there, from the one at the next pixel of the run.
RF_INLINE RF_REAL RF_ROW_FN(rf_fuse_backward)(RF_INT run_ends, RF_REAL c, RF_REAL d, RF_REAL next_update) {
  return RF_SELECT(RF_REAL, run_ends, d, d - c * next_update);
}

// The forward sweep at pixel u of a run (state reset at the run's first pixel), linked_next set where pixel u + 1
// continues the run: z and z_next are the current depths at u and u + 1 (z_next unused at the run's last pixel), t the
// triangulated depth at u (NaN where none). Leaves the sweep's coefficients at u in state->c and state->d and the link
// from u to u + 1 in the rest of the state. The link's slopes are evaluated at the run's last pixel too (on lanes,
// unless no lane links), and not used. Rows of width >= 2. The two increments' eight slopes read the projector row at
// e_proj_row + s * slope_stride, s = 0 to 7 (rf_rk4_increment).
RF_INLINE void RF_ROW_FN(rf_fuse_forward)(RfRectifiedRig rig, RF_REAL beta, int u, int width, RF_INT linked_next,
                                          int proj_width, RfFusionWeights weights, RF_ROW_SPACE const float* e_cam_row,
                                          RF_ROW_SPACE const float* e_proj_row, int slope_stride, RF_REAL z,
                                          RF_REAL z_next, RF_REAL t, RF_LANE_TYPE(RfSweepState) * state) {
  const RF_REAL sigma_z = z * z * weights.depth_noise_scale;
  const RF_REAL lambda = RF_SELECT(RF_REAL, t == t, 1.0f / (sigma_z * sigma_z), 0.0f);
  RF_INT ok = RF_TRUE;
  const RF_REAL dz = RF_FUSION_DIFF_STEP * z;
  RF_REAL h = 0.0f;
  RF_REAL h_shifted = 0.0f;
  if (RF_ANY(linked_next)) {                    // the slopes matter only on a link to the next pixel
    const int from = RF_MIN_INT(u, width - 2);  // at the row's last pixel, any step inside the row
    const RF_REAL e0 = RF_LOAD(e_cam_row, from), e1 = RF_LOAD(e_cam_row, from + 1);
    h = RF_ROW_FN(rf_rk4_increment)(rig, beta, from, z, e0, e1, e_proj_row, slope_stride, proj_width, &ok);
    h_shifted = RF_ROW_FN(rf_rk4_increment)(rig, beta, from, z + dz, e0, e1, e_proj_row + 4 * slope_stride,
                                            slope_stride, proj_width, &ok);
  }
  const RF_INT linked = linked_next & ok;  // the link from u to u + 1
  const RF_REAL mu_next = RF_SELECT(RF_REAL, linked, weights.mu, 0.0f);
  const RF_REAL a = RF_SELECT(RF_REAL, linked, 1.0f + (h_shifted - h) / dz, 0.0f);
  const RF_REAL r = RF_SELECT(RF_REAL, linked, z_next - z - h, 0.0f);
  const RF_REAL lower = -state->mu * state->a;
  const RF_REAL upper = -mu_next * a;
  const RF_REAL diagonal = lambda + state->mu + mu_next * a * a;
  const RF_REAL rhs = RF_SELECT(RF_REAL, t == t, lambda * (t - z), 0.0f) - state->mu * state->r + mu_next * a * r;
  const RF_REAL pivot = diagonal - lower * state->c;
  state->c = upper / pivot;
  state->d = (rhs - lower * state->d) / pivot;
  state->mu = mu_next;
  state->a = a;
  state->r = r;
}

// The whole row: `iterations` linearised solves of every run. z_row holds the start on entry (finite wherever the
// run code is not RF_RUN_MASKED) and the fused depth on return. c_row and d_row are scratch of the row's width. A
// masked pixel leaves the sweeps' states as they were and its depth unchanged.
RF_INLINE void RF_ROW_FN(rf_fuse_row)(RfRectifiedRig rig, RF_REAL beta, int width, int proj_width, int iterations,
                                      RfFusionWeights weights, RF_ROW_SPACE const float* e_cam_row,
                                      RF_ROW_SPACE const float* e_proj_row, RF_ROW_SPACE const float* z_tri_row,
                                      RF_ROW_SPACE const unsigned char* run_row, RF_ROW_SPACE float* z_row,
                                      RF_ROW_SPACE float* c_row, RF_ROW_SPACE float* d_row) {
  for (int iteration = 0; iteration < iterations; ++iteration) {
    RF_LANE_TYPE(RfSweepState) state;
    RF_ROW_FN(rf_sweep_state_init)(&state);
    for (int u = 0; u < width; ++u) {
      const RF_INT code = RF_LOAD_CODE(run_row, u);
      if (RF_ANY(code != RF_RUN_MASKED)) {  // else every row is masked here and the state stays
        const RF_INT next_code = RF_ROW_FN(rf_next_code)(run_row, u, width);
        RF_LANE_TYPE(RfSweepState) next = state;
        const RF_INT starts = RF_ROW_FN(rf_fusion_run_starts)(code, RF_ROW_FN(rf_prev_code)(run_row, u));
        next.mu = RF_SELECT(RF_REAL, starts, 0.0f, next.mu);
        next.a = RF_SELECT(RF_REAL, starts, 0.0f, next.a);
        next.r = RF_SELECT(RF_REAL, starts, 0.0f, next.r);
        next.c = RF_SELECT(RF_REAL, starts, 0.0f, next.c);
        next.d = RF_SELECT(RF_REAL, starts, 0.0f, next.d);
        RF_ROW_FN(rf_fuse_forward)
        (rig, beta, u, width, next_code == RF_RUN_CONTINUE, proj_width, weights, e_cam_row, e_proj_row, 0,
         RF_LOAD(z_row, u), RF_LOAD(z_row, RF_MIN_INT(u + 1, width - 1)), RF_LOAD(z_tri_row, u), &next);
        const RF_INT masked = code == RF_RUN_MASKED;
        state.mu = RF_SELECT(RF_REAL, masked, state.mu, next.mu);
        state.a = RF_SELECT(RF_REAL, masked, state.a, next.a);
        state.r = RF_SELECT(RF_REAL, masked, state.r, next.r);
        state.c = RF_SELECT(RF_REAL, masked, state.c, next.c);
        state.d = RF_SELECT(RF_REAL, masked, state.d, next.d);
      }
      RF_STORE(c_row, u, state.c);
      RF_STORE(d_row, u, state.d);
    }
    RF_REAL update = 0.0f;
    for (int u = width - 1; u >= 0; --u) {
      const RF_INT masked = RF_LOAD_CODE(run_row, u) == RF_RUN_MASKED;
      const RF_INT run_ends = RF_ROW_FN(rf_fusion_run_ends)(RF_ROW_FN(rf_next_code)(run_row, u, width));
      update = RF_SELECT(RF_REAL, masked, update,
                         RF_ROW_FN(rf_fuse_backward)(run_ends, RF_LOAD(c_row, u), RF_LOAD(d_row, u), update));
      const RF_REAL z = RF_LOAD(z_row, u);
      RF_STORE(z_row, u, RF_SELECT(RF_REAL, masked, z, z + update));
    }
  }
}
