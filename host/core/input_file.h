// Inputs are regular files: refused by name before any open that could block (a FIFO) or read forever (a device).
#pragma once

#include <filesystem>
#include <string>

namespace rfrecon {

// Throws InputError "FILE: missing" or "FILE: is a FIFO (a named pipe); rfrecon reads only regular files" (also a
// socket, a device or a directory) unless `file`, links followed, is a regular file. Uses stat(2) alone: nothing is
// opened, so a FIFO with no writer cannot make the command wait.
void check_input_file(const std::filesystem::path& file);

// Throws InputError unless `directory`, links followed, is a directory ("DIR: missing" or "DIR: is a file, not a
// directory").
void check_input_directory(const std::filesystem::path& directory);

// What `status` is, for messages: "a file", "a directory", "a FIFO (a named pipe)", "a socket", "a character device"...
std::string kind_of_file(const std::filesystem::file_status& status);

}  // namespace rfrecon
