// The SHA-256 of a file's bytes (OpenSSL's EVP digest), read in blocks: for checking that a board binary is the one
// its manifest describes.
#pragma once

#include <filesystem>
#include <string>

namespace rfrecon {

// Lowercase hex. Throws InputError naming the file when it cannot be read.
std::string file_sha256(const std::filesystem::path& file);

}  // namespace rfrecon
