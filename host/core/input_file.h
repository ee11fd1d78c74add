// Inputs are regular files: refused by name before any open that could block (a FIFO) or read forever (a device).
#pragma once

#include <filesystem>
#include <string>

namespace rfrecon {

// Empty when `file`, links followed, is a regular file; else what is wrong, for a message: `when_missing` when
// nothing is there, "is a FIFO (a named pipe); rfrecon reads only regular files" (a socket, a device, a directory).
// Uses stat(2) alone: nothing is opened.
std::string input_file_problem(const std::filesystem::path& file, const std::string& when_missing = "missing");

// Throws InputError "FILE: missing" or "FILE: is a FIFO (a named pipe); rfrecon reads only regular files" (also a
// socket, a device or a directory) unless `file`, links followed, is a regular file. Uses stat(2) alone: nothing is
// opened, so a FIFO with no writer cannot make the command wait.
void check_input_file(const std::filesystem::path& file);

// What `status` is, for messages: "a file", "a directory", "a FIFO (a named pipe)", "a socket", "a character device"...
std::string kind_of_file(const std::filesystem::file_status& status);

}  // namespace rfrecon
