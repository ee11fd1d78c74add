// Parsing and checking of injected device faults.
#include "host/sched/fault.h"

#include <charconv>
#include <cstdlib>

#include "host/core/errors.h"

namespace rfrecon::sched {

namespace {
std::size_t parse_count(std::string_view text, std::string_view term) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw InputError(std::string(kInjectFaultEnv) + ": '" + std::string(term) +
                     "' is not DEVICE:TILE (DEVICE a number or *, TILE a number from 1)");
  }
  return value;
}
}  // namespace

InjectedFault::InjectedFault(std::size_t device, std::size_t tile)
    : cl::ClError("injected fault (" + std::string(kInjectFaultEnv) + ") on device " + std::to_string(device) +
                      ", tile " + std::to_string(tile),
                  CL_DEVICE_NOT_AVAILABLE, __FILE__, __LINE__) {}

FaultPolicy FaultPolicy::parse(std::string_view spec) {
  std::vector<Term> terms;
  while (!spec.empty()) {
    const auto comma = spec.find(',');
    const std::string_view term = spec.substr(0, comma);
    spec = comma == std::string_view::npos ? std::string_view() : spec.substr(comma + 1);
    const auto colon = term.find(':');
    if (colon == std::string_view::npos) parse_count("x", term);  // throws the grammar message
    Term parsed;
    const std::string_view device = term.substr(0, colon);
    parsed.every_device = device == "*";
    if (!parsed.every_device) parsed.device = parse_count(device, term);
    parsed.tile = parse_count(term.substr(colon + 1), term);
    if (parsed.tile == 0) parse_count("x", term);
    terms.push_back(parsed);
  }
  return FaultPolicy(std::move(terms));
}

FaultPolicy FaultPolicy::from_environment() {
  const char* spec = std::getenv(kInjectFaultEnv);
  return spec != nullptr ? parse(spec) : FaultPolicy();
}

void FaultPolicy::check(std::size_t device, std::size_t tile) const {
  for (const auto& term : terms_) {
    if ((term.every_device || term.device == device) && term.tile == tile) throw InjectedFault(device, tile);
  }
}

}  // namespace rfrecon::sched
