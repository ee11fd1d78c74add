// The functions of row_integration.h, for the kind of row of depth/row_kind_*.h, named RF_ROW_FN(name). No include
// guard: row_integration.h includes this file once per kind of row (depth/row_space.h).

RF_INLINE void RF_ROW_FN(rf_run_state_init)(RF_LANE_TYPE(RfRunState) * state) {
  state->start = -1;
  state->count = 0;
  state->sum_rel = 0.0f;
  state->seed = 0.0f;
  state->z = 0.0f;
}

// Ends the current run where `closes` is set; before the last pass (rescale_seed), rescales its seed by its mean
// relative residual. A plain write of the seed kept in the state (z_row[start] holds that seed), so no
// read-modify-write of the row.
RF_INLINE void RF_ROW_FN(rf_close_run)(RF_LANE_TYPE(RfRunState) * state, RF_ROW_SPACE float* z_row, RF_INT closes,
                                       int rescale_seed) {
  const RF_INT rescale = closes & (state->start >= 0) & (state->count > 0);
  if (rescale_seed) {
    RF_STORE_IF(z_row, rescale, state->start, state->seed * (1.0f + state->sum_rel / RF_TO_REAL(state->count)));
  }
  state->start = RF_SELECT(RF_INT, closes, -1, state->start);
}

// Pixel u of pass `pass` (of `passes`) given its run code, its triangulated depth, what z_row held at u before this
// pass wrote it (z_before: the seed the pass before left there) and the RK4 increment into it from u - 1 at state->z
// (used only where the run continues; ok cleared where the step broke down).
RF_INLINE void RF_ROW_FN(rf_integrate_pixel_step)(int u, int pass, int passes, RF_INT code, RF_REAL z_tri,
                                                  RF_REAL z_before, RF_REAL increment, RF_INT ok,
                                                  RF_ROW_SPACE float* z_row, RF_LANE_TYPE(RfRunState) * state) {
  const RF_INT masked = code == RF_RUN_MASKED, starts = code == RF_RUN_START, continues = code == RF_RUN_CONTINUE;
  RF_ROW_FN(rf_close_run)(state, z_row, code != RF_RUN_CONTINUE, pass + 1 < passes);
  // A run starting here starts from its triangulated depth, then from the seed the pass before left in z_row.
  const RF_REAL z_start = pass == 0 ? z_tri : z_before;
  state->start = RF_SELECT(RF_INT, starts, u, state->start);
  state->count = RF_SELECT(RF_INT, starts, 0, state->count);
  state->sum_rel = RF_SELECT(RF_REAL, starts, 0.0f, state->sum_rel);
  state->seed = RF_SELECT(RF_REAL, starts, z_start, state->seed);
  state->z = RF_SELECT(RF_REAL, starts, z_start, RF_SELECT(RF_REAL, continues & ok, state->z + increment, state->z));
  RF_STORE(z_row, u, RF_SELECT(RF_REAL, masked, NAN, state->z));
  const RF_INT measured = (code != RF_RUN_MASKED) & (z_tri == z_tri);  // z_tri not NaN
  state->sum_rel += RF_SELECT(RF_REAL, measured, (z_tri - state->z) / state->z, 0.0f);
  state->count = RF_SELECT(RF_INT, measured, state->count + 1, state->count);
}

// One pixel u of pass `pass` (of `passes`). Rows are given as pointers to their first element. The increment from
// u - 1 is evaluated at every pixel (from column 0 at u = 0) and used only where the run continues.
RF_INLINE void RF_ROW_FN(rf_integrate_pixel)(RfRectifiedRig rig, RF_REAL beta, int u, int proj_width, int pass,
                                             int passes, RF_ROW_SPACE const float* e_cam_row,
                                             RF_ROW_SPACE const float* e_proj_row, RF_ROW_SPACE const float* z_tri_row,
                                             RF_ROW_SPACE const unsigned char* run_row, RF_ROW_SPACE float* z_row,
                                             RF_LANE_TYPE(RfRunState) * state) {
  const RF_INT code = RF_LOAD_CODE(run_row, u);
  RF_INT ok = RF_TRUE;
  RF_REAL increment = 0.0f;
  if (RF_ANY(code == RF_RUN_CONTINUE)) {  // used only where the run continues
    const int from = RF_MAX_INT(u - 1, 0);
    increment = RF_ROW_FN(rf_rk4_increment)(rig, beta, from, state->z, RF_LOAD(e_cam_row, from),
                                            RF_LOAD(e_cam_row, from + 1), e_proj_row, 0, proj_width, &ok);
  }
  const RF_REAL z_before = pass == 0 ? 0.0f : RF_LOAD(z_row, u);
  RF_ROW_FN(rf_integrate_pixel_step)
  (u, pass, passes, code, RF_LOAD(z_tri_row, u), z_before, increment, ok, z_row, state);
}

// The whole row: `passes` shooting passes (>= 1) over every run. Writes z_row (NaN where masked).
RF_INLINE void RF_ROW_FN(rf_integrate_row)(RfRectifiedRig rig, RF_REAL beta, int width, int proj_width, int passes,
                                           RF_ROW_SPACE const float* e_cam_row, RF_ROW_SPACE const float* e_proj_row,
                                           RF_ROW_SPACE const float* z_tri_row,
                                           RF_ROW_SPACE const unsigned char* run_row, RF_ROW_SPACE float* z_row) {
  for (int pass = 0; pass < passes; ++pass) {
    RF_LANE_TYPE(RfRunState) state;
    RF_ROW_FN(rf_run_state_init)(&state);
    for (int u = 0; u < width; ++u) {
      RF_ROW_FN(rf_integrate_pixel)
      (rig, beta, u, proj_width, pass, passes, e_cam_row, e_proj_row, z_tri_row, run_row, z_row, &state);
    }
    RF_ROW_FN(rf_close_run)(&state, z_row, state.start >= 0, pass + 1 < passes);
  }
}
