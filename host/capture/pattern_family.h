// Pattern families: what a kind of structured light projects and how its captures are laid out. A family makes the
// sequence, renders each pattern, names its files and its manifest entries, and checks that a manifest's frames are
// its whole sequence. One registry lists them for `patterns`, `simulate`, `capture` and the manifest reader; the
// transport stage's side of a family (decoding its frames into T) is host/transport/decoding_family.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include "host/capture/manifest.h"
#include "host/capture/protocol.h"

namespace rfrecon::capture {

// A whole-number option of a family: ProtocolOptions::parameters[name], the manifest's `parameters`, and
// `--NAME` (underscores as dashes) on the command line.
struct FamilyParameter {
  std::string name;  // "phase_steps"
  int default_value = 0;
  int min = 0;
  int max = 0;
  std::string help;
  std::string zero_means{};  // non-empty: 0 is also allowed, and means this (e.g. "Gray code unwrapping")
};

class PatternFamily {
 public:
  virtual ~PatternFamily() = default;
  virtual std::string name() const = 0;  // the manifest's `family`, `--family`
  virtual std::string help() const = 0;  // one line for the commands' help
  // Its parameters; none by default.
  virtual std::vector<FamilyParameter> parameters() const { return {}; }
  // The patterns in projection order, one white and one black among them; options.projector_size is checked already.
  // Throws InputError for an option the family does not take.
  virtual std::vector<Pattern> sequence(const ProtocolOptions& options) const = 0;
  // CV_8UC1 of options.projector_size, 255 = lit.
  virtual cv::Mat render(const Pattern& pattern, const ProtocolOptions& options) const = 0;
  // The file name's part after the sequence number: "gray_col_b02_inv", "dot_03_05".
  virtual std::string file_stem(const Pattern& pattern) const = 0;
  // A manifest frame entry's fields besides "file" and "pattern" (the kind), and back. read_entry sets every field
  // but the kind, and throws InputError starting with `where` (the manifest and the entry) for a missing or mistyped
  // field or a kind that is not the family's.
  virtual void write_entry(const Pattern& pattern, nlohmann::json& entry) const = 0;
  virtual void read_entry(const nlohmann::json& entry, const std::string& where, Pattern& pattern) const = 0;
  // Throws InputError starting with `where` unless the frames are the whole sequence for the manifest's projector
  // size and options, each pattern once (white and black are checked before).
  virtual void validate(const CaptureManifest& manifest, const std::string& where) const = 0;
};

// The family called `name`; InputError listing the registered ones when there is none.
const PatternFamily& pattern_family(const std::string& name);

// The registered families' names: the built-in ones first, then those registered, in order.
std::vector<std::string> pattern_family_names();

// Adds a family (e.g. from a static initializer of a scanner's own code); throws std::invalid_argument when its name
// is taken.
void register_pattern_family(std::shared_ptr<const PatternFamily> family);

// The value of `name`, one of family's parameters, in `options` (its default when not given).
int family_parameter(const PatternFamily& family, const ProtocolOptions& options, const std::string& name);

// Throws InputError starting with `where` when a parameter given is not one of the family's or outside its range.
void check_family_parameters(const PatternFamily& family, const std::map<std::string, int>& parameters,
                             const std::string& where);

// Reading manifest entry fields for read_entry: InputError "<where>field 'KEY' is missing" or "... has the wrong type".
int entry_int(const nlohmann::json& entry, const std::string& key, const std::string& where);
bool entry_bool(const nlohmann::json& entry, const std::string& key, const std::string& where);
std::vector<int> entry_ints(const nlohmann::json& entry, const std::string& key, const std::string& where);

}  // namespace rfrecon::capture
