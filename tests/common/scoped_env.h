// An environment variable set for one scope in a test, then restored.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace rfrecon::testing {

// Sets (or, given nullptr, unsets) an environment variable for one scope (the scheduler reads RFRECON_INJECT_FAULT
// and RFRECON_TILE_TIMEOUT from it, as the commands do), then restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace rfrecon::testing
