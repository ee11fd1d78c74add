// The dot window arithmetic of transport/compression.h on RF_DOT_INT values, named RF_DOT_FN(name). No include guard:
// compression.h includes it once per integer type (one pixel, or RF_LANES pixels in vector lanes).

#if defined(RF_TARGET_INTEL_FPGA) || defined(RF_TARGET_XILINX_FPGA) || defined(RF_TARGET_HLS)
// x mod s for x >= 0 and s among RF_DOT_SPACINGS: one divider by a constant per supported spacing, no run-time one.
RF_INLINE RF_DOT_INT RF_DOT_FN(rf_mod_spacing)(RF_DOT_INT x, int s) {
  const int spacings[RF_DOT_SPACING_COUNT] = RF_DOT_SPACINGS;
  RF_DOT_INT r = 0;
  RF_UNROLL
  for (int i = 0; i < RF_DOT_SPACING_COUNT; ++i) {
    if (s == spacings[i]) r = x % spacings[i];
  }
  return r;
}
#else
// x mod s for 0 <= x < 2^22 without an integer divider (CPUs divide vector lanes one by one): the truncated float
// quotient is the exact one or one less (at multiples of s), so the remainder is s too large at most
// (CompressionHelpersTest checks every x below 2^16 and those just below 2^22).
RF_INLINE RF_DOT_INT RF_DOT_FN(rf_mod_spacing)(RF_DOT_INT x, int s) {
  const RF_DOT_INT r = x - RF_DOT_TO_INT(RF_DOT_TO_REAL(x) * (1.0f / (float)s)) * s;
  return r >= s ? r - s : r;
}
#endif

// The first coordinate of a pixel's s-wide window and its residue mod s (x0 >= -(s-1)/2 > -s).
RF_INLINE RF_DOT_INT RF_DOT_FN(rf_window_start)(RF_DOT_INT coordinate, int s) { return coordinate - ((s - 1) >> 1); }
RF_INLINE RF_DOT_INT RF_DOT_FN(rf_window_residue)(RF_DOT_INT x0, int s) {
  return x0 >= 0 ? RF_DOT_FN(rf_mod_spacing)(x0, s) : x0 + s;
}

// The lit dot of the offset in the window starting at x0 with residue a.
RF_INLINE RF_DOT_INT RF_DOT_FN(rf_window_dot)(RF_DOT_INT x0, RF_DOT_INT a, int offset, int s) {
  const RF_DOT_INT d = offset - a;
  return x0 + (d < 0 ? d + s : d);
}
