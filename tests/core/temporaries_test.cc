// Temporaries by name: those of a process that is gone are removed by the next output beside them, those of a live
// process are kept, and an earlier output moved aside by a killed run comes back when nothing replaced it.
#include "host/core/temporaries.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "host/core/atomic_file.h"
#include "tests/common/temp_dir.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

// The PID of a child process that has exited and been reaped: no process has it (until the PID wraps around).
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

class TemporariesTest : public ::testing::Test {
 protected:
  testing::TempDir temp_{"temporaries"};
  const fs::path dir_ = temp_.path();
};

TEST_F(TemporariesTest, ADeadProcessesTemporariesGoAndALiveOnesStay) {
  const std::string dead = std::to_string(dead_pid());
  const std::string live = std::to_string(::getppid());
  for (const auto& name : {"T.h5.tmp-" + dead + "-0", "out.staging-" + dead + "-3", "T.h5.tmp-" + live + "-0",
                           "T.h5.tmp-" + dead + "-x", "other.tmp-" + dead + "-0"}) {
    fs::create_directories(dir_ / name);
  }
  remove_stale_temporaries(dir_ / "T.h5");
  remove_stale_temporaries(dir_ / "out");
  EXPECT_FALSE(fs::exists(dir_ / ("T.h5.tmp-" + dead + "-0")));
  EXPECT_FALSE(fs::exists(dir_ / ("out.staging-" + dead + "-3")));
  EXPECT_TRUE(fs::exists(dir_ / ("T.h5.tmp-" + live + "-0"))) << "a running process's temporary";
  EXPECT_TRUE(fs::exists(dir_ / ("T.h5.tmp-" + dead + "-x"))) << "not a temporary's name";
  EXPECT_TRUE(fs::exists(dir_ / ("other.tmp-" + dead + "-0"))) << "another output's temporary";
}

TEST_F(TemporariesTest, AnOutputMovedAsideComesBackWhenNothingReplacedIt) {
  const std::string dead = std::to_string(dead_pid());
  fs::create_directories(dir_ / ("scan.old-" + dead + "-1"));
  std::ofstream(dir_ / ("scan.old-" + dead + "-1") / "depth.tiff") << "earlier";
  remove_stale_temporaries(dir_ / "scan");
  EXPECT_TRUE(fs::exists(dir_ / "scan" / "depth.tiff"));
  EXPECT_FALSE(fs::exists(dir_ / ("scan.old-" + dead + "-1")));
}

TEST_F(TemporariesTest, AnAtomicFileCleansWhatAKilledRunLeft) {
  const std::string stale = "T.h5.tmp-" + std::to_string(dead_pid()) + "-0";
  std::ofstream(dir_ / stale) << "partial";
  write_file_atomically(dir_ / "T.h5", "whole");
  EXPECT_FALSE(fs::exists(dir_ / stale));
  EXPECT_EQ(fs::file_size(dir_ / "T.h5"), 5u);
}

TEST_F(TemporariesTest, RegisteredTemporariesAreRemovedOnRequest) {
  const fs::path temporary = make_temporary(dir_ / "out.json", TemporaryKind::kFile);
  EXPECT_TRUE(fs::is_regular_file(temporary)) << "made with the name, under the registry's lock";
  std::ofstream(temporary) << "partial";
  const fs::path staging = make_temporary(dir_ / "scan", TemporaryKind::kDirectory);
  fs::create_directories(staging / "capture" / "pose_00");
  std::ofstream(staging / "capture" / "pose_00" / "frame.png") << "frame";
  remove_registered_temporaries();
  EXPECT_TRUE(fs::is_empty(dir_));
}

// Temporaries of a name near the file system's limit are shortened (with a hash of the whole name) to fit, and
// the cleanup still knows them as that output's: not another long name's with the same beginning.
TEST_F(TemporariesTest, ALongNamesTemporariesFitAndAreStillCleanedUp) {
  const std::size_t limit = name_max(dir_);
  const fs::path target = dir_ / std::string(limit, 'a');
  const fs::path other = dir_ / (std::string(limit - 1, 'a') + "b");
  const std::string prefix = temporary_prefix(target);
  ASSERT_LT(prefix.size() + kMaxTemporarySuffix, limit + 1);
  EXPECT_NE(prefix, temporary_prefix(other));
  EXPECT_EQ(temporary_prefix(dir_ / "T.h5"), "T.h5");
  const std::string dead = std::to_string(dead_pid());
  const std::string stale = prefix + ".tmp-" + dead + "-0", staging = prefix + ".staging-" + dead + "-7";
  const std::string others = temporary_prefix(other) + ".tmp-" + dead + "-0";
  std::ofstream(dir_ / stale) << "partial";
  fs::create_directories(dir_ / staging / "sub");
  std::ofstream(dir_ / others) << "another output's";
  const fs::path temporary = make_temporary(target, TemporaryKind::kFile);
  EXPECT_LE(temporary.filename().string().size(), limit);
  EXPECT_FALSE(fs::exists(dir_ / stale));
  EXPECT_FALSE(fs::exists(dir_ / staging));
  EXPECT_TRUE(fs::exists(dir_ / others));
  fs::remove(temporary);
  release_temporary(temporary);
}

// T.h5's image is written through an AtomicFile of T.h5's own temporary: the inner temporary is named after T.h5
// (one suffix), so a kill -9 between the two renames leaves a name the cleanup knows. Nested names that earlier
// versions made are recognised too.
TEST_F(TemporariesTest, NestedTemporariesAreNamedAfterTheOutputAndCleanedUp) {
  const std::string dead = std::to_string(dead_pid());
  const std::string live = std::to_string(::getppid());
  const std::string old_nested = "T.h5.tmp-" + dead + "-0.tmp-" + dead + "-1";
  const std::string live_nested = "T.h5.tmp-" + dead + "-0.tmp-" + live + "-1";
  std::ofstream(dir_ / old_nested) << "partial";
  std::ofstream(dir_ / live_nested) << "a running process's";
  {
    AtomicFile outer(dir_ / "T.h5");
    AtomicFile inner(outer.temp_path());
    const std::string name = inner.temp_path().filename().string();
    EXPECT_EQ(name.rfind("T.h5.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << name;
    EXPECT_EQ(name.find(".tmp-"), name.rfind(".tmp-")) << "one suffix: " << name;
    inner.write("whole");
    inner.commit();
    outer.commit();
  }
  EXPECT_FALSE(fs::exists(dir_ / old_nested));
  EXPECT_TRUE(fs::exists(dir_ / live_nested));
  fs::remove(dir_ / live_nested);
  EXPECT_EQ(fs::file_size(dir_ / "T.h5"), 5u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace rfrecon
