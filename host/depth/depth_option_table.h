// The depth stage's tuning options by name, with their documented ranges: the one table that `rfrecon reconstruct`
// turns into flags and the front door checks and sets by name (docs/cli.md#option-ranges).
#pragma once

#include <string>
#include <vector>

#include "host/depth/reconstruct_depth.h"

namespace rfrecon::depth {

struct DepthOptionSpec {
  const char* name;  // the flag without "--" ("epipolar-tolerance"), as summary.json's options name it
  const char* help;
  double low, high;  // the accepted range, both ends included
  // Where the value lives: exactly one of the two is set.
  float* (*real)(DepthOptions&);
  int* (*whole)(DepthOptions&);
};

// Every tuning option (rectification, segmentation, integration, fusion), in the order of `rfrecon reconstruct --help`.
const std::vector<DepthOptionSpec>& depth_option_table();

// Sets option `name` of `options` to `value`. Throws UsageError naming the option and its range for a value outside
// it (or not whole, for a whole option), and one listing the names for an unknown name.
void set_depth_option(DepthOptions& options, const std::string& name, double value);

// Throws UsageError, as set_depth_option, for the first option of `options` outside its range.
void check_depth_options(const DepthOptions& options);

}  // namespace rfrecon::depth
