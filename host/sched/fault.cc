// Parsing and checking of injected device faults and hangs.
#include "host/sched/fault.h"

#include <charconv>
#include <chrono>
#include <cstdlib>
#include <thread>

#include "host/core/errors.h"

namespace rfrecon::sched {

namespace {
std::size_t parse_count(std::string_view text, std::string_view term) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw InputError(std::string(kInjectFaultEnv) + ": '" + std::string(term) +
                     "' is not [hang:]DEVICE:TILE (DEVICE a number or *, TILE a number from 1)");
  }
  return value;
}

// A device that stops answering: the thread sleeps for good, holding nothing a destructor at exit would wait for.
[[noreturn]] void hang() {
  while (true) std::this_thread::sleep_for(std::chrono::hours(1));
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
    constexpr std::string_view kHang = "hang:";
    Term parsed;
    parsed.hang = term.substr(0, kHang.size()) == kHang;
    const std::string_view target = parsed.hang ? term.substr(kHang.size()) : term;
    const auto colon = target.find(':');
    if (colon == std::string_view::npos) parse_count("x", term);  // throws the grammar message
    const std::string_view device = target.substr(0, colon);
    parsed.every_device = device == "*";
    if (!parsed.every_device) parsed.device = parse_count(device, term);
    parsed.tile = parse_count(target.substr(colon + 1), term);
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
    if ((term.every_device || term.device == device) && term.tile == tile) {
      if (term.hang) hang();
      throw InjectedFault(device, tile);
    }
  }
}

}  // namespace rfrecon::sched
