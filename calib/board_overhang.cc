// Checkerboard squares beyond the detected grid, sampled ring by ring through a homography of each side.
#include "calib/board_overhang.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <opencv2/calib3d.hpp>

#include "calib/board_detection.h"
#include "host/core/errors.h"

namespace rfrecon::calib {

bool BoardOverhang::any() const {
  return before_first_column > 0 || after_last_column > 0 || before_first_row > 0 || after_last_row > 0;
}

std::string BoardOverhang::describe() const {
  std::string text;
  const auto add = [&](int lines, const char* kind, const char* where) {
    if (lines == 0) return;
    if (!text.empty()) text += ", ";
    text += std::to_string(lines) + " more " + kind + (lines > 1 ? "s" : "") + " of corners " + where;
  };
  add(before_first_column, "column", "before the first");
  add(after_last_column, "column", "after the last");
  add(before_first_row, "row", "before the first");
  add(after_last_row, "row", "after the last");
  return text;
}

namespace {

// One side of the grid in board coordinates (corner (col, row) at (col, row)): its outer line of corners starts at
// `origin` and runs along `along` for `length` corners; `outward` leaves the grid, which is `depth` lines deep.
struct Side {
  cv::Point2d origin;
  cv::Point2d outward;
  cv::Point2d along;
  int length;
  int depth;
  int BoardOverhang::*lines;
};

std::array<Side, 4> sides_of(const BoardSpec& board) {
  const double last_column = board.cols - 1;
  const double last_row = board.rows - 1;
  return {{{{0, 0}, {-1, 0}, {0, 1}, board.rows, board.cols, &BoardOverhang::before_first_column},
           {{last_column, 0}, {1, 0}, {0, 1}, board.rows, board.cols, &BoardOverhang::after_last_column},
           {{0, 0}, {0, -1}, {1, 0}, board.cols, board.rows, &BoardOverhang::before_first_row},
           {{0, last_row}, {0, 1}, {1, 0}, board.cols, board.rows, &BoardOverhang::after_last_row}}};
}

// Board coordinates to image pixels, fitted (least squares) to the side's three outer lines of corners.
std::optional<cv::Matx33d> image_from_board(const Side& side, const BoardSpec& board,
                                            const std::vector<cv::Point2f>& corners) {
  std::vector<cv::Point2f> board_points;
  std::vector<cv::Point2f> image_points;
  for (int line = 0; line < std::min(3, side.depth); ++line) {
    for (int step = 0; step < side.length; ++step) {
      const cv::Point2d at = side.origin - line * side.outward + step * side.along;
      const auto index = static_cast<std::size_t>(std::lround(at.y) * board.cols + std::lround(at.x));
      board_points.emplace_back(at);
      image_points.push_back(corners[index]);
    }
  }
  const cv::Mat fitted = cv::findHomography(board_points, image_points);
  if (fitted.empty()) return std::nullopt;
  // A grid that a homography does not fit to a tenth of a square is not a board's (a false detection).
  const cv::Matx33d homography(fitted);
  const double square_px =
      cv::norm(image_points[static_cast<std::size_t>(side.length) - 1] - image_points[0]) / (side.length - 1);
  for (std::size_t i = 0; i < board_points.size(); ++i) {
    const cv::Vec3d image = homography * cv::Vec3d(board_points[i].x, board_points[i].y, 1.0);
    const cv::Point2d error(image[0] / image[2] - image_points[i].x, image[1] / image[2] - image_points[i].y);
    if (!(cv::norm(error) < 0.1 * square_px)) return std::nullopt;
  }
  return homography;
}

// The level of `levels` (CV_32F) at `at` by bilinear interpolation; none outside the image.
std::optional<float> level_at(const cv::Mat& levels, cv::Point2d at) {
  if (!(at.x >= 0.0 && at.y >= 0.0 && at.x < levels.cols - 1.0 && at.y < levels.rows - 1.0)) return std::nullopt;
  const int x = static_cast<int>(at.x);
  const int y = static_cast<int>(at.y);
  const auto fx = static_cast<float>(at.x - x);
  const auto fy = static_cast<float>(at.y - y);
  const float top = levels.at<float>(y, x) * (1 - fx) + levels.at<float>(y, x + 1) * fx;
  const float bottom = levels.at<float>(y + 1, x) * (1 - fx) + levels.at<float>(y + 1, x + 1) * fx;
  return top * (1 - fy) + bottom * fy;
}

struct SquareLevel {
  float level;
  bool even;  // (col + row) of the square's first corner is even: the colour of the grid's first square
};

// The mean level over the middle of each square of one ring that lies inside the image: ring 0 lies just inside the
// side's outer line of corners, ring k at k - 1/2 squares beyond it.
std::vector<SquareLevel> ring_levels(const cv::Mat& levels, const cv::Matx33d& homography, const Side& side, int ring) {
  constexpr double kSampleOffset = 0.2;  // squares from the centre: clear of the edges the homography may misplace
  std::vector<SquareLevel> squares;
  for (int step = -1; step < side.length; ++step) {
    const cv::Point2d centre = side.origin + (ring - 0.5) * side.outward + (step + 0.5) * side.along;
    float sum = 0.0f;
    bool inside = true;
    for (const double dx : {-kSampleOffset, 0.0, kSampleOffset}) {
      for (const double dy : {-kSampleOffset, 0.0, kSampleOffset}) {
        const cv::Vec3d image = homography * cv::Vec3d(centre.x + dx, centre.y + dy, 1.0);
        const auto level = level_at(levels, {image[0] / image[2], image[1] / image[2]});
        inside = inside && level.has_value();
        sum += level.value_or(0.0f);
      }
    }
    const auto first_corner_sum = static_cast<long>(std::floor(centre.x) + std::floor(centre.y));
    if (inside) squares.push_back({sum / 9.0f, first_corner_sum % 2 == 0});
  }
  return squares;
}

// Mean level of the even squares less that of the odd ones.
double contrast(const std::vector<SquareLevel>& squares) {
  double even = 0.0;
  double odd = 0.0;
  int evens = 0;
  for (const auto& square : squares) {
    (square.even ? even : odd) += square.level;
    evens += square.even ? 1 : 0;
  }
  const auto odds = static_cast<int>(squares.size()) - evens;
  return evens > 0 && odds > 0 ? even / evens - odd / odds : 0.0;
}

// Whether a ring of a side `length` corners long continues the checkerboard whose squares inside the grid have
// `inner_contrast`: at least half its squares (and kMinRingSquares) inside the image, the same parity, at least
// kRingContrastShare of the contrast, and every square on its parity's side of the ring's mid-level.
bool continues_checkerboard(const std::vector<SquareLevel>& squares, int length, double inner_contrast) {
  constexpr std::size_t kMinRingSquares = 4;
  if (squares.size() < std::max(kMinRingSquares, static_cast<std::size_t>(length + 2) / 2)) return false;
  const double ring_contrast = contrast(squares);
  if (!(ring_contrast / inner_contrast >= kRingContrastShare)) return false;
  double mid = 0.0;
  for (const auto& square : squares) mid += square.level;
  mid /= static_cast<double>(squares.size());
  // The even squares lie above the ring's mean when inner_contrast > 0, below it otherwise.
  return std::all_of(squares.begin(), squares.end(), [&](const SquareLevel& square) {
    return (square.level - mid) * inner_contrast * (square.even ? 1.0 : -1.0) > 0.0;
  });
}

// Lines of corners beyond one side: rings past the border squares (ring 1) that continue the checkerboard.
int side_overhang(const cv::Mat& levels, const Side& side, const BoardSpec& board,
                  const std::vector<cv::Point2f>& corners) {
  const auto homography = image_from_board(side, board, corners);
  if (!homography) return 0;
  const auto inner = ring_levels(levels, *homography, side, 0);
  const double inner_contrast = contrast(inner);
  constexpr double kMinContrastLevels = 1.0;  // of the 8-bit detection image
  // The grid's own squares must be a checkerboard too (a false detection's are not).
  if (!(std::abs(inner_contrast) >= kMinContrastLevels && continues_checkerboard(inner, side.length, inner_contrast))) {
    return 0;
  }
  int lines = 0;
  for (int ring = 1; ring <= kMaxOverhangLines + 1; ++ring) {
    const auto squares = ring_levels(levels, *homography, side, ring);
    if (!continues_checkerboard(squares, side.length, inner_contrast)) break;
    lines = ring - 1;  // ring 1 holds the border squares every board has
  }
  return lines;
}

// Whether consecutive corner steps along every row and column agree within kMaxStepRatio, as perspective and lens
// distortion leave them on a real board; a false detection (corners a square apart, then two) does not.
bool regular_grid(const std::vector<cv::Point2f>& corners, const BoardSpec& board) {
  constexpr double kMaxStepRatio = 1.4;
  const auto at = [&](int col, int row) {
    return corners[static_cast<std::size_t>(row) * static_cast<std::size_t>(board.cols) +
                   static_cast<std::size_t>(col)];
  };
  const auto steps_agree = [&](cv::Point2f a, cv::Point2f b, cv::Point2f c) {
    const double first = cv::norm(b - a);
    const double second = cv::norm(c - b);
    return first < kMaxStepRatio * second && second < kMaxStepRatio * first;
  };
  for (int row = 0; row < board.rows; ++row) {
    for (int col = 0; col < board.cols; ++col) {
      if (col + 2 < board.cols && !steps_agree(at(col, row), at(col + 1, row), at(col + 2, row))) return false;
      if (row + 2 < board.rows && !steps_agree(at(col, row), at(col, row + 1), at(col, row + 2))) return false;
    }
  }
  return true;
}

std::string grid_text(int cols, int rows) { return std::to_string(cols) + "x" + std::to_string(rows); }

}  // namespace

BoardOverhang board_overhang(const cv::Mat& image, const BoardSpec& board, const std::vector<cv::Point2f>& corners) {
  BoardOverhang overhang;
  if (corners.size() != static_cast<std::size_t>(board.cols) * static_cast<std::size_t>(board.rows) ||
      !regular_grid(corners, board)) {
    return overhang;
  }
  cv::Mat levels;
  to_detection_image(image).convertTo(levels, CV_32F);
  for (const auto& side : sides_of(board)) overhang.*side.lines = side_overhang(levels, side, board, corners);
  return overhang;
}

void check_board_fits(const std::vector<ViewOverhang>& overhangs, const BoardSpec& board, std::size_t views_found) {
  if (overhangs.empty()) return;
  int extra_columns = 0;
  int extra_rows = 0;
  std::string evidence;
  constexpr std::size_t kViewsNamed = 3;
  for (std::size_t i = 0; i < overhangs.size(); ++i) {
    const auto& overhang = overhangs[i].overhang;
    extra_columns = std::max(extra_columns, overhang.before_first_column + overhang.after_last_column);
    extra_rows = std::max(extra_rows, overhang.before_first_row + overhang.after_last_row);
    if (i < kViewsNamed) evidence += (i > 0 ? "; " : "") + overhangs[i].view + ": " + overhang.describe();
  }
  if (overhangs.size() > kViewsNamed) evidence += "; and " + std::to_string(overhangs.size() - kViewsNamed) + " more";
  const std::string given = grid_text(board.cols, board.rows);
  throw ProcessingError("--board " + given + ": the printed board continues beyond the detected " + given +
                        " corners in " + std::to_string(overhangs.size()) + " of the " + std::to_string(views_found) +
                        " views where it was found (" + evidence + "): is it " +
                        grid_text(board.cols + extra_columns, board.rows + extra_rows) +
                        "? Give --board the printed board's inner corners, COLSxROWS (its squares less one each way)");
}

}  // namespace rfrecon::calib
