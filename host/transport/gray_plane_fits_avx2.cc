// The plane fits in AVX2's 256-bit lanes with FMA, for the CPUs that have both: built where host/transport/
// CMakeLists.txt gives this file AVX2's flags and OpenCV's dispatch macros (its intrinsics then live in namespace
// cv::hal_AVX2, apart from the baseline's), empty elsewhere.
#ifdef RFRECON_GRAY_FITS_AVX2
#include <immintrin.h>
#define RFRECON_SIMD_NAMESPACE avx2
#include "host/transport/gray_plane_fits.simd.h"
#undef RFRECON_SIMD_NAMESPACE
#endif
