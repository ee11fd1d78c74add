// The C simulation's access and dependence check: the hooks of kernels/common/csim_hooks.h and the ThreadSanitizer
// entry points that the instrumented tops call on every load and store (csim_check.h says how).
#include "tests/fpga/csim_check.h"

#include <algorithm>
#include <cstddef>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <pthread.h>

#include "common/csim_hooks.h"

namespace rf_csim {
namespace {

constexpr std::size_t kViolationsKept = 8;  // per loop; the rest are counted

struct Region {
  std::uintptr_t begin = 0, end = 0;  // end unused for a bundle (up to the next bundle's start)
  std::size_t element_bytes = 0;      // a bundle's: one AXI word, its argument's element (a wide struct: one beat)
  std::size_t bank_bytes = 0;         // an on-chip array's blocks, one RAM each
  std::string name;                   // the array, or the bundle
  std::string argument;               // a bundle's argument
  bool bundle = false;
};

// One load or store. A bundle's accesses to one word (`beat`: the argument and the word's index) in one iteration
// are one beat, as a wide word's fields are loaded in pieces; each RAM access counts (beat empty).
struct Touch {
  std::string memory;
  bool write;
  std::string beat;
};

struct Loop {
  LoopUse use;
  std::map<std::string, std::size_t> index;          // memory -> use.memories
  std::uint64_t last_end_event = ~std::uint64_t{0};  // events when its last iteration ended
  std::int64_t iteration = 0;                        // in the current execution
  int safelen = 0;
  std::map<std::string, int> claimed;                           // array -> distance, this execution
  std::unordered_map<std::uintptr_t, std::int64_t> last_write;  // address -> iteration, this execution
  std::int64_t violations_dropped = 0;
};

struct State {
  std::vector<Region> regions;
  std::vector<std::unique_ptr<Loop>> loops;
  std::map<std::pair<std::string, int>, Loop*> by_site;
  std::vector<Loop*> active;                // innermost last
  std::vector<std::vector<Touch>> touches;  // per active iteration
  std::uint64_t events = 0;                 // hook calls so far: tells a loop's next execution from its next iteration
  std::pair<int, std::uint64_t> pending_safelen{0, ~std::uint64_t{0}};  // distance, events when it was given
};

State& state() {
  static State s;
  return s;
}

std::string repository_path(const char* file) {
  const std::string path(file);
  for (const char* top : {"/kernels/", "/hw/", "/tests/"}) {
    const auto at = path.rfind(top);
    if (at != std::string::npos) return path.substr(at + 1);
  }
  return path;
}

bool on_this_stack(std::uintptr_t address) {
  thread_local std::pair<std::uintptr_t, std::uintptr_t> bounds = [] {
    pthread_attr_t attributes;
    void* low = nullptr;
    std::size_t size = 0;
    pthread_getattr_np(pthread_self(), &attributes);
    pthread_attr_getstack(&attributes, &low, &size);
    pthread_attr_destroy(&attributes);
    const auto begin = reinterpret_cast<std::uintptr_t>(low);
    return std::pair{begin, begin + size};
  }();
  return address >= bounds.first && address < bounds.second;
}

const Region kUnknown{0, 0, 0, 0, "memory no RAM or argument holds", "", true};

// The region holding an address: an on-chip RAM by its range, else (off this thread's stack) the argument whose
// start is the nearest below it, else kUnknown. Null for a register (the stack outside every RAM).
const Region* region_of(std::uintptr_t address) {
  const Region* nearest_argument = nullptr;
  for (const Region& r : state().regions) {
    if (!r.bundle && address >= r.begin && address < r.end) return &r;
    if (r.bundle && address >= r.begin && (!nearest_argument || r.begin > nearest_argument->begin)) {
      nearest_argument = &r;
    }
  }
  if (on_this_stack(address)) return nullptr;
  return nearest_argument ? nearest_argument : &kUnknown;
}

void violation(Loop& loop, std::string text) {
  if (loop.use.violations.size() < kViolationsKept) {
    loop.use.violations.push_back(std::move(text));
  } else {
    ++loop.violations_dropped;
  }
}

MemoryUse& memory_use(Loop& loop, const std::string& memory, const Region& region) {
  const auto [at, added] = loop.index.try_emplace(memory, loop.use.memories.size());
  if (added) {
    loop.use.memories.push_back(MemoryUse{});
    loop.use.memories.back().memory = memory;
    loop.use.memories.back().bundle = region.bundle;
  }
  MemoryUse& use = loop.use.memories[at->second];
  if (region.bundle && (" " + use.arguments + ",").find(" " + region.argument + ",") == std::string::npos) {
    use.arguments += (use.arguments.empty() ? "" : ", ") + region.argument;
  }
  return use;
}

void record(const void* at, std::size_t size, bool write) {
  State& s = state();
  ++s.events;
  if (s.active.empty()) return;
  Loop& loop = *s.active.back();
  const auto address = reinterpret_cast<std::uintptr_t>(at);
  const Region* region = region_of(address);
  if (!region) return;
  if (region == &kUnknown) {
    violation(loop, "an access to " + region->name + ", " + std::to_string(size) + " bytes");
    return;
  }
  std::string memory = region->name;
  if (!region->bundle && region->bank_bytes < region->end - region->begin) {
    memory += "[" + std::to_string((address - region->begin) / region->bank_bytes) + "]";
  }
  if (!region->bundle && region->element_bytes > size) {
    memory += "+" + std::to_string((address - region->begin) % region->element_bytes);
  }
  // The distance the loop claims for this memory: safelen for every one, a dependence directive for its array.
  int claimed = loop.safelen;
  if (const auto directive = loop.claimed.find(region->name); !region->bundle && directive != loop.claimed.end()) {
    claimed = std::max(claimed, directive->second);
  }
  MemoryUse& use = memory_use(loop, memory, *region);
  use.claimed_distance = std::max(use.claimed_distance, claimed);
  if (write) {
    loop.last_write[address] = loop.iteration;
  } else if (const auto written = loop.last_write.find(address); written != loop.last_write.end()) {
    const std::int64_t distance = loop.iteration - written->second;
    if (distance > 0) {
      if (use.shortest_distance == 0 || distance < use.shortest_distance) use.shortest_distance = distance;
      if (distance < claimed) {
        violation(loop, memory + ": read at iteration " + std::to_string(loop.iteration) + " what iteration " +
                            std::to_string(written->second) + " wrote, " + std::to_string(distance) +
                            " apart where the loop claims " + std::to_string(claimed));
      }
    }
  }
  const std::string beat =
      region->bundle ? region->argument + "#" + std::to_string((address - region->begin) / region->element_bytes) : "";
  s.touches.back().push_back(Touch{memory, write, beat});
}

// Each memory's reads and writes in the iteration that ends: every load and store the compiled body made (the
// compiler merges the loads it can prove the same, as a tool does; two gathers that happen to meet are two reads).
void close_iteration(Loop& loop, const std::vector<Touch>& touches) {
  std::map<std::string, std::pair<int, int>> counts;
  std::set<std::tuple<std::string, bool, std::string>> beats;
  for (const Touch& t : touches) {
    if (!t.beat.empty() && !beats.insert({t.memory, t.write, t.beat}).second) continue;
    auto& [reads, writes] = counts[t.memory];
    ++(t.write ? writes : reads);
  }
  for (const auto& [memory, count] : counts) {
    MemoryUse& use = loop.use.memories[loop.index.at(memory)];
    use.reads = std::max(use.reads, count.first);
    use.writes = std::max(use.writes, count.second);
    use.accesses = std::max(use.accesses, count.first + count.second);
  }
}

}  // namespace

Iteration::Iteration(const char* file, int line, int claimed_ii) {
  State& s = state();
  auto& loop = s.by_site[{file, line}];
  if (!loop) {
    s.loops.push_back(std::make_unique<Loop>());
    loop = s.loops.back().get();
    loop->use.where = repository_path(file) + ":" + std::to_string(line);
    loop->use.claimed_ii = claimed_ii;
  }
  if (loop->last_end_event == s.events) {
    ++loop->iteration;
  } else {  // something happened since its last iteration: a new execution of the loop
    ++loop->use.executions;
    loop->iteration = 0;
    loop->claimed.clear();
    loop->last_write.clear();
    loop->safelen = s.pending_safelen.second == s.events ? s.pending_safelen.first : 0;
  }
  ++s.events;
  ++loop->use.iterations;
  s.active.push_back(loop);
  s.touches.emplace_back();
}

Iteration::~Iteration() {
  State& s = state();
  Loop& loop = *s.active.back();
  close_iteration(loop, s.touches.back());
  s.touches.pop_back();
  s.active.pop_back();
  loop.last_end_event = ++s.events;
}

Memory::Memory(const void* at, std::size_t bytes, std::size_t element_bytes, int banks, const char* name) : at_(at) {
  const auto begin = reinterpret_cast<std::uintptr_t>(at);
  ++state().events;
  state().regions.push_back(Region{begin, begin + bytes, element_bytes, bytes / banks, name, "", false});
}

Memory::Memory(const void* at, std::size_t element_bytes, const char* argument, const char* bundle) : at_(at) {
  ++state().events;
  state().regions.push_back(Region{reinterpret_cast<std::uintptr_t>(at), 0, element_bytes, 0, bundle, argument, true});
}

Memory::~Memory() {
  auto& regions = state().regions;
  const auto begin = reinterpret_cast<std::uintptr_t>(at_);
  ++state().events;
  // The most recent region from here (a bundle and a RAM never share a start; two bundles may).
  const auto it = std::find_if(regions.rbegin(), regions.rend(), [&](const Region& r) { return r.begin == begin; });
  if (it != regions.rend()) regions.erase(std::next(it).base());
}

void dependence(const void* at, int distance) {
  State& s = state();
  ++s.events;
  if (s.active.empty()) return;
  if (const Region* region = region_of(reinterpret_cast<std::uintptr_t>(at)); region && !region->bundle) {
    s.active.back()->claimed[region->name] = distance;
  }
}

void safelen(int distance) {
  State& s = state();
  s.pending_safelen = {distance, ++s.events};
}

int MemoryUse::initiation_interval() const {
  if (bundle) return std::max({1, reads, writes});
  return std::max(1, (accesses + 1) / 2);
}

int LoopUse::initiation_interval() const {
  int ii = 1;
  for (const MemoryUse& m : memories) ii = std::max(ii, m.initiation_interval());
  return ii;
}

std::vector<LoopUse> loop_uses() {
  std::vector<LoopUse> uses;
  for (const auto& loop : state().loops) {
    uses.push_back(loop->use);
    if (loop->violations_dropped > 0) {
      uses.back().violations.push_back("and " + std::to_string(loop->violations_dropped) + " more");
    }
  }
  return uses;
}

void reset() {
  State& s = state();
  s.loops.clear();
  s.by_site.clear();
}

std::string table(std::vector<LoopUse> loops) {
  // In file and line order, each loop's memories by name: the same table whatever order the compiler's accesses take.
  const auto at = [](const LoopUse& loop) {
    const auto colon = loop.where.rfind(':');
    return std::pair{loop.where.substr(0, colon), std::stoi(loop.where.substr(colon + 1))};
  };
  std::sort(loops.begin(), loops.end(), [&](const LoopUse& a, const LoopUse& b) { return at(a) < at(b); });
  for (LoopUse& loop : loops) {
    std::sort(loop.memories.begin(), loop.memories.end(),
              [](const MemoryUse& a, const MemoryUse& b) { return a.memory < b.memory; });
  }
  std::ostringstream out;
  out << "| loop | II claimed | memory | reads | writes | II allowed | shortest RAW distance | claimed |\n";
  out << "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const LoopUse& loop : loops) {
    for (const MemoryUse& m : loop.memories) {
      out << "| `" << loop.where << "` | " << loop.claimed_ii << " | "
          << (m.bundle ? m.memory + " (AXI: " + m.arguments + ")" : m.memory) << " | " << m.reads << " | " << m.writes
          << " | " << m.initiation_interval() << " | "
          << (m.shortest_distance > 0 ? std::to_string(m.shortest_distance) : "-") << " | "
          << (m.claimed_distance > 0 ? std::to_string(m.claimed_distance) : "-") << " |\n";
    }
  }
  return out.str();
}

}  // namespace rf_csim

// The ThreadSanitizer instrumentation's entry points (GCC and Clang emit these names), for the tops only.
extern "C" {
void __tsan_init() {}
void __tsan_func_entry(void*) {}
void __tsan_func_exit() {}
void __tsan_vptr_update(void**, void*) {}
void __tsan_vptr_read(void**) {}
#define RF_CSIM_TSAN_ACCESS(bytes)                                                   \
  void __tsan_read##bytes(void* at) { rf_csim::record(at, bytes, false); }           \
  void __tsan_write##bytes(void* at) { rf_csim::record(at, bytes, true); }           \
  void __tsan_unaligned_read##bytes(void* at) { rf_csim::record(at, bytes, false); } \
  void __tsan_unaligned_write##bytes(void* at) { rf_csim::record(at, bytes, true); } \
  void __tsan_volatile_read##bytes(void* at) { rf_csim::record(at, bytes, false); }  \
  void __tsan_volatile_write##bytes(void* at) { rf_csim::record(at, bytes, true); }
RF_CSIM_TSAN_ACCESS(1)
RF_CSIM_TSAN_ACCESS(2)
RF_CSIM_TSAN_ACCESS(4)
RF_CSIM_TSAN_ACCESS(8)
RF_CSIM_TSAN_ACCESS(16)
#undef RF_CSIM_TSAN_ACCESS
void __tsan_read_range(void* at, unsigned long bytes) { rf_csim::record(at, bytes, false); }
void __tsan_write_range(void* at, unsigned long bytes) { rf_csim::record(at, bytes, true); }
}
