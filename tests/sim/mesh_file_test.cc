// Mesh and scene files are refused by name before anything is allocated for what they declare: counts that cannot
// fit in the file or pass the limits, formats other than PLY and OBJ, inputs that are not regular files.
#include "sim/mesh_file.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "host/core/errors.h"
#include "host/core/limits.h"
#include "sim/builtin_scenes.h"
#include "sim/objects.h"
#include "sim/scene.h"
#include "tests/common/temp_dir.h"
#include "tests/core/refusal_in_child.h"

namespace rfrecon::sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kTriangleVertices = "0 0 0\n1 0 0\n0 1 0\n";

class MeshFileTest : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& bytes) const {
    const fs::path file = dir_ / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }

  static std::string ply_header(const std::string& format, const std::string& vertices, const std::string& faces,
                                const std::string& count_type = "uchar") {
    return "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " + vertices +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces + "\nproperty list " +
           count_type + " int vertex_indices\nend_header\n";
  }

  // The InputError of load_mesh in a child process (tests/core/refusal_in_child.h).
  static std::string mesh_error(const fs::path& file) {
    return rfrecon::testing::refusal_in_child([&] { (void)load_mesh(file.string(), 1.0, "objects[0].file"); });
  }

  rfrecon::testing::TempDir temp_{"mesh_file"};
  const fs::path dir_ = temp_.path();
};

TEST_F(MeshFileTest, SmallPlyAndObjLoad) {
  const auto ascii =
      load_mesh(write("a.ply", ply_header("ascii", "3", "1") + kTriangleVertices + "3 0 1 2\n").string(), 2.0, "f");
  EXPECT_EQ(ascii->triangles.size(), 1u);
  std::string binary = ply_header("binary_little_endian", "3", "1");
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    binary.append(reinterpret_cast<const char*>(&v), 4);
  binary += '\3';
  for (const std::int32_t i : {0, 1, 2}) binary.append(reinterpret_cast<const char*>(&i), 4);
  EXPECT_EQ(load_mesh(write("b.ply", binary).string(), 1.0, "f")->triangles.size(), 1u);
  EXPECT_EQ(
      load_mesh(write("q.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").string(), 1.0, "f")->triangles.size(),
      2u);
}

TEST_F(MeshFileTest, HugeDeclaredCountsAreRefusedBeforeAllocating) {
  // Each is a file of under 300 bytes; assimp would reserve gigabytes for it.
  const fs::path over_limit = write("over.ply", ply_header("ascii", "4000000000", "1") + kTriangleVertices);
  EXPECT_THAT(mesh_error(over_limit), HasSubstr("declares 4000000000 'vertex' elements, over the limit of " +
                                                std::to_string(kMaxMeshElements)));
  EXPECT_THAT(mesh_error(write("unfit.ply", ply_header("binary_little_endian", "4000000", "1"))),
              HasSubstr("need at least"));
  std::string long_list = ply_header("binary_little_endian", "0", "1", "uint");
  long_list += std::string(4, '\xff');
  EXPECT_THAT(mesh_error(write("list.ply", long_list)), HasSubstr("a list of 4294967295 items"));
  EXPECT_THAT(mesh_error(write("ascii_list.ply",
                               ply_header("ascii", "3", "1", "uint") + kTriangleVertices + "3000000000 0 1\n")),
              HasSubstr("a list of 3000000000 items"));
  // A length beyond its declared type (uchar), and a NUL that would split tokens differently in assimp's parser.
  EXPECT_THAT(mesh_error(write("ascii_uchar.ply", ply_header("ascii", "3", "1") + kTriangleVertices + "300 0 1\n")),
              HasSubstr("does not fit its declared 1-byte type"));
  EXPECT_THAT(mesh_error(write("ascii_nul.ply",
                               ply_header("ascii", "3", "1") + kTriangleVertices + std::string("3 0\0 1 2\n", 9))),
              HasSubstr("holds the byte \\x00"));
  const fs::path message_file = write("named.ply", ply_header("ascii", "4000000000", "1"));
  const std::string message = mesh_error(message_file);
  EXPECT_THAT(message, HasSubstr("objects[0].file"));
  EXPECT_THAT(message, HasSubstr(message_file.string()));
}

TEST_F(MeshFileTest, TextAssimpMisreadsIsRefused) {
  // assimp takes an unknown element's count from the start of its name: 2222222222 here, not 4.
  std::string digits_name = ply_header("ascii", "3", "1") + kTriangleVertices + "3 0 1 2\n";
  digits_name.replace(digits_name.find("element face"), 12, "element 2222222222face");
  EXPECT_THAT(mesh_error(write("digits.ply", digits_name)), HasSubstr("is not an identifier"));
  // After an element it does not know, assimp read a binary body from another offset.
  std::string edges = ply_header("binary_little_endian", "3", "0");
  edges.replace(edges.find("element face"), 12, "element edge");
  EXPECT_THAT(mesh_error(write("edge.ply", edges)), HasSubstr("the element 'edge' is not read"));
  // Header lines are exactly what PLY 1.0 defines: assimp split longer ones its own way, and a second vertex element
  // or a list in one made it read the body elsewhere than this check walked it.
  const std::string header = ply_header("binary_big_endian", "3", "0");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = header;
    return text.replace(text.find(from), from.size(), to);
  };
  EXPECT_THAT(mesh_error(write("words.ply", with("property float y", "property float y list uchar int z"))),
              HasSubstr("a property line ends in 'y list'"));
  EXPECT_THAT(mesh_error(write("twice.ply", with("element face 0", "element vertex 4"))),
              HasSubstr("a second 'vertex' element"));
  EXPECT_THAT(mesh_error(write("list.ply", with("property float z", "property list uchar float z"))),
              HasSubstr("the list property 'z' of a 'vertex' element"));
  EXPECT_THAT(mesh_error(write("same.ply", with("property float y", "property float x"))),
              HasSubstr("a second property 'x' in 'vertex'"));
  EXPECT_THAT(mesh_error(write("version.ply", with(" 1.0", " 1ed"))), HasSubstr("is not of version 1.0"));
  EXPECT_THAT(mesh_error(write("format.ply", with("end_header", "format ascii 1.0\nend_header"))),
              HasSubstr("the format line is the second line, and only it"));
  // A NUL in an OBJ comment crashed assimp's OBJ parser; UTF-8 in a comment is text and loads.
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_THAT(mesh_error(write("nul.obj", std::string("# a\0b\nmtllib x.mtl\n", 18) + triangle)),
              HasSubstr("line 1: a control byte"));
  EXPECT_EQ(mesh_error(write("utf8.obj", "# caf\xc3\xa9 by J\xc3\xb6rg\n" + triangle)), "(no InputError)");
  EXPECT_THAT(mesh_error(write("latin.obj", "g caf\xc3\xa9\n" + triangle)), HasSubstr("not ASCII outside a comment"));
}

TEST_F(MeshFileTest, AsciiPlyIsOneElementPerLine) {
  // assimp reads an ASCII PLY line by line: a face short of its items took its last one, a list length, from the next
  // line here, and assimp read that line as a list of 34294967295 items.
  const std::string header = ply_header("ascii", "3", "2");
  EXPECT_THAT(mesh_error(write("short.ply", header + kTriangleVertices + "4 0 1 2\n34294967295 0 1 2\n")),
              HasSubstr("line 14 ends before its element's properties"));
  EXPECT_THAT(mesh_error(write("long.ply", header + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n")),
              HasSubstr("line 11 holds more values than a 'vertex' element has properties"));
  EXPECT_THAT(mesh_error(write("word.ply", header + "0 0 0\n1 0 0\n0 1*2 0\n3 0 1 2\n3 0 1 2\n")),
              HasSubstr("line 13: '1*2' is not a number"));
  EXPECT_THAT(mesh_error(write("blank.ply", header + kTriangleVertices + "\n3 0 1 2\n3 0 1 2\n")),
              HasSubstr("line 14 is blank"));
  EXPECT_EQ(load_mesh(write("ok.ply", header + kTriangleVertices + "3 0 1 2\r\n 3  2 1 0 \n").string(), 1.0, "f")
                ->triangles.size(),
            2u);
}

TEST_F(MeshFileTest, ObjGeometryOnlyReachesAssimp) {
  // Material libraries (one continued with "\" crashed assimp), groups and names are dropped; the faces stay.
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const fs::path named =
      write("named.obj", "mtllib a\\\nb.mtl\no part\ng left\nusemtl m\ns 1\n" + quad + "f 1 2 3\ng right\nf 1 3 4\n");
  EXPECT_EQ(load_mesh(named.string(), 1.0, "f")->triangles.size(), 2u);
  // Each statement holds as many values as it takes: a vertex of one coordinate corrupted assimp's heap.
  EXPECT_THAT(mesh_error(write("short_v.obj", "v 15\n" + quad + "f 1 2 3\n")),
              HasSubstr("line 1: 'v' with 1 values (it takes 3 to 7)"));
  EXPECT_THAT(mesh_error(write("short_f.obj", quad + "f 1 2\n")), HasSubstr("line 5: 'f' with 2 values (it takes 3"));
  // Normals, texture coordinates, lines and points are checked, then dropped (assimp's importer wrote past its buffers
  // on lines mixed with faces): the faces keep their vertex indices, relative ones made absolute.
  const fs::path mixed = write("mixed.obj", quad + "v 0 0 1 1 0 0\nvt 0 0\nvn 0 0 1\nvp 0.5\nl 1/1 2/1 3/1\np 1 2\n" +
                                                "f 1/1/1 2//1 3/1\nf -5 -3 -2\n");
  const auto mesh = load_mesh(mixed.string(), 1.0, "f");
  ASSERT_EQ(mesh->triangles.size(), 2u);
  const Eigen::Vector3i& relative = mesh->triangles[1];
  EXPECT_EQ(mesh->vertices[relative[0]], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(mesh->vertices[relative[1]], Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(mesh->vertices[relative[2]], Eigen::Vector3d(0, 1, 0));
  // Every face corner names a vertex of the file.
  EXPECT_THAT(mesh_error(write("zero.obj", quad + "f 0 1 2\n")),
              HasSubstr("line 5: the face corner '0' names no vertex"));
  EXPECT_THAT(mesh_error(write("back.obj", quad + "f -5 1 2\n")), HasSubstr("-1 back to -4"));
  EXPECT_THAT(mesh_error(write("past.obj", quad + "f 1 2 5/1\n")), HasSubstr("line 5: a face names vertex 5 of 4"));
  EXPECT_THAT(mesh_error(write("slash.obj", quad + "f /1 2 3\n")), HasSubstr("'/1' names no vertex"));
}

TEST_F(MeshFileTest, TrianglesAfterTriangulationAreCapped) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (std::uint32_t i = 0; i < kMaxMeshElements + 3; ++i) obj += " 1";
  EXPECT_THAT(mesh_error(write("fan.obj", obj + "\n")), HasSubstr("triangles, over the limit"));
}

TEST_F(MeshFileTest, OnlyDocumentedFormatsAndRegularFilesAreRead) {
  EXPECT_THAT(mesh_error(write("box.stl", "solid box\nendsolid box\n")), HasSubstr("not .ply or .obj"));
  const fs::path fifo = dir_ / "box.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(mesh_error(fifo), HasSubstr("FIFO"));
  // A material library the OBJ names is never opened: a FIFO there would block.
  const fs::path mtl_fifo = dir_ / "box.mtl";
  ASSERT_EQ(::mkfifo(mtl_fifo.c_str(), 0600), 0);
  const fs::path with_mtl = write("with_mtl.obj", "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(mesh_error(with_mtl), "(no InputError)");
}

TEST_F(MeshFileTest, SceneInputsAreBoundedAndQuotedCut) {
  const fs::path fifo = dir_ / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(rfrecon::testing::refusal_in_child([&] { (void)resolve_scene(fifo.string()); }),
              HasSubstr(fifo.string() + ": is a FIFO"));
  const std::string key(5000, 'k');
  const fs::path long_key = write("long_key.json", "{\"" + key + "\": 1}");
  const std::string message = rfrecon::testing::refusal_in_child([&] { (void)load_scene_file(long_key); });
  EXPECT_THAT(message, HasSubstr("unknown field"));
  EXPECT_LT(message.size(), long_key.string().size() + 250) << message;
  const fs::path deep = write("deep.json", "{\"objects\": " + std::string(100000, '[') + "}");
  EXPECT_THAT(rfrecon::testing::refusal_in_child([&] { (void)load_scene_file(deep); }),
              HasSubstr("deeper than " + std::to_string(kMaxNestingDepth)));
}

}  // namespace
}  // namespace rfrecon::sim
