// Outputs under races: what appears between a command's start check and its final rename is never replaced (a file)
// or deleted (a directory with a user's file in it) without --force, two writers of one new output cannot both
// succeed, names up to the file system's limit work with their temporaries, and SIGTERM at a commit leaves nothing.
// The races are made with the before-commit hook, not with timing.
#include "host/core/atomic_file.h"

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "host/core/errors.h"
#include "host/core/output_path.h"
#include "host/core/temporaries.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace atomic_file_races {  // named, not anonymous: the tests build as one unity source

namespace fs = std::filesystem;

void touch(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

// The UsageError message of `write`, or "" when it succeeds.
template <typename Write>
std::string refusal(Write write) {
  try {
    write();
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

// Runs `hook` once, at the next commit of `target` (other commits pass).
class HookOnce {
 public:
  template <typename Hook>
  HookOnce(fs::path target, Hook hook) {
    set_before_commit_hook([target = std::move(target), hook, done = std::make_shared<bool>(false)](const fs::path& t) {
      if (*done || t != target) return;
      *done = true;
      hook();
    });
  }
  ~HookOnce() { set_before_commit_hook({}); }
  HookOnce(const HookOnce&) = delete;
  HookOnce& operator=(const HookOnce&) = delete;
};

class AtomicFileTest : public ::testing::Test {
 protected:
  testing::TempDir temp_{"atomic_file"};
  const fs::path dir_ = temp_.path();
};

TEST_F(AtomicFileTest, AFileThatAppearsBeforeTheRenameIsKept) {
  const fs::path output = dir_ / "T.h5";
  check_output_file({output, "--output", false}, {});
  const HookOnce appear(output, [&] { touch(output, "the user's"); });
  const std::string message = refusal([&] { write_file_atomically(output, "ours"); });
  EXPECT_NE(message.find("--output " + output.string() + " appeared while the command ran"), std::string::npos)
      << message;
  EXPECT_EQ(text_of(output), "the user's");
  EXPECT_EQ(entries(dir_), std::set<std::string>{"T.h5"});  // no temporary left
}

// --force replaces what was there at the start, not what appeared since.
TEST_F(AtomicFileTest, ForceReplacesOnlyWhatExistedAtTheStart) {
  const fs::path fresh = dir_ / "fresh.json";
  check_output_file({fresh, "--summary", true}, {});
  {
    const HookOnce appear(fresh, [&] { touch(fresh, "the user's"); });
    EXPECT_NE(refusal([&] { write_file_atomically(fresh, "ours"); }).find("--summary"), std::string::npos);
  }
  EXPECT_EQ(text_of(fresh), "the user's");

  const fs::path existing = dir_ / "existing.json";
  touch(existing, "earlier");
  check_output_file({existing, "--output", true}, {});
  const HookOnce rewrite(existing, [&] { touch(existing, "rewritten meanwhile"); });
  write_file_atomically(existing, "ours");
  EXPECT_EQ(text_of(existing), "ours");
  EXPECT_EQ(entries(dir_), (std::set<std::string>{"existing.json", "fresh.json"}));
}

// The refusal comes before anything is renamed: a main output is not put in place when its summary appeared.
TEST_F(AtomicFileTest, NoOutputIsRenamedWhenAnotherOfTheCommandAppeared) {
  const fs::path main = dir_ / "T.h5", summary = dir_ / "summary.json";
  check_output_file({main, "--output", false}, {});
  check_output_file({summary, "--summary", false}, {});
  AtomicFile main_file(main);
  AtomicFile summary_file(summary);
  main_file.write("T");
  summary_file.write("{}");
  const HookOnce appear(main, [&] { touch(summary, "the user's"); });
  EXPECT_NE(refusal([&] { main_file.commit(); }).find("--summary " + summary.string()), std::string::npos);
  EXPECT_FALSE(fs::exists(main));
  EXPECT_EQ(text_of(summary), "the user's");
}

// An output renamed into place is the command's own: the next one's commit does not take it for one that appeared.
TEST_F(AtomicFileTest, ACommandsOutputsAreRenamedOneAfterAnother) {
  const fs::path main = dir_ / "T.h5", summary = dir_ / "summary.json", maps = dir_ / "maps";
  check_output_file({main, "--output", false}, {});
  check_output_file({summary, "--summary", false}, {});
  check_output_directory({maps, "--maps", false}, {});
  AtomicFile main_file(main);
  AtomicFile summary_file(summary);
  StagingDirectory maps_directory(maps, false);
  main_file.write("T");
  summary_file.write("{}");
  main_file.commit();
  summary_file.commit();
  maps_directory.commit();
  EXPECT_EQ(text_of(main), "T");
  EXPECT_EQ(text_of(summary), "{}");
  EXPECT_EQ(entries(dir_), (std::set<std::string>{"T.h5", "maps", "summary.json"}));
}

TEST_F(AtomicFileTest, ADirectoryThatAppearsWithAUsersFileIsKept) {
  const fs::path output = dir_ / "scan";
  check_output_directory({output, "--output", false}, {});
  {
    StagingDirectory staging(output, false);
    touch(staging.path() / "depth.tiff", "ours");
    const HookOnce appear(output, [&] {
      fs::create_directory(output);
      touch(output / "notes.txt", "the user's");
    });
    const std::string message = refusal([&] { staging.commit(); });
    EXPECT_NE(message.find("--output " + output.string() + " appeared while the command ran"), std::string::npos)
        << message;
  }
  EXPECT_EQ(text_of(output / "notes.txt"), "the user's");
  EXPECT_EQ(entries(output), std::set<std::string>{"notes.txt"});
  EXPECT_EQ(entries(dir_), std::set<std::string>{"scan"});
}

// With --force too: the directory was absent at the start, so what appeared is not the user's to lose.
TEST_F(AtomicFileTest, ForceDoesNotDeleteADirectoryThatAppeared) {
  const fs::path output = dir_ / "scan";
  check_output_directory({output, "--output", true}, {});
  {
    StagingDirectory staging(output, true);
    const HookOnce appear(output, [&] {
      fs::create_directory(output);
      touch(output / "notes.txt", "the user's");
    });
    EXPECT_NE(refusal([&] { staging.commit(); }).find("appeared"), std::string::npos);
  }
  EXPECT_EQ(text_of(output / "notes.txt"), "the user's");
  EXPECT_EQ(entries(dir_), std::set<std::string>{"scan"});
}

// An empty directory at the start counts as absent: replaced while it stays empty, kept once it holds a file.
TEST_F(AtomicFileTest, AnEmptyDirectoryIsReplacedOnlyWhileEmpty) {
  const fs::path output = dir_ / "scan";
  fs::create_directory(output);
  check_output_directory({output, "--report", false}, {});
  {
    StagingDirectory staging(output, true);  // as calibrate: replace_existing, but no --force
    touch(staging.path() / "report.json", "ours");
    const HookOnce fill(output, [&] { touch(output / "notes.txt", "the user's"); });
    const std::string message = refusal([&] { staging.commit(); });
    EXPECT_NE(message.find("--report " + output.string() + " was an empty directory when the command started"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(entries(output), std::set<std::string>{"notes.txt"});

  fs::remove(output / "notes.txt");
  check_output_directory({output, "--report", false}, {});
  StagingDirectory staging(output, true);
  touch(staging.path() / "report.json", "ours");
  staging.commit();
  EXPECT_EQ(entries(output), std::set<std::string>{"report.json"});
  EXPECT_EQ(entries(dir_), std::set<std::string>{"scan"});
}

// An output given up (an error before its commit) takes away the directories made for it, not those it found.
TEST_F(AtomicFileTest, AFailedOutputLeavesNoDirectoryMadeForIt) {
  fs::create_directories(dir_ / "kept");
  {
    AtomicFile file(dir_ / "kept" / "new" / "deeper" / "T.h5");
    StagingDirectory staging(dir_ / "made" / "scan", false);
    EXPECT_TRUE(fs::is_directory(dir_ / "kept" / "new" / "deeper"));
  }
  EXPECT_EQ(entries(dir_), std::set<std::string>{"kept"});
  EXPECT_TRUE(fs::is_empty(dir_ / "kept"));
  write_file_atomically(dir_ / "kept" / "new" / "T.h5", "whole");  // committed: the directory it made stays
  EXPECT_EQ(text_of(dir_ / "kept" / "new" / "T.h5"), "whole");
}

// --force on a directory that exists: the two swap names in one step; the earlier one goes, nothing else is left.
TEST_F(AtomicFileTest, ForceReplacesAnExistingDirectoryWhole) {
  const fs::path output = dir_ / "scan";
  fs::create_directories(output / "sub");
  touch(output / "sub" / "old.tiff", "earlier");
  check_output_directory({output, "--output", true}, {});
  StagingDirectory staging(output, true);
  touch(staging.path() / "depth.tiff", "ours");
  staging.commit();
  EXPECT_EQ(entries(output), std::set<std::string>{"depth.tiff"});
  EXPECT_EQ(entries(dir_), std::set<std::string>{"scan"});
}

TEST_F(AtomicFileTest, OfTwoWritersOfOneNewOutputOneSucceeds) {
  const fs::path file = dir_ / "T.h5";
  AtomicFile first(file), second(file);
  first.write("first");
  second.write("second");
  second.commit();
  EXPECT_NE(refusal([&] { first.commit(); }).find("appeared while the command ran"), std::string::npos);
  EXPECT_EQ(text_of(file), "second");

  const fs::path directory = dir_ / "scan";
  StagingDirectory one(directory, false), two(directory, false);
  touch(one.path() / "from", "one");
  touch(two.path() / "from", "two");
  one.commit();
  EXPECT_NE(refusal([&] { two.commit(); }).find("appeared while the command ran"), std::string::npos);
  EXPECT_EQ(text_of(directory / "from"), "one");
}

// Two processes that both found the output absent and rename at the same moment: the no-replace rename lets one
// through. Each child stops before its commit until the parent lets both go.
TEST_F(AtomicFileTest, OfTwoProcessesWritingOneNewOutputOneSucceeds) {
  for (const bool directory : {false, true}) {
    const fs::path output = dir_ / (directory ? "scan" : "T.h5");
    int go[2];
    ASSERT_EQ(::pipe(go), 0);
    pid_t children[2];
    for (int i = 0; i < 2; ++i) {
      children[i] = ::fork();
      if (children[i] == 0) {
        ::close(go[1]);
        int code = 0;
        try {
          const OutputPath path{output, "--output", false};
          directory ? check_output_directory(path, {}) : check_output_file(path, {});
          set_before_commit_hook([&](const fs::path&) {
            char byte = 0;
            if (::read(go[0], &byte, 1) != 1) ::_exit(3);
          });
          const std::string text = "writer " + std::to_string(i);
          if (directory) {
            StagingDirectory staging(output, false);
            touch(staging.path() / "from", text);
            staging.commit();
          } else {
            write_file_atomically(output, text);
          }
        } catch (const UsageError&) {
          code = 2;
        } catch (...) {
          code = 4;
        }
        ::_exit(code);
      }
    }
    ::close(go[0]);
    ::usleep(100000);  // both children reach their hook (or, late, read the bytes already there: the same result)
    ASSERT_EQ(::write(go[1], "gg", 2), 2);
    ::close(go[1]);
    int codes[2];
    for (int i = 0; i < 2; ++i) {
      int status = 0;
      ::waitpid(children[i], &status, 0);
      ASSERT_TRUE(WIFEXITED(status));
      codes[i] = WEXITSTATUS(status);
    }
    EXPECT_EQ(std::multiset<int>(codes, codes + 2), (std::multiset<int>{0, 2})) << output;
    const std::string winner = "writer " + std::to_string(codes[0] == 0 ? 0 : 1);
    EXPECT_EQ(text_of(directory ? output / "from" : output), winner);
    EXPECT_EQ(entries(dir_).size(), directory ? 2u : 1u) << "nothing but the outputs";
  }
}

TEST_F(AtomicFileTest, RenamesThatNeverReplace) {
  touch(dir_ / "a", "a");
  touch(dir_ / "b", "b");
  EXPECT_EQ(rename_no_replace(dir_ / "a", dir_ / "b"), EEXIST);
  EXPECT_EQ(text_of(dir_ / "a"), "a");
  EXPECT_EQ(text_of(dir_ / "b"), "b");
  EXPECT_EQ(rename_no_replace(dir_ / "a", dir_ / "c"), 0);
  EXPECT_EQ(text_of(dir_ / "c"), "a");
  fs::create_directories(dir_ / "d1");
  fs::create_directories(dir_ / "d2");
  EXPECT_NE(rename_no_replace(dir_ / "d1", dir_ / "d2"), 0) << "an empty directory is not replaced either";
  EXPECT_EQ(exchange_paths(dir_ / "b", dir_ / "c"), 0);
  EXPECT_EQ(text_of(dir_ / "b"), "a");
  EXPECT_EQ(text_of(dir_ / "c"), "b");
}

// A cache entry (the program store) replaces whatever another run stored meanwhile.
TEST_F(AtomicFileTest, AlwaysReplaceIsForCaches) {
  const fs::path entry = dir_ / "0123456789abcdef.clbin";
  AtomicFile file(entry, ReplacePolicy::kAlways);
  file.write("ours");
  touch(entry, "another run's");
  file.commit();
  EXPECT_EQ(text_of(entry), "ours");
}

std::string name_of_length(std::size_t bytes, char fill = 'n') { return std::string(bytes, fill); }

// A name at the file system's limit is an output like any other: its temporaries are shortened to fit.
TEST_F(AtomicFileTest, NamesAtTheFileSystemsLimitWork) {
  const std::size_t limit = name_max(dir_);
  const fs::path file = dir_ / name_of_length(limit);
  const fs::path directory = dir_ / name_of_length(limit, 'd');
  check_output_file({file, "--output", false}, {});
  std::set<std::string> seen;
  set_before_commit_hook([&](const fs::path&) {
    for (const auto& name : entries(dir_)) seen.insert(name);
  });
  write_file_atomically(file, "whole");
  check_output_directory({directory, "--output", false}, {});
  {
    StagingDirectory staging(directory, false);
    write_file_atomically(staging.path() / name_of_length(limit, 'f'), "inside");
    staging.commit();
  }
  set_before_commit_hook({});
  EXPECT_EQ(text_of(file), "whole");
  EXPECT_EQ(text_of(directory / name_of_length(limit, 'f')), "inside");
  EXPECT_EQ(entries(dir_), (std::set<std::string>{file.filename().string(), directory.filename().string()}));
  EXPECT_GE(seen.size(), 2u);
  for (const auto& name : seen) {
    EXPECT_LE(name.size(), limit) << name;
    if (name.size() < limit) {
      EXPECT_NE(name.find('~'), std::string::npos) << "a shortened temporary: " << name;
    }
  }
}

TEST_F(AtomicFileTest, ANameLongerThanTheLimitIsAUsageError) {
  const std::size_t limit = name_max(dir_);
  const std::string message = refusal([&] { check_output_file({dir_ / name_of_length(limit + 1), "-o", true}, {}); });
  EXPECT_NE(message.find("is " + std::to_string(limit + 1) + " bytes long"), std::string::npos) << message;
  EXPECT_NE(refusal([&] {
              check_output_directory({dir_ / name_of_length(limit + 1) / "out", "-o", true}, {});
            }).find("a directory name in it"),
            std::string::npos);
  fs::path deep = dir_;
  while (deep.string().size() <= kMaxOutputPathBytes) deep /= name_of_length(200);
  EXPECT_NE(refusal([&] { check_output_file({deep, "-o", true}, {}); }).find("bytes long; at most"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir_));
}

// ---- SIGTERM: a child process stops itself at a commit (the hook) and the signal thread must leave nothing.

// Runs `body` in a child with the signal cleanup installed; the hook sends SIGTERM to the process at the commit
// of `at` and waits there. Returns the child's exit status.
template <typename Body>
int terminated_at(const fs::path& at, Body body) {
  const pid_t child = ::fork();
  if (child == 0) {
    install_signal_cleanup();
    set_before_commit_hook([at](const fs::path& target) {
      if (target != at) return;
      ::kill(::getpid(), SIGTERM);
      for (;;) ::pause();
    });
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(AtomicFileTest, SigtermAtACommitLeavesNothing) {
  const fs::path scan = dir_ / "scan", file = dir_ / "T.h5";
  EXPECT_EQ(terminated_at(scan,
                          [&] {
                            StagingDirectory staging(scan, false);
                            fs::create_directories(staging.path() / "capture" / "pose_00");
                            write_file_atomically(staging.path() / "capture" / "pose_00" / "manifest.json", "{}");
                            AtomicFile t_file(file);
                            t_file.write("T");
                            staging.commit();
                          }),
            128 + SIGTERM);
  EXPECT_TRUE(fs::is_empty(dir_)) << *entries(dir_).begin();

  // The directories made above an output go too (they are registered as they are made).
  const fs::path deep = dir_ / "out" / "demo" / "scan";
  EXPECT_EQ(terminated_at(deep,
                          [&] {
                            StagingDirectory staging(deep, false);
                            touch(staging.path() / "depth.tiff", "ours");
                            staging.commit();
                          }),
            128 + SIGTERM);
  EXPECT_TRUE(fs::is_empty(dir_)) << *entries(dir_).begin();

  // Inside a nested commit (T.h5's image renamed onto its AtomicFile's temporary).
  EXPECT_EQ(terminated_at(dir_ / "never",
                          [&] {
                            AtomicFile t_file(file);
                            set_before_commit_hook([&](const fs::path& target) {
                              if (target != t_file.temp_path()) return;
                              ::kill(::getpid(), SIGTERM);
                              for (;;) ::pause();
                            });
                            write_file_atomically(t_file.temp_path(), "T");
                          }),
            128 + SIGTERM);
  EXPECT_TRUE(fs::is_empty(dir_));
}

// An earlier output being replaced (--force) survives a signal before the swap, whole.
TEST_F(AtomicFileTest, SigtermBeforeAForcedSwapKeepsTheEarlierOutput) {
  const fs::path scan = dir_ / "scan";
  fs::create_directories(scan);
  touch(scan / "depth.tiff", "earlier");
  EXPECT_EQ(terminated_at(scan,
                          [&] {
                            check_output_directory({scan, "--output", true}, {});
                            StagingDirectory staging(scan, true);
                            touch(staging.path() / "depth.tiff", "ours");
                            staging.commit();
                          }),
            128 + SIGTERM);
  EXPECT_EQ(entries(dir_), std::set<std::string>{"scan"});
  EXPECT_EQ(text_of(scan / "depth.tiff"), "earlier");
}

// Other threads keep making directories and files inside the staging directory (as `simulate` does with
// create_directories) while the signal's cleanup runs: they are stopped first, so nothing is made again after it.
TEST_F(AtomicFileTest, SigtermWhileOtherThreadsWriteLeavesNothing) {
  for (int round = 0; round < 20; ++round) {
    const fs::path scan = dir_ / "scan";
    const int code = terminated_at(scan, [&] {
      StagingDirectory staging(scan, false);
      std::atomic<bool> started{false};
      for (int t = 0; t < 3; ++t) {
        std::thread([root = staging.path(), t, &started] {
          for (int i = 0;; ++i) {
            std::error_code ec;
            const fs::path sub = root / ("pose_" + std::to_string(t)) / std::to_string(i % 7);
            fs::create_directories(sub, ec);
            std::ofstream(sub / "frame.png") << "frame";
            started = true;
          }
        }).detach();
      }
      while (!started) std::this_thread::yield();
      staging.commit();
    });
    ASSERT_EQ(code, 128 + SIGTERM);
    ASSERT_TRUE(fs::is_empty(dir_)) << "round " << round << ": " << *entries(dir_).begin();
  }
}

}  // namespace atomic_file_races
}  // namespace rfrecon
