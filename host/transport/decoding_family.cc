// The registry of decoding families, with the built-in one.
#include "host/transport/decoding_family.h"

#include <utility>

#include "host/core/named_registry.h"
#include "host/transport/graycode_decoding.h"
#include "host/transport/phase_decoding.h"

namespace rfrecon::transport {

namespace {
NamedRegistry<DecodingFamily>& registry() {
  static NamedRegistry<DecodingFamily> instance("decoding family", {graycode_decoding(), phase_decoding()});
  return instance;
}
}  // namespace

const DecodingFamily& decoding_family(const std::string& name) { return registry().find(name); }

void register_decoding_family(std::shared_ptr<const DecodingFamily> family) { registry().add(std::move(family)); }

}  // namespace rfrecon::transport
