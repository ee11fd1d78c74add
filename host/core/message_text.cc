// Bounded, printable excerpts of input text.
#include "host/core/message_text.h"

#include <cstdio>

namespace rfrecon {

namespace {
void append_printable(std::string& out, std::string_view text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    }
  }
}
}  // namespace

std::string excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  if (text.size() <= max_chars) {
    append_printable(out, text);
    return out;
  }
  const std::size_t head = max_chars / 2;
  const std::size_t tail = max_chars - head;
  append_printable(out, text.substr(0, head));
  out += " ... (" + std::to_string(text.size()) + " bytes) ... ";
  append_printable(out, text.substr(text.size() - tail));
  return out;
}

}  // namespace rfrecon
