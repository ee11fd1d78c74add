// Regular-file and directory checks of inputs by stat(2), before anything opens them.
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

void check_input_file(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (fs::is_regular_file(status)) return;
  if (!fs::exists(status)) throw InputError(file.string() + ": missing");
  throw InputError(file.string() + ": is " + kind_of_file(status) + "; rfrecon reads only regular files");
}

void check_input_directory(const fs::path& directory) {
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (fs::is_directory(status)) return;
  if (!fs::exists(status)) throw InputError(directory.string() + ": missing");
  throw InputError(directory.string() + ": is " + kind_of_file(status) + ", not a directory");
}

}  // namespace rfrecon
