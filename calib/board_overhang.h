// Whether the checkerboard in an image continues beyond the detected corners: evidence that --board is too small.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "calib/rig.h"

namespace rfrecon::calib {

// Lines of inner corners that the printed board continues by beyond the detected grid, on each of its sides, in the
// grid's own order (columns along BoardSpec::cols). 0 where the board ends there or where the image cannot tell
// (the side leaves the image, is occluded or too distorted to extrapolate): a count is never more than the evidence.
struct BoardOverhang {
  int before_first_column = 0;
  int after_last_column = 0;
  int before_first_row = 0;
  int after_last_row = 0;
  bool any() const;
  // e.g. "1 more column of corners after the last, 2 more rows before the first"
  std::string describe() const;
};

// The most lines of corners a side is searched for beyond the detected grid (extrapolation error grows with each).
inline constexpr int kMaxOverhangLines = 12;

// Each side's overhang: a homography fitted to the grid's three outer lines of corners on that side (to a tenth of a
// square, or the side says nothing) predicts the squares around them ring by ring. A ring continues the checkerboard
// when at least half its squares lie in the image, their levels alternate in the grid's parity (every square on its
// colour's side of the ring's mean) and their contrast is at least kRingContrastShare of that of the squares just
// inside the grid, which must alternate too. The first ring beyond (the board's border squares) must continue it, or
// the side says nothing; each further ring that does is a line of corners the detector left out. A grid whose steps
// along a line jump (a false detection) has no overhang.
inline constexpr double kRingContrastShare = 0.25;
BoardOverhang board_overhang(const cv::Mat& image, const BoardSpec& board, const std::vector<cv::Point2f>& corners);

// One view whose board continues beyond its detected corners.
struct ViewOverhang {
  std::string view;
  BoardOverhang overhang;
};

// Throws ProcessingError when any view's board continues beyond its detected corners (the detector found a smaller
// board inside the printed one): the message names --board, the views with their evidence (the first three), and
// the smallest board that the evidence allows.
void check_board_fits(const std::vector<ViewOverhang>& overhangs, const BoardSpec& board, std::size_t views_found);

}  // namespace rfrecon::calib
