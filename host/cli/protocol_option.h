// The pattern sequence on the command line: --family (any registered pattern family), the graycode family's
// --dot-spacing and the families' parameters, for `patterns`, `capture` and (the parameters) `simulate`.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

#include "host/capture/protocol.h"

namespace rfrecon::cli {

// Adds the options to `command`; after parsing, `protocol` (held by the caller for as long as the command) has the
// family and dot spacing, the latter 8 for graycode and 0 for other families unless given.
void add_protocol_options(CLI::App& command, const std::shared_ptr<capture::ProtocolOptions>& protocol);

// One option per parameter of every registered family (--phase-steps ...), each given one stored in `parameters`.
void add_family_parameter_options(CLI::App& command, const std::shared_ptr<std::map<std::string, int>>& parameters);

}  // namespace rfrecon::cli
