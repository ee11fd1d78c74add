// The functions of reciprocity.h that read rows, for rows in address space RF_ROW_SPACE, named RF_ROW_FN(name).
// No include guard: reciprocity.h includes this file once per address space (depth/row_space.h).

// Linear interpolation of row[0 .. width-1] at x (pixel centres at integers); 0 outside the row.
RF_INLINE float RF_ROW_FN(rf_sample_row)(RF_ROW_SPACE const float* row, int width, float x) {
  if (!(x >= 0.0f && x <= (float)(width - 1))) return 0.0f;
  const int i = (int)x;
  if (i >= width - 1) return row[width - 1];
  const float t = x - (float)i;
  return row[i] + t * (row[i + 1] - row[i]);
}

// dz/du at column u (fractional) for depth z, given e_cam at u. Sets *ok to 0 where the ODE breaks down (no dual
// signal at the projector column, no camera signal, grazing angle) and returns 0 there.
RF_INLINE float RF_ROW_FN(rf_slope)(RfRectifiedRig rig, float beta, float u, float z, float e_cam,
                                    RF_ROW_SPACE const float* e_proj_row, int proj_width, int* ok) {
  const float a = (u - rig.cx_cam) / rig.f;
  const float x = z * a, y = z * beta;
  const float u_proj = rig.f * (x - rig.b) / z + rig.cx_proj;
  const float e_proj = RF_ROW_FN(rf_sample_row)(e_proj_row, proj_width, u_proj);
  if (!(e_cam > 0.0f && e_proj > 0.0f && z > 0.0f)) {
    *ok = 0;
    return 0.0f;
  }
  // Unit vectors toward the camera (w_c = -X / d_c) and the projector (w_p = (o_p - X) / d_p), scaled by 1 / d^2.
  const float dc2 = x * x + y * y + z * z, dc = RF_SQRT(dc2);
  const float px = rig.b - x, py = -y, pz = -z;
  const float dp2 = px * px + py * py + pz * pz, dp = RF_SQRT(dp2);
  const float kc = e_cam / (dc2 * dc), kp = e_proj / (dp2 * dp);
  const float wx = -kc * x - kp * px, wy = -kc * y - kp * py, wz = -kc * z - kp * pz;
  const float s = RF_SQRT(1.0f + beta * beta);
  const float w_perp = (beta * wy + wz) / s;
  const float denominator = s * wx - a * w_perp;
  const float w_norm = RF_SQRT(wx * wx + wy * wy + wz * wz);
  if (!(RF_FABS(denominator) > RF_GRAZING_LIMIT * w_norm)) {
    *ok = 0;
    return 0.0f;
  }
  return z * w_perp / (rig.f * denominator);
}

// Stage `stage` (0 to 3) of the step from column u (integer) at depth z; e0 and e1 are e_cam at u and u + 1, linearly
// interpolated between the two pixel centres for the midpoint stages. Stage 0 restarts the step.
RF_INLINE void RF_ROW_FN(rf_rk4_stage)(RfRectifiedRig rig, float beta, int u, int stage, float z, float e0, float e1,
                                       RF_ROW_SPACE const float* e_proj_row, int proj_width, RfRk4Stages* rk) {
  if (stage == 0) rk->ok = 1;
  const int midpoint = stage == 1 || stage == 2;
  const float du = stage == 0 ? 0.0f : (midpoint ? 0.5f : 1.0f);
  const float z_at = stage == 0 ? z : (midpoint ? z + 0.5f * rk->k_last : z + rk->k_last);
  const float e_at = stage == 0 ? e0 : (midpoint ? 0.5f * (e0 + e1) : e1);
  const float k = RF_ROW_FN(rf_slope)(rig, beta, (float)u + du, z_at, e_at, e_proj_row, proj_width, &rk->ok);
  rk->sum = stage == 0 ? k : rk->sum + (midpoint ? 2.0f * k : k);
  rk->k_last = k;
}

// The RK4 increment z(u + 1) - z(u) from column u (integer, u + 1 < width) at depth z: its four stages in turn.
// *ok is cleared when any of the four slopes breaks down.
RF_INLINE float RF_ROW_FN(rf_rk4_increment)(RfRectifiedRig rig, float beta, int u, float z,
                                            RF_ROW_SPACE const float* e_cam_row, RF_ROW_SPACE const float* e_proj_row,
                                            int proj_width, int* ok) {
  RfRk4Stages rk = {0.0f, 0.0f, 1};
  const float e0 = e_cam_row[u], e1 = e_cam_row[u + 1];
  // Written out rather than looped, so that every stage's selects fold away.
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 0, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 1, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 2, z, e0, e1, e_proj_row, proj_width, &rk);
  RF_ROW_FN(rf_rk4_stage)(rig, beta, u, 3, z, e0, e1, e_proj_row, proj_width, &rk);
  if (!rk.ok) *ok = 0;
  return rk.sum / 6.0f;
}
