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
// result selected (a discarded one may be infinite or NaN). The slope and the grazing test depend on the direction of
// w only, so w is scaled by d_c^3 > 0 and both are multiplied through by s: one division and one square root for w
// and the test, where they took three divisions and four square roots (docs/method.md). The squared test stays
// finite while e |X| < 1e18 (the rectified images are scaled to a median e_cam of 1, host/depth/rectification.cc).
RF_INLINE RF_REAL RF_ROW_FN(rf_slope)(RfRectifiedRig rig, RF_REAL beta, float u, RF_REAL z, RF_REAL e_cam,
                                      RF_ROW_SPACE const float* e_proj_row, int proj_width, RF_INT* ok) {
  const float a = (u - rig.cx_cam) / rig.f;
  const RF_REAL x = z * a, y = z * beta;
  const RF_REAL u_proj = rig.f * (x - rig.b) / z + rig.cx_proj;
  const RF_REAL e_proj = RF_ROW_FN(rf_sample_row)(e_proj_row, proj_width, u_proj);
  const RF_INT lit = (e_cam > 0.0f) & (e_proj > 0.0f) & (z > 0.0f);
  // d_c^3 w = -e_cam X - e_proj (d_c / d_p)^3 (o_p - X): w_c = -X / d_c and w_p = (o_p - X) / d_p over d^2.
  const RF_REAL dc2 = x * x + y * y + z * z;
  const RF_REAL px = rig.b - x, py = -y, pz = -z;
  const RF_REAL dp2 = px * px + py * py + pz * pz;
  const RF_REAL ratio2 = dc2 / dp2;
  const RF_REAL kp = e_proj * (ratio2 * RF_SQRT(ratio2));
  const RF_REAL wx = -e_cam * x - kp * px, wy = -e_cam * y - kp * py, wz = -e_cam * z - kp * pz;
  // s w_perp and s (s w_x - a w_perp), s = sqrt(1 + beta^2); the grazing test |s w_x - a w_perp| > limit |w| squared.
  const RF_REAL s2 = 1.0f + beta * beta;
  const RF_REAL w_perp_s = beta * wy + wz;
  const RF_REAL denominator_s = s2 * wx - a * w_perp_s;
  const RF_REAL w_norm2 = wx * wx + wy * wy + wz * wz;
  const RF_INT valid = lit & (denominator_s * denominator_s > (RF_GRAZING_LIMIT * RF_GRAZING_LIMIT) * (s2 * w_norm2));
  *ok = *ok & valid;
  return RF_SELECT(RF_REAL, valid, z * w_perp_s / (rig.f * denominator_s), 0.0f);
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

// The RK4 increment z(u + 1) - z(u) from column u (integer, u + 1 < width) at depth z, e0 and e1 being e_cam at u and
// u + 1: its four stages in turn, stage s reading the projector row at e_proj_row + s * slope_stride (0: one row; the
// fusion's on-chip rows give each slope its own copy, two reads of a RAM per slope). *ok is cleared when any of the
// four slopes breaks down.
RF_INLINE RF_REAL RF_ROW_FN(rf_rk4_increment)(RfRectifiedRig rig, RF_REAL beta, int u, RF_REAL z, RF_REAL e0,
                                              RF_REAL e1, RF_ROW_SPACE const float* e_proj_row, int slope_stride,
                                              int proj_width, RF_INT* ok) {
  RF_LANE_TYPE(RfRk4Stages) rk;
  rk.k_last = 0.0f;
  rk.sum = 0.0f;
  rk.ok = RF_TRUE;
  // Written out rather than looped, so that every stage's selects fold away.
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 0, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 1, z, e0, e1, e_proj_row + slope_stride, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 2, z, e0, e1, e_proj_row + 2 * slope_stride, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 3, z, e0, e1, e_proj_row + 3 * slope_stride, proj_width, &rk);
  *ok = *ok & rk.ok;
  return rk.sum * (1.0f / 6.0f);  // multiplied, not divided: a divider would lengthen the pipelines (docs/fpga.md)
}
