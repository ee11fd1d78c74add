// The checks of a mesh file before assimp: a PLY's header and element layout walked, an OBJ's geometry kept.
#include "sim/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "host/core/errors.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"

namespace rfrecon::sim {

namespace {

// Refusals naming the scene field and the mesh file.
struct Fail {
  std::string prefix;  // "FIELD: mesh FILE: "
  [[noreturn]] void operator()(const std::string& what) const { throw InputError(prefix + what); }
};

std::string limit_text() {
  return "over the limit of " + std::to_string(kMaxMeshElements) + " (docs/formats.md#limits)";
}

// One PLY property: a scalar of `value_bytes`, or a list whose length takes `count_bytes` before its items.
struct PlyProperty {
  std::string name;
  int count_bytes = 0;  // 0: a scalar
  bool count_signed = false;
  int value_bytes = 0;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  std::string format;  // ascii, binary_little_endian or binary_big_endian
  std::vector<PlyElement> elements;
  std::size_t body_start = 0;
};

// The bytes of a PLY scalar type, 0 for an unknown name; `is_signed` set for the signed integer types.
int ply_type_bytes(const std::string& type, bool& is_signed) {
  static const std::vector<std::pair<std::vector<std::string>, int>> kTypes{
      {{"char", "int8", "uchar", "uint8"}, 1},
      {{"short", "int16", "ushort", "uint16"}, 2},
      {{"int", "int32", "uint", "uint32", "float", "float32"}, 4},
      {{"double", "float64"}, 8}};
  is_signed =
      type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
  for (const auto& [names, bytes] : kTypes) {
    if (std::find(names.begin(), names.end(), type) != names.end()) return bytes;
  }
  return 0;
}

// Whether `name` is an identifier: a letter or "_", then letters, digits or "_".
bool is_identifier(const std::string& name) {
  return !name.empty() && std::isdigit(static_cast<unsigned char>(name[0])) == 0 &&
         std::all_of(name.begin(), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; });
}

// "property TYPE NAME" or "property list COUNT_TYPE TYPE NAME", nothing after the name: assimp splits a longer line
// its own way (a list read where this reading saw a scalar).
PlyProperty parse_ply_property(std::istringstream& words, const Fail& fail) {
  std::string type;
  words >> type;
  PlyProperty property;
  bool is_signed = false;
  if (type == "list") {
    std::string count_type;
    words >> count_type >> type;
    property.count_bytes = ply_type_bytes(count_type, property.count_signed);
    if (property.count_bytes == 0 || count_type.find("float") != std::string::npos || count_type == "double") {
      fail("a list length of type '" + excerpt(count_type) + "': an integer type is expected");
    }
  }
  property.value_bytes = ply_type_bytes(type, is_signed);
  if (property.value_bytes == 0) fail("unknown property type '" + excerpt(type) + "'");
  std::string more;
  words >> property.name >> more;
  if (!is_identifier(property.name) || !more.empty()) {
    fail("a property line ends in '" + excerpt(property.name + (more.empty() ? "" : " " + more)) +
         "', not one name (letters, digits and _, not first a digit)");
  }
  return property;
}

// An element count: decimal digits, at most kMaxMeshElements. The element's name must be an identifier (a letter or
// "_", then letters, digits or "_"): assimp reads the count of an element it does not know from the start of its
// name, so "123face 4" would declare 123 elements there and 4 here. And it must be vertex or face: after an element
// assimp does not know, it read a binary body from another offset (a list of 4 billion indices from a 124-byte body).
std::uint64_t parse_ply_count(const std::string& name, const std::string& count, const Fail& fail) {
  if (!is_identifier(name)) {
    fail("the element name '" + excerpt(name) + "' is not an identifier (letters, digits and _, not first a digit)");
  }
  if (name != "vertex" && name != "face") {
    fail("the element '" + excerpt(name) +
         "' is not read: a mesh is its 'vertex' and 'face' elements only (assimp misreads a body after others)");
  }
  if (count.empty() || count.size() > 19 || !std::all_of(count.begin(), count.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) != 0;
      })) {
    fail("element '" + excerpt(name) + "' has the count '" + excerpt(count) + "', not a number");
  }
  const std::uint64_t value = std::stoull(count);
  if (value > kMaxMeshElements) {
    fail("declares " + count + " '" + excerpt(name) + "' elements, " + limit_text());
  }
  return value;
}

PlyHeader parse_ply_header(const std::string& bytes, const Fail& fail) {
  PlyHeader header;
  std::size_t line_start = 0;
  for (int line_number = 1;; ++line_number) {
    const std::size_t line_end = bytes.find('\n', line_start);
    if (line_end == std::string::npos) fail("the header has no end_header line");
    std::string line = bytes.substr(line_start, line_end - line_start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    line_start = line_end + 1;
    // Printable text only, so that this reading and assimp's split the header alike (a vertical tab after
    // end_header would end the header here and not there).
    if (!std::all_of(line.begin(), line.end(), [](char c) { return c >= 0x20 && c <= 0x7e; })) {
      fail("header line " + std::to_string(line_number) + " '" + excerpt(line) + "' holds a byte that is not text");
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (line_number == 1) {
      if (line != "ply") fail("the first line is not 'ply'");
    } else if ((line_number == 2) != (keyword == "format")) {
      // assimp takes the format from the line after "ply" alone.
      fail("header line " + std::to_string(line_number) + " '" + excerpt(line) +
           "': the format line is the second line, and only it");
    } else if (line == "end_header") {
      header.body_start = line_start;
      if (header.format.empty()) fail("the header has no format line");
      return header;
    } else if (keyword == "format") {
      std::string version, more;
      words >> header.format >> version >> more;
      if (header.format != "ascii" && header.format != "binary_little_endian" && header.format != "binary_big_endian") {
        fail("unknown format '" + excerpt(header.format) + "'");
      }
      if (version != "1.0" || !more.empty()) fail("the format line '" + excerpt(line) + "' is not of version 1.0");
    } else if (keyword == "element") {
      std::string name, count, more;
      words >> name >> count >> more;
      if (!more.empty()) fail("the element line '" + excerpt(line) + "' holds more than a name and a count");
      const std::uint64_t declared = parse_ply_count(name, count, fail);
      for (const PlyElement& element : header.elements) {
        if (element.name == name) fail("a second '" + name + "' element");
      }
      header.elements.push_back({name, declared, {}});
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("a property before any element");
      PlyElement& element = header.elements.back();
      const PlyProperty property = parse_ply_property(words, fail);
      if (property.count_bytes != 0 && element.name != "face") {
        fail("the list property '" + property.name + "' of a '" + element.name + "' element (lists are face's)");
      }
      for (const PlyProperty& other : element.properties) {
        if (other.name == property.name) fail("a second property '" + property.name + "' in '" + element.name + "'");
      }
      element.properties.push_back(property);
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      fail("header line " + std::to_string(line_number) + " '" + excerpt(line) + "' is not a PLY header line");
    }
  }
}

// Steps through a PLY body, refusing anything that runs past its end; counts the triangles its lists make.
class PlyBody {
 public:
  PlyBody(const std::string& bytes, const PlyHeader& header, const Fail& fail)
      : bytes_(bytes),
        at_(header.body_start),
        ascii_(header.format == "ascii"),
        big_endian_(header.format == "binary_big_endian"),
        fail_(fail) {
    if (ascii_) check_ascii_text();
  }

  void walk(const PlyElement& element) {
    check_room(element);
    for (std::uint64_t i = 0; i < element.count; ++i) {
      if (ascii_) begin_line();
      for (const PlyProperty& property : element.properties) {
        if (property.count_bytes == 0) {
          skip_values(1, property.value_bytes);
          continue;
        }
        const std::uint64_t length = list_length(property);
        skip_values(length, property.value_bytes);
        triangles_ += length > 2 ? length - 2 : 0;
        if (triangles_ > kMaxMeshElements) {
          fail_("its faces make more than " + std::to_string(kMaxMeshElements) + " triangles, " + limit_text());
        }
      }
      if (ascii_) end_line(element);
    }
  }

 private:
  std::size_t left() const { return bytes_.size() - at_; }

  [[noreturn]] void truncated() const {
    fail_("the header declares more data than the file holds after it (truncated?)");
  }

  // Refuses at once a count whose smallest encoding (1 character and a separator a value in ASCII) cannot fit.
  void check_room(const PlyElement& element) const {
    std::uint64_t least_bytes = 0;
    for (const PlyProperty& property : element.properties) {
      least_bytes +=
          ascii_ ? 2 : static_cast<std::uint64_t>(property.count_bytes ? property.count_bytes : property.value_bytes);
    }
    if (least_bytes > 0 && element.count > (left() + 1) / least_bytes) {
      fail_("declares " + std::to_string(element.count) + " '" + excerpt(element.name) + "' elements, which need " +
            "at least " + std::to_string(element.count * least_bytes) + " bytes; " + std::to_string(left()) +
            " follow the header");
    }
  }

  // An ASCII body is printable text and white space only: a NUL or other control byte would split tokens one way
  // here and another way in assimp's parser (a list length it reads as 34000000000).
  void check_ascii_text() const {
    for (std::size_t i = at_; i < bytes_.size(); ++i) {
      const auto c = static_cast<unsigned char>(bytes_[i]);
      if ((c < 0x20 || c > 0x7e) && c != '\n' && c != '\r' && c != '\t') {
        fail_("an ASCII PLY holds the byte " + excerpt(std::string_view(bytes_).substr(i, 1)) + " at offset " +
              std::to_string(i) + " (only printable text and white space may follow the header)");
      }
    }
  }

  // An ASCII body holds one element per line, as assimp reads it: a line that ends early or holds more would be split
  // one way here and another way there (a list length read from the next line).
  std::string line_number() const {
    return std::to_string(std::count(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(at_), '\n') + 1);
  }

  void skip_blanks() {
    while (at_ < bytes_.size() && (bytes_[at_] == ' ' || bytes_[at_] == '\t' || bytes_[at_] == '\r')) ++at_;
  }

  void begin_line() {
    skip_blanks();
    if (at_ == bytes_.size()) truncated();
    if (bytes_[at_] == '\n') fail_("line " + line_number() + " is blank (an ASCII PLY holds one element per line)");
  }

  void end_line(const PlyElement& element) {
    skip_blanks();
    if (at_ < bytes_.size() && bytes_[at_] != '\n') {
      fail_("line " + line_number() + " holds more values than a '" + excerpt(element.name) +
            "' element has properties (an ASCII PLY holds one element per line)");
    }
    if (at_ < bytes_.size()) ++at_;
  }

  // The next ASCII token of the current line.
  std::string_view token() {
    skip_blanks();
    if (at_ == bytes_.size()) truncated();
    if (bytes_[at_] == '\n') {
      fail_("line " + line_number() +
            " ends before its element's properties (an ASCII PLY holds one element per line)");
    }
    const std::size_t start = at_;
    while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    return std::string_view(bytes_).substr(start, at_ - start);
  }

  void skip_values(std::uint64_t count, int value_bytes) {
    if (ascii_) {
      for (std::uint64_t i = 0; i < count; ++i) {
        const std::string_view text = token();
        if (text.find_first_not_of("0123456789+-.eE") != std::string_view::npos ||
            text.find_first_of("0123456789") == std::string_view::npos) {
          fail_("line " + line_number() + ": '" + excerpt(text) + "' is not a number");
        }
      }
      return;
    }
    if (count > left() / static_cast<std::uint64_t>(value_bytes)) truncated();
    at_ += static_cast<std::size_t>(count) * static_cast<std::size_t>(value_bytes);
  }

  std::uint64_t list_length(const PlyProperty& property) {
    std::uint64_t length = 0;
    if (ascii_) {
      const std::string_view text = token();
      if (text.size() > 19 || !std::all_of(text.begin(), text.end(),
                                           [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
        fail_("a list length '" + excerpt(text) + "' is not a non-negative integer");
      }
      length = std::stoull(std::string(text));
      const int value_bits = 8 * property.count_bytes - (property.count_signed ? 1 : 0);
      if (value_bits < 64 && length >> value_bits != 0) {
        fail_("a list length " + std::string(text) + " does not fit its declared " +
              std::to_string(property.count_bytes) + "-byte type");
      }
      if (length > (left() + 1) / 2) {
        fail_("a list of " + std::string(text) + " items, more than the " + std::to_string(left()) +
              " bytes after it hold");
      }
      return length;
    }
    if (left() < static_cast<std::size_t>(property.count_bytes)) truncated();
    for (int i = 0; i < property.count_bytes; ++i) {
      const int byte = big_endian_ ? i : property.count_bytes - 1 - i;
      length = length << 8 | static_cast<unsigned char>(bytes_[at_ + static_cast<std::size_t>(byte)]);
    }
    at_ += static_cast<std::size_t>(property.count_bytes);
    const std::uint64_t sign_bit = std::uint64_t{1} << (8 * property.count_bytes - 1);
    if (property.count_signed && (length & sign_bit) != 0) fail_("a negative list length");
    if (length > left() / static_cast<std::uint64_t>(property.value_bytes)) {
      fail_("a list of " + std::to_string(length) + " items, more than the " + std::to_string(left()) +
            " bytes after it hold");
    }
    return length;
  }

  const std::string& bytes_;
  std::size_t at_;
  bool ascii_;
  bool big_endian_;
  const Fail& fail_;
  std::uint64_t triangles_ = 0;
};

void check_ply(const std::string& bytes, const Fail& fail) {
  const PlyHeader header = parse_ply_header(bytes, fail);
  PlyBody body(bytes, header, fail);
  for (const PlyElement& element : header.elements) body.walk(element);
}

// Whether `word` can be an OBJ number ("-1.5e3": digits, signs, ".", "e") or, with `corner` set, a face corner
// ("3", "-2", "3/1", "3//2": digits, "-" and at most two "/"). A cheap filter, not a parse: assimp parses.
bool obj_word_fits(const std::string& word, bool corner) {
  const char* allowed = corner ? "0123456789-/" : "0123456789+-.eE";
  return word.find_first_not_of(allowed) == std::string::npos &&
         word.find_first_of("0123456789") != std::string::npos &&
         (!corner || std::count(word.begin(), word.end(), '/') <= 2);
}

// The geometry of an OBJ, checked line by line, as the text assimp is given: its vertices' positions and its faces'
// vertex indices only, one per line, so that few of assimp's paths see the file: its OBJ parser crashes on some
// malformed text (a NUL even in a comment, a material library line continued with "\\"), and its importer wrote past
// its buffers on lines and points mixed with faces (assimp pull requests 1654 and 5112, the latter after Debian's
// 5.2.5). The statements v, vt, vn, vp (numbers) and f, l, p (corners) must each hold a number of values it takes;
// vt, vn, vp, l, p are then dropped with comments and o, g, s, usemtl, mtllib (rfrecon takes the triangles; materials
// come from the scene), and each face corner keeps its vertex index, which must name a vertex of the file (1 to their
// count, or -1 back to the first; made absolute). No control bytes but tabs, only ASCII outside comments; lines joined
// where one ends in "\\".
std::string obj_geometry(const std::string& bytes, const Fail& fail) {
  // Each statement's keyword with the fewest and most values it may hold.
  static const std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> kArity{
      {"v", {3, 7}},          {"vt", {1, 3}},         {"vn", {3, 3}},        {"vp", {1, 3}},
      {"f", {3, UINT64_MAX}}, {"l", {2, UINT64_MAX}}, {"p", {1, UINT64_MAX}}};
  static const std::set<std::string> kDropped{"o", "g", "s", "usemtl", "mtllib"};
  std::uint64_t vertices = 0, triangles = 0, highest_index = 0;
  int highest_index_line = 0;
  std::string geometry, statement;
  std::istringstream lines(bytes);
  int line_number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t comment = std::min(line.find('#'), line.size());
    const auto control = [](char c) { return (c >= 0 && c < ' ' && c != '\t') || c == '\x7f'; };
    if (std::any_of(line.begin(), line.end(), control) ||
        std::any_of(line.begin(), line.begin() + static_cast<std::ptrdiff_t>(comment), [](char c) { return c < 0; })) {
      fail("line " + std::to_string(line_number) +
           ": a control byte, or a byte that is not ASCII outside a comment (not an OBJ text file?)");
    }
    const std::string text = line.substr(0, comment);
    if (!text.empty() && text.back() == '\\') {
      statement += text.substr(0, text.size() - 1) + " ";
      continue;
    }
    std::istringstream words(statement + text);
    statement.clear();
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || kDropped.count(keyword) != 0) continue;
    const auto arity = kArity.find(keyword);
    if (arity == kArity.end()) {
      fail("line " + std::to_string(line_number) + ": '" + excerpt(keyword) + "' is not an OBJ statement read");
    }
    const bool corners = keyword == "f" || keyword == "l" || keyword == "p";
    const bool kept = keyword == "v" || keyword == "f";
    std::uint64_t count = 0;
    if (kept) geometry += keyword;
    for (std::string word; words >> word; ++count) {
      if (!obj_word_fits(word, corners)) {
        fail("line " + std::to_string(line_number) + ": '" + excerpt(word) + "' is not " +
             (corners ? "a face corner" : "a number"));
      }
      if (keyword == "v" && count < 3) geometry += ' ' + word;
      if (keyword != "f") continue;
      const std::string index = word.substr(0, word.find('/'));
      const bool relative = !index.empty() && index[0] == '-';
      const std::string digits = index.substr(relative ? 1 : 0);
      const std::uint64_t magnitude =
          digits.empty() || digits.find('-') != std::string::npos || digits.size() > 10 ? 0 : std::stoull(digits);
      if (magnitude == 0 || (relative && magnitude > vertices)) {
        fail("line " + std::to_string(line_number) + ": the face corner '" + excerpt(word) +
             "' names no vertex (1 to the vertices' count, or -1 back to -" + std::to_string(vertices) + ")");
      }
      if (!relative && magnitude > highest_index) {
        highest_index = magnitude;
        highest_index_line = line_number;
      }
      geometry += ' ' + (relative ? std::to_string(vertices + 1 - magnitude) : digits);
    }
    if (kept) geometry += '\n';
    if (count < arity->second.first || count > arity->second.second) {
      fail("line " + std::to_string(line_number) + ": '" + keyword + "' with " + std::to_string(count) +
           " values (it takes " + std::to_string(arity->second.first) +
           (arity->second.second == UINT64_MAX ? " or more" : " to " + std::to_string(arity->second.second)) + ")");
    }
    vertices += keyword == "v" ? 1 : 0;
    triangles += keyword == "f" ? count - 2 : 0;
  }
  if (vertices > kMaxMeshElements) fail(std::to_string(vertices) + " vertices, " + limit_text());
  if (triangles > kMaxMeshElements) fail("its faces make " + std::to_string(triangles) + " triangles, " + limit_text());
  if (highest_index > vertices) {
    fail("line " + std::to_string(highest_index_line) + ": a face names vertex " + std::to_string(highest_index) +
         " of " + std::to_string(vertices));
  }
  return geometry;
}

}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& file, const std::string& field) {
  const Fail fail{field + ": mesh " + file.string() + ": "};
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".ply" && extension != ".obj") {
    fail("the extension '" + excerpt(extension) + "' is not .ply or .obj, the mesh formats read (docs/sim.md)");
  }
  MeshFile mesh{read_input_file(file, kMaxMeshBytes, "a mesh file"), extension.substr(1)};
  if (mesh.format == "ply") {
    check_ply(mesh.bytes, fail);
  } else {
    mesh.bytes = obj_geometry(mesh.bytes, fail);
  }
  return mesh;
}

}  // namespace rfrecon::sim
