// The functions of row_integration.h that read and write rows, for rows in address space RF_ROW_SPACE, named
// RF_ROW_FN(name). No include guard: row_integration.h includes this file once per address space
// (depth/row_space.h).

// Ends the current run; before the last pass, rescales its seed by its mean relative residual. A plain write of the
// seed kept in the state (z_row[start] holds that seed), so no read-modify-write of the row.
RF_INLINE void RF_ROW_FN(rf_close_run)(RfRunState* state, RF_ROW_SPACE float* z_row, int rescale_seed) {
  if (state->start >= 0 && rescale_seed && state->count > 0) {
    z_row[state->start] = state->seed * (1.0f + state->sum_rel / (float)state->count);
  }
  state->start = -1;
}

// Pixel u of pass `pass` (of `passes`) given its run code, its triangulated depth and the RK4 increment into it from
// u - 1 at state->z (used only where the run continues; ok cleared where the step broke down).
RF_INLINE void RF_ROW_FN(rf_integrate_pixel_step)(int u, int pass, int passes, unsigned int code, float z_tri,
                                                  float increment, int ok, RF_ROW_SPACE float* z_row,
                                                  RfRunState* state) {
  if (code != RF_RUN_CONTINUE) RF_ROW_FN(rf_close_run)(state, z_row, pass + 1 < passes);
  if (code == RF_RUN_MASKED) {
    z_row[u] = NAN;
    return;
  }
  if (code == RF_RUN_START) {
    state->start = u;
    state->count = 0;
    state->sum_rel = 0.0f;
    state->z = pass == 0 ? z_tri : z_row[u];
    state->seed = state->z;
  } else if (ok) {
    state->z += increment;
  }
  z_row[u] = state->z;
  if (z_tri == z_tri) {  // not NaN
    state->sum_rel += (z_tri - state->z) / state->z;
    state->count += 1;
  }
}

// One pixel u of pass `pass` (of `passes`). Rows are given as pointers to their first element.
RF_INLINE void RF_ROW_FN(rf_integrate_pixel)(RfRectifiedRig rig, float beta, int u, int proj_width, int pass,
                                             int passes, RF_ROW_SPACE const float* e_cam_row,
                                             RF_ROW_SPACE const float* e_proj_row, RF_ROW_SPACE const float* z_tri_row,
                                             RF_ROW_SPACE const unsigned char* run_row, RF_ROW_SPACE float* z_row,
                                             RfRunState* state) {
  const unsigned int code = run_row[u];
  int ok = 1;
  const float increment = code == RF_RUN_CONTINUE ? RF_ROW_FN(rf_rk4_increment)(rig, beta, u - 1, state->z, e_cam_row,
                                                                                e_proj_row, proj_width, &ok)
                                                  : 0.0f;
  RF_ROW_FN(rf_integrate_pixel_step)(u, pass, passes, code, z_tri_row[u], increment, ok, z_row, state);
}
