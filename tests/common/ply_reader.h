// Test helper: a minimal reader of binary little-endian PLY vertex lists with float and uchar properties, written
// independently of host/core/ply.cc so that the writer is checked against the format, not against itself.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rfrecon::testing {

struct PlyVertices {
  std::vector<std::string> header_lines;  // between "ply" and "end_header", exclusive
  std::vector<std::string> properties;    // in file order
  std::vector<std::string> types;         // "float" or "uchar", per property
  std::size_t count = 0;
  std::vector<float> values;  // count x properties.size(), row-major (uchar values as floats)
  std::size_t trailing_bytes = 0;
  float at(std::size_t vertex, std::size_t property) const { return values[vertex * properties.size() + property]; }
};

inline PlyVertices read_ply_vertices(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string end = "end_header\n";
  const auto end_at = bytes.find(end);
  if (bytes.rfind("ply\n", 0) != 0 || end_at == std::string::npos) throw std::runtime_error("not a PLY file");
  PlyVertices ply;
  std::istringstream header(bytes.substr(4, end_at - 4));
  for (std::string line; std::getline(header, line);) {
    ply.header_lines.push_back(line);
    std::istringstream words(line);
    std::string keyword, type, name;
    words >> keyword;
    if (keyword == "element") {
      words >> type >> ply.count;
      if (type != "vertex") throw std::runtime_error("unexpected element " + type);
    } else if (keyword == "property") {
      words >> type >> name;
      if (type != "float" && type != "uchar") throw std::runtime_error("unexpected property type " + type);
      ply.properties.push_back(name);
      ply.types.push_back(type);
    }
  }
  const std::size_t body = end_at + end.size();
  std::size_t stride = 0;
  for (const auto& type : ply.types) stride += type == "float" ? 4 : 1;
  const std::size_t needed = ply.count * stride;
  if (bytes.size() < body + needed) throw std::runtime_error("truncated PLY body");
  std::size_t at = body;
  for (std::size_t vertex = 0; vertex < ply.count; ++vertex) {
    for (const auto& type : ply.types) {
      if (type == "uchar") {
        ply.values.push_back(static_cast<float>(static_cast<unsigned char>(bytes[at++])));
        continue;
      }
      std::uint32_t bits = 0;
      for (int b = 3; b >= 0; --b) bits = (bits << 8) | static_cast<unsigned char>(bytes[at + b]);
      at += 4;
      float value = 0.0f;
      std::memcpy(&value, &bits, sizeof value);
      ply.values.push_back(value);
    }
  }
  ply.trailing_bytes = bytes.size() - body - needed;
  return ply;
}

}  // namespace rfrecon::testing
