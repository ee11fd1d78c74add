// Frames from a callback equal frames from files; bad callback frames name the source; the read-ahead pool hands
// groups over in order, never reads more than its window ahead, and passes a reader's error to the group's taker.
#include "host/capture/frame_source.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/frame_read_ahead.h"
#include "host/capture/protocol.h"
#include "host/core/errors.h"
#include "tests/common/temp_dir.h"

namespace rfrecon::capture {
namespace {

using ::testing::HasSubstr;

// A 16-bit capture (bit depth 12, black level 64) whose frame i is filled with 100 + 10 i, the files on disk.
class FrameSourceTest : public ::testing::Test {
 protected:
  FrameSourceTest() {
    manifest_.projector_size = {32, 16};
    manifest_.camera_size = {20, 10};
    manifest_.bit_depth = 12;
    manifest_.black_level = 64;
    manifest_.camera_response = "gamma:2.2";
    const auto sequence = make_protocol({manifest_.projector_size, 0});
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const std::string name = "frame_" + std::to_string(i) + ".png";
      cv::imwrite((dir_.path() / name).string(), raw(i));
      manifest_.frames.push_back({sequence[i], name});
    }
    write_manifest(manifest_, dir_.path());
  }

  cv::Mat raw(std::size_t i) const {
    return cv::Mat(manifest_.camera_size, CV_16UC1, cv::Scalar(100 + 10 * static_cast<double>(i)));
  }

  rfrecon::testing::TempDir dir_{"frame_source"};
  CaptureManifest manifest_;
};

TEST_F(FrameSourceTest, CallbackFramesEqualTheFilesLinearised) {
  const FrameSource files(dir_.path());
  const FrameSource memory = FrameSource::from_callback([this](std::size_t i) { return raw(i); }, "camera");
  for (std::size_t i = 0; i < manifest_.frames.size(); ++i) {
    const cv::Mat expected = files.load(manifest_, i);
    const cv::Mat got = memory.load(manifest_, i);
    ASSERT_EQ(got.type(), CV_32FC1);
    EXPECT_EQ(cv::norm(got, expected, cv::NORM_INF), 0.0) << i;
  }
  // The linear response of the first frame: ((100 - 64) / (4095 - 64))^2.2.
  EXPECT_NEAR(memory.load(manifest_, 0).at<float>(0, 0), std::pow(36.0 / 4031.0, 2.2), 1e-9);
}

TEST_F(FrameSourceTest, RawFramesAreCheckedButNotConverted) {
  const FrameSource files(dir_.path());
  const FrameSource memory = FrameSource::from_callback([this](std::size_t i) { return raw(i); }, "camera");
  for (std::size_t i = 0; i < manifest_.frames.size(); ++i) {
    for (const FrameSource* source : {&files, &memory}) {
      const cv::Mat got = source->load(manifest_, i, FrameForm::kRaw);
      ASSERT_EQ(got.type(), CV_16UC1);
      EXPECT_EQ(cv::norm(got, raw(i), cv::NORM_INF), 0.0) << i;
    }
  }
  const auto eight_bit = FrameSource::from_callback(
      [this](std::size_t) { return cv::Mat(manifest_.camera_size, CV_8UC1, cv::Scalar(9)); }, "camera SDK");
  try {
    (void)eight_bit.load(manifest_, 3, FrameForm::kRaw);
    ADD_FAILURE() << "an 8-bit frame of a 12-bit capture was accepted raw";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("camera SDK frame 3 (frame_3.png)"));
  }
}

// A camera SDK that hands over each frame in the same buffer of its own: the raw frames taken before keep their
// samples (copied), and a view of part of a larger image comes out continuous.
TEST_F(FrameSourceTest, RawFramesOverTheCallersBufferAreCopied) {
  std::vector<std::uint16_t> sdk_buffer(static_cast<std::size_t>(manifest_.camera_size.area()));
  const FrameSource camera = FrameSource::from_callback(
      [&](std::size_t i) {
        raw(i).copyTo(cv::Mat(manifest_.camera_size, CV_16UC1, sdk_buffer.data()));
        return cv::Mat(manifest_.camera_size, CV_16UC1, sdk_buffer.data());
      },
      "camera SDK");
  const cv::Mat first = camera.load(manifest_, 0, FrameForm::kRaw);
  const cv::Mat second = camera.load(manifest_, 1, FrameForm::kRaw);
  EXPECT_EQ(cv::norm(first, raw(0), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(second, raw(1), cv::NORM_INF), 0.0);

  const cv::Mat wide(manifest_.camera_size.height, 2 * manifest_.camera_size.width, CV_16UC1, cv::Scalar(7));
  const FrameSource view = FrameSource::from_callback(
      [&](std::size_t) { return wide.colRange(0, manifest_.camera_size.width); }, "camera SDK");
  const cv::Mat got = view.load(manifest_, 0, FrameForm::kRaw);
  EXPECT_TRUE(got.isContinuous());
  EXPECT_EQ(cv::norm(got, cv::Mat(manifest_.camera_size, CV_16UC1, cv::Scalar(7)), cv::NORM_INF), 0.0);
}

TEST_F(FrameSourceTest, BadCallbackFramesNameTheSourceAndFrame) {
  const auto error_of = [this](const FrameSource& source) {
    try {
      (void)source.load(manifest_, 3);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no InputError");
  };
  const auto eight_bit = FrameSource::from_callback(
      [this](std::size_t) { return cv::Mat(manifest_.camera_size, CV_8UC1, cv::Scalar(9)); }, "camera SDK");
  EXPECT_THAT(error_of(eight_bit), HasSubstr("camera SDK frame 3 (frame_3.png)"));
  EXPECT_THAT(error_of(eight_bit), HasSubstr("8-bit samples"));
  const auto small = FrameSource::from_callback([](std::size_t) { return cv::Mat(4, 4, CV_16UC1); }, "camera SDK");
  EXPECT_THAT(error_of(small), HasSubstr("differs from the capture's camera size"));
  const auto none = FrameSource::from_callback([](std::size_t) { return cv::Mat(); }, "camera SDK");
  EXPECT_THAT(error_of(none), HasSubstr("returned no image"));
}

// Groups of one or two frames, their pixel values telling which; a reader that sleeps so that the window fills.
TEST_F(FrameSourceTest, ReadAheadHandsGroupsOverInOrderWithinItsWindow) {
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i + 1 < manifest_.frames.size(); i += 2) groups.push_back({i, i + 1});
  groups.push_back({});
  groups.push_back({manifest_.frames.size() - 1});
  constexpr std::size_t kDepth = 3;
  std::atomic<std::size_t> taken{0};     // groups the test has asked for (set before each take)
  std::atomic<std::size_t> furthest{0};  // largest group index requested, plus one
  std::atomic<bool> too_far{false};
  const FrameSource source = FrameSource::from_callback(
      [&](std::size_t i) {
        const std::size_t group = i / 2;  // the first groups hold frames 2g and 2g + 1
        if (group + 1 > taken.load() + kDepth && group < groups.size() - 2) too_far = true;
        furthest = std::max(furthest.load(), group + 1);
        return raw(i);
      },
      "counting source");
  FrameReadAhead read_ahead(source, manifest_, groups, 2, kDepth);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the readers run ahead as far as they may
    taken = g + 1;
    const auto frames = read_ahead.take(g);
    ASSERT_EQ(frames.size(), groups[g].size()) << g;
    for (std::size_t f = 0; f < frames.size(); ++f) {
      EXPECT_EQ(cv::norm(frames[f], source.load(manifest_, groups[g][f]), cv::NORM_INF), 0.0) << g;
    }
  }
  EXPECT_FALSE(too_far) << "a reader went more than " << kDepth << " groups ahead";
  EXPECT_THROW(read_ahead.take(0), std::logic_error);  // out of order
}

TEST_F(FrameSourceTest, ReadAheadRethrowsAReadersErrorAtItsGroup) {
  const FrameSource source = FrameSource::from_callback(
      [this](std::size_t i) {
        if (i == 5) throw InputError("camera SDK: frame 5 timed out");
        return raw(i);
      },
      "camera SDK");
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < 10; ++i) groups.push_back({i});
  FrameReadAhead read_ahead(source, manifest_, groups, 3, 4);
  for (std::size_t g = 0; g < 5; ++g) EXPECT_EQ(read_ahead.take(g).size(), 1u);
  try {
    (void)read_ahead.take(5);
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("frame 5 timed out"));
  }
}

}  // namespace
}  // namespace rfrecon::capture
