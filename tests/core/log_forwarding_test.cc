// ScopedLogForwarding: lines reach every live callback, scopes end in any order, the previous logger comes back.
#include "host/core/log_forwarding.h"

#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

namespace rfrecon {
namespace {

TEST(LogForwardingTest, LinesReachEveryLiveCallbackAndTheToolsLoggerComesBack) {
  const auto tools_logger = spdlog::default_logger();
  std::vector<std::string> first_lines, second_lines;
  auto first = std::make_unique<ScopedLogForwarding>(
      [&](int level, const std::string& text) { first_lines.push_back(std::to_string(level) + " " + text); });
  spdlog::warn("one");
  {
    const ScopedLogForwarding second([&](int, const std::string& text) { second_lines.push_back(text); });
    std::thread([] { spdlog::info("two"); }).join();  // from another thread too
    first.reset();                                    // the first scope ends before the second
    spdlog::error("three");
  }
  EXPECT_EQ(spdlog::default_logger(), tools_logger);
  spdlog::info("four");  // no callback is live: the tool's logger has it
  EXPECT_EQ(first_lines, (std::vector<std::string>{"2 one", "1 two"}));
  EXPECT_EQ(second_lines, (std::vector<std::string>{"two", "three"}));
}

TEST(LogForwardingTest, ACallbackThatThrowsLosesItsLineOnly) {
  std::vector<std::string> lines;
  const ScopedLogForwarding throwing([](int, const std::string&) { throw std::runtime_error("callback failed"); });
  const ScopedLogForwarding keeping([&](int, const std::string& text) { lines.push_back(text); });
  EXPECT_NO_THROW(spdlog::info("kept"));
  EXPECT_EQ(lines, (std::vector<std::string>{"kept"}));
}

TEST(LogForwardingTest, AnEmptyCallbackChangesNothing) {
  const auto tools_logger = spdlog::default_logger();
  const ScopedLogForwarding none{LogCallback()};
  EXPECT_EQ(spdlog::default_logger(), tools_logger);
}

}  // namespace
}  // namespace rfrecon
