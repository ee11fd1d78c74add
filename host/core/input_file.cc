// Regular-file checks of inputs by stat(2), before anything opens them.
#include "host/core/input_file.h"

#include <system_error>

#include "host/core/errors.h"

namespace rfrecon {

namespace fs = std::filesystem;

std::string kind_of_file(const fs::file_status& status) {
  switch (status.type()) {
    case fs::file_type::regular:
      return "a file";
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::fifo:
      return "a FIFO (a named pipe)";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::not_found:
      return "missing";
    default:
      return "not a regular file";
  }
}

std::string input_file_problem(const fs::path& file, const std::string& when_missing) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (fs::is_regular_file(status)) return "";
  if (!fs::exists(status)) return when_missing;
  return "is " + kind_of_file(status) + "; rfrecon reads only regular files";
}

void check_input_file(const fs::path& file) {
  if (const std::string problem = input_file_problem(file); !problem.empty()) {
    throw InputError(file.string() + ": " + problem);
  }
}

}  // namespace rfrecon
