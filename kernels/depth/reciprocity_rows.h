// The functions of reciprocity.h that read rows, for the kind of row of depth/row_kind_*.h, named RF_ROW_FN(name).
// No include guard: reciprocity.h includes this file once per kind of row (depth/row_space.h).

// Linear interpolation of row[0 .. width-1] (width >= 2) at x (pixel centres at integers); 0 outside the row. The
// loads are clamped into the row and the result selected.
RF_INLINE RF_REAL RF_ROW_FN(rf_sample_row)(RF_ROW_SPACE const float* row, int width, RF_REAL x) {
  const RF_INT inside = (x >= 0.0f) & (x <= (float)(width - 1));  // false for NaN
  const RF_INT i = RF_SELECT(RF_INT, inside, RF_TO_INT(x), 0);
  const RF_INT i0 = RF_MIN_INT(i, (RF_INT)(width - 2));
  const RF_REAL left = RF_GATHER(row, i0), right = RF_GATHER(row, i0 + 1);
  const RF_REAL t = x - RF_TO_REAL(i);
  const RF_REAL value = RF_SELECT(RF_REAL, i >= width - 1, right, left + t * (right - left));
  return RF_SELECT(RF_REAL, inside, value, 0.0f);
}

// dz/du at column u (fractional) for depth z, given e_cam at u. Clears *ok where the ODE breaks down (no dual signal
// at the projector column, no camera signal, grazing angle) and returns 0 there. Every quantity is computed and the
// result selected (a discarded one may be infinite or NaN).
RF_INLINE RF_REAL RF_ROW_FN(rf_slope)(RfRectifiedRig rig, RF_REAL beta, float u, RF_REAL z, RF_REAL e_cam,
                                      RF_ROW_SPACE const float* e_proj_row, int proj_width, RF_INT* ok) {
  const float a = (u - rig.cx_cam) / rig.f;
  const RF_REAL x = z * a, y = z * beta;
  const RF_REAL u_proj = rig.f * (x - rig.b) / z + rig.cx_proj;
  const RF_REAL e_proj = RF_ROW_FN(rf_sample_row)(e_proj_row, proj_width, u_proj);
  const RF_INT lit = (e_cam > 0.0f) & (e_proj > 0.0f) & (z > 0.0f);
  // Unit vectors toward the camera (w_c = -X / d_c) and the projector (w_p = (o_p - X) / d_p), scaled by 1 / d^2.
  const RF_REAL dc2 = x * x + y * y + z * z, dc = RF_SQRT(dc2);
  const RF_REAL px = rig.b - x, py = -y, pz = -z;
  const RF_REAL dp2 = px * px + py * py + pz * pz, dp = RF_SQRT(dp2);
  const RF_REAL kc = e_cam / (dc2 * dc), kp = e_proj / (dp2 * dp);
  const RF_REAL wx = -kc * x - kp * px, wy = -kc * y - kp * py, wz = -kc * z - kp * pz;
  const RF_REAL s = RF_SQRT(1.0f + beta * beta);
  const RF_REAL w_perp = (beta * wy + wz) / s;
  const RF_REAL denominator = s * wx - a * w_perp;
  const RF_REAL w_norm = RF_SQRT(wx * wx + wy * wy + wz * wz);
  const RF_INT valid = lit & (RF_FABS(denominator) > RF_GRAZING_LIMIT * w_norm);
  *ok = *ok & valid;
  return RF_SELECT(RF_REAL, valid, z * w_perp / (rig.f * denominator), 0.0f);
}

// Stage `stage` (0 to 3) of the step from column u (integer) at depth z; e0 and e1 are e_cam at u and u + 1, linearly
// interpolated between the two pixel centres for the midpoint stages. Stage 0 restarts the step.
RF_INLINE void RF_ROW_FN(rf_rk4_stage)(RfRectifiedRig rig, RF_REAL beta, int u, int stage, RF_REAL z, RF_REAL e0,
                                       RF_REAL e1, RF_ROW_SPACE const float* e_proj_row, int proj_width,
                                       RF_LANE_TYPE(RfRk4Stages) * rk) {
  if (stage == 0) rk->ok = RF_TRUE;
  const int midpoint = stage == 1 || stage == 2;
  const float du = stage == 0 ? 0.0f : (midpoint ? 0.5f : 1.0f);
  const RF_REAL z_at = stage == 0 ? z : (midpoint ? z + 0.5f * rk->k_last : z + rk->k_last);
  const RF_REAL e_at = stage == 0 ? e0 : (midpoint ? 0.5f * (e0 + e1) : e1);
  const RF_REAL k = RF_ROW_FN(rf_slope)(rig, beta, (float)u + du, z_at, e_at, e_proj_row, proj_width, &rk->ok);
  rk->sum = stage == 0 ? k : rk->sum + (midpoint ? 2.0f * k : k);
  rk->k_last = k;
}

// The RK4 increment z(u + 1) - z(u) from column u (integer, u + 1 < width) at depth z: its four stages in turn.
// *ok is cleared when any of the four slopes breaks down.
RF_INLINE RF_REAL RF_ROW_FN(rf_rk4_increment)(RfRectifiedRig rig, RF_REAL beta, int u, RF_REAL z,
                                              RF_ROW_SPACE const float* e_cam_row, RF_ROW_SPACE const float* e_proj_row,
                                              int proj_width, RF_INT* ok) {
  RF_LANE_TYPE(RfRk4Stages) rk;
  rk.k_last = 0.0f;
  rk.sum = 0.0f;
  rk.ok = RF_TRUE;
  const RF_REAL e0 = RF_LOAD(e_cam_row, u), e1 = RF_LOAD(e_cam_row, u + 1);
  // Written out rather than looped, so that every stage's selects fold away.
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 0, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 1, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 2, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 3, z, e0, e1, e_proj_row, proj_width, &rk);
  *ok = *ok & rk.ok;
  return rk.sum / 6.0f;
}
