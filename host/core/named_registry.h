// A registry of named plug-ins (depth methods, pattern families): the built-ins first, then those registered from
// anywhere (a scanner's own code, a test), in order. Safe to use from several threads and from static initializers.
#pragma once

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/core/errors.h"
#include "host/core/message_text.h"

namespace rfrecon {

// T has `std::string name() const`.
template <typename T>
class NamedRegistry {
 public:
  // `what` names an item in messages ("depth method").
  NamedRegistry(std::string what, std::vector<std::shared_ptr<const T>> built_ins)
      : what_(std::move(what)), items_(std::move(built_ins)) {}

  // Throws std::invalid_argument when `item` is null or its name is taken.
  void add(std::shared_ptr<const T> item) {
    if (!item) throw std::invalid_argument("register " + what_ + ": none given");
    const std::scoped_lock lock(mutex_);
    for (const auto& known : items_) {
      if (known->name() == item->name()) {
        throw std::invalid_argument("register " + what_ + ": '" + item->name() + "' is registered already");
      }
    }
    items_.push_back(std::move(item));
  }

  // Throws InputError "unknown WHAT 'NAME' (the names)" when none has the name.
  const T& find(const std::string& name) const {
    const std::scoped_lock lock(mutex_);
    std::string names;
    for (const auto& item : items_) {
      if (item->name() == name) return *item;
      names += (names.empty() ? "" : ", ") + item->name();
    }
    throw InputError("unknown " + what_ + " '" + excerpt(name) + "' (" + names + ")");
  }

  std::vector<std::string> names() const {
    const std::scoped_lock lock(mutex_);
    std::vector<std::string> names;
    names.reserve(items_.size());
    for (const auto& item : items_) names.push_back(item->name());
    return names;
  }

 private:
  mutable std::mutex mutex_;
  std::string what_;
  std::vector<std::shared_ptr<const T>> items_;
};

}  // namespace rfrecon
