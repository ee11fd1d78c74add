// Input text quoted in messages: bounded in length and printable, however long or binary the input is.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rfrecon {

inline constexpr std::size_t kMaxQuotedChars = 80;

// `text` as a message quotes it: bytes outside printable ASCII as \xNN, and when longer than `max_chars` its first
// and last parts around " ... (N bytes) ... ", so a message stays readable whatever a file holds.
std::string excerpt(std::string_view text, std::size_t max_chars = kMaxQuotedChars);

}  // namespace rfrecon
