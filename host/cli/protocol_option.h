// The pattern sequence on the command line: --family (any registered pattern family) and the graycode family's
// --dot-spacing, for `patterns` and `capture`.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

#include "host/capture/protocol.h"

namespace rfrecon::cli {

// Adds the options to `command`; after parsing, `protocol` (held by the caller for as long as the command) has the
// family and dot spacing, the latter 8 for graycode and 0 for other families unless given.
void add_protocol_options(CLI::App& command, const std::shared_ptr<capture::ProtocolOptions>& protocol);

}  // namespace rfrecon::cli
