// Mesh files checked before assimp reads them: the format by extension, the size, and every count the file declares.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace rfrecon::sim {

inline constexpr std::size_t kMaxMeshBytes = std::size_t{64} << 20;  // 64 MiB
// Declared elements of a PLY (vertices, faces, ...), vertices of an OBJ, and triangles after triangulation: assimp
// and the BVH hold about 300 bytes per triangle, so 2^22 triangles take about 1.2 GB.
inline constexpr std::uint32_t kMaxMeshElements = 1u << 22;

// What assimp is given of a mesh file: a PLY's bytes, or an OBJ's geometry statements only, and the format ("ply" or
// "obj").
struct MeshFile {
  std::string bytes;
  std::string format;
};

// Reads `file` (a regular file of at most kMaxMeshBytes, check_input_file) after its extension named one of the
// formats above, then checks what it declares before anything allocates for it: a PLY's header and the whole
// element layout it describes (every count and list length must fit in the bytes that follow, each element count
// and the triangles its faces make at most kMaxMeshElements; an ASCII PLY holds one element per line), an OBJ's
// statements, each with a number of values it takes, its vertices and face triangles (at most kMaxMeshElements
// each). Throws InputError "FIELD: mesh FILE: ..." naming the count and the limit.
MeshFile read_mesh_file(const std::filesystem::path& file, const std::string& field);

}  // namespace rfrecon::sim
