// Binary little-endian PLY writer: header text, then each vertex's floats as little-endian bytes and its colour bytes.
#include "host/core/ply.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "host/core/atomic_file.h"
#include "host/core/image_file.h"

namespace rfrecon {

namespace {
void append_little_endian(std::string& bytes, float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((bits >> shift) & 0xffu));
}

void check_map(const cv::Mat& map, int type, cv::Size size, const std::string& what) {
  if (map.type() != type || map.size() != size) {
    throw std::invalid_argument("write_point_cloud_ply: " + what + " must be " + cv::typeToString(type) + " of " +
                                size_text(size));
  }
}

bool is_property_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return name != "x" && name != "y" && name != "z" && name != "nx" && name != "ny" && name != "nz" && name != "u" &&
         name != "v" && name != "red" && name != "green" && name != "blue";
}
}  // namespace

void write_point_cloud_ply(const std::filesystem::path& file, const std::string& comment, const cv::Mat& points,
                           const cv::Mat& normals, const std::vector<PlyScalarMap>& scalars,
                           const cv::Mat& colours_rgb) {
  check_map(points, CV_32FC3, points.size(), "points");
  if (!colours_rgb.empty()) check_map(colours_rgb, CV_8UC3, points.size(), "colours");
  check_map(normals, CV_32FC3, points.size(), "normals");
  for (const auto& scalar : scalars) {
    if (!is_property_name(scalar.name)) {
      throw std::invalid_argument("write_point_cloud_ply: bad property name '" + scalar.name + "'");
    }
    check_map(scalar.values, CV_32F, points.size(), "property '" + scalar.name + "'");
  }
  if (comment.find_first_of("\r\n") != std::string::npos) {
    throw std::invalid_argument("write_point_cloud_ply: the comment must be one line");
  }

  std::string body;
  std::size_t count = 0;
  for (int y = 0; y < points.rows; ++y) {
    for (int x = 0; x < points.cols; ++x) {
      const cv::Vec3f& p = points.at<cv::Vec3f>(y, x);
      if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
      cv::Vec3f n = normals.at<cv::Vec3f>(y, x);
      if (!(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]))) n = cv::Vec3f(0.0f, 0.0f, 0.0f);
      for (const float value : {p[0], p[1], p[2], n[0], n[1], n[2], static_cast<float>(x), static_cast<float>(y)}) {
        append_little_endian(body, value);
      }
      for (const auto& scalar : scalars) {
        const float value = scalar.values.at<float>(y, x);
        append_little_endian(body, std::isfinite(value) ? value : 0.0f);
      }
      if (!colours_rgb.empty()) {
        const cv::Vec3b& rgb = colours_rgb.at<cv::Vec3b>(y, x);
        body.append({static_cast<char>(rgb[0]), static_cast<char>(rgb[1]), static_cast<char>(rgb[2])});
      }
      ++count;
    }
  }

  std::string header = "ply\nformat binary_little_endian 1.0\n";
  if (!comment.empty()) header += "comment " + comment + "\n";
  header += "comment u v: camera pixel (column, row); normal 0 0 0: none estimated\n";
  header += "element vertex " + std::to_string(count) + "\n";
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "u", "v"}) {
    header += std::string("property float ") + name + "\n";
  }
  for (const auto& scalar : scalars) header += "property float " + scalar.name + "\n";
  if (!colours_rgb.empty()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "end_header\n";
  write_file_atomically(file, header + body);
}

}  // namespace rfrecon
