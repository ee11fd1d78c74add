// The access and dependence check over the C simulation (hls_csim_test.cc's tests, run on the tops built with
// RF_CSIM_CHECK): after every test, every pipelined loop of kernels/ has run through the check, no claimed dependence
// distance is violated, no loop touches memory outside its RAMs and AXI bundles, and every loop's accesses allow the
// II its directive claims (at most two accesses
// per RAM, one read and one write per bundle, per II clocks). Writes the table of docs/fpga.md#access-and-dependence-
// check to the file given by RFRECON_CSIM_ACCESS_TABLE, which ctest's fpga_access_docs compares with the docs.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tests/fpga/csim_check.h"

namespace {

// file:line of every pipelined loop's directive in kernels/ (RF_HLS_PIPELINE or RF_HLS_PIPELINE_II at a line's start).
std::set<std::string> pipelined_loops() {
  namespace fs = std::filesystem;
  const fs::path kernels = fs::path(RFRECON_SOURCE_DIR) / "kernels";
  const std::regex directive(R"(^\s*RF_HLS_PIPELINE(_II\(.*\))?\b)");
  std::set<std::string> loops;
  for (const auto& entry : fs::recursive_directory_iterator(kernels)) {
    if (entry.path().extension() != ".h") continue;
    std::ifstream in(entry.path());
    int number = 0;
    for (std::string line; std::getline(in, line);) {
      ++number;
      if (std::regex_search(line, directive)) {
        loops.insert("kernels/" + fs::relative(entry.path(), kernels).generic_string() + ":" + std::to_string(number));
      }
    }
  }
  return loops;
}

class AccessCheck final : public testing::Environment {
 public:
  void TearDown() override {
    const auto loops = rf_csim::loop_uses();
    const std::string table = rf_csim::table(loops);
    std::cout << table;
    std::set<std::string> unchecked = pipelined_loops();
    EXPECT_FALSE(unchecked.empty()) << "no RF_HLS_PIPELINE in " << RFRECON_SOURCE_DIR << "/kernels";
    for (const auto& loop : loops) {
      for (const auto& violation : loop.violations) ADD_FAILURE() << loop.where << ": " << violation;
      EXPECT_LE(loop.initiation_interval(), loop.claimed_ii) << loop.where;
      unchecked.erase(loop.where);
    }
    for (const auto& where : unchecked) ADD_FAILURE() << where << ": a pipelined loop no test ran through the check";
    if (const char* path = std::getenv("RFRECON_CSIM_ACCESS_TABLE")) {
      std::ofstream out(path);
      out << table;
      EXPECT_TRUE(out.good()) << "cannot write " << path;
    }
  }
};

const auto* const registered = testing::AddGlobalTestEnvironment(new AccessCheck);

}  // namespace
