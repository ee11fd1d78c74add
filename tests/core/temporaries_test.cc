// Temporaries by name: those of a process that is gone are removed by the next output beside them, those of a live
// process are kept, and an earlier output moved aside by a killed run comes back when nothing replaced it.
#include "host/core/temporaries.h"

#include <filesystem>
#include <fstream>
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
  const fs::path temporary = make_temporary(dir_ / "out.json", "tmp");
  std::ofstream(temporary) << "partial";
  remove_registered_temporaries();
  EXPECT_FALSE(fs::exists(temporary));
}

}  // namespace
}  // namespace rfrecon
