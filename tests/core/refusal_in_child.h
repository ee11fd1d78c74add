// Test helper: runs a read in a child process, so that a read that blocks (a FIFO opened) or crashes fails the test
// instead of hanging or killing it, and returns the InputError message the child got.
#pragma once

#include <csignal>
#include <functional>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "host/core/errors.h"

namespace rfrecon::testing {

// The what() of the InputError that `read` throws in a child process, or "(no InputError)", "(another exception)",
// "(killed by signal N)": SIGALRM after `alarm_seconds` stops a read that blocks (a safety net far above the
// milliseconds a refusal takes, not a timing).
inline std::string refusal_in_child(const std::function<void()>& read, unsigned alarm_seconds = 30) {
  int fds[2];
  if (::pipe(fds) != 0) return "(no pipe)";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(fds[0]);
    ::alarm(alarm_seconds);
    std::string message = "(no InputError)";
    try {
      read();
    } catch (const InputError& error) {
      message = error.what();
    } catch (...) {
      message = "(another exception)";
    }
    const ssize_t written = ::write(fds[1], message.data(), message.size());
    ::_exit(written == static_cast<ssize_t>(message.size()) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[4096];
  for (ssize_t got; (got = ::read(fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, got);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (WIFSIGNALED(status)) return "(killed by signal " + std::to_string(WTERMSIG(status)) + ")";
  return message;
}

}  // namespace rfrecon::testing
