// `rfrecon patterns`, `transport` and `dual` run in process: a good capture gives T.h5 and images; bad captures fail
// with an InputError naming the file and leave no T.h5 behind.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>

#include "host/capture/graycode_patterns.h"
#include "host/capture/protocol.h"
#include "host/cl/program_store.h"
#include "host/cli/commands.h"
#include "host/core/errors.h"
#include "host/outputs/legend.h"
#include "host/transport/transport_file.h"
#include "tests/common/scoped_env.h"
#include "tests/transport/synthetic_capture.h"

namespace rfrecon::transport {
namespace {

namespace fs = std::filesystem;

void run_cli(std::vector<std::string> args) {
  CLI::App app;
  cli::add_patterns_command(app);
  cli::add_transport_command(app);
  cli::add_dual_command(app);
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments in reverse order
  app.parse(args);
}

class TransportCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::SceneOptions options;
    options.camera_size = {24, 20};
    options.projector_size = {16, 12};
    scene_ = testing::make_plane_scene(options);
    sequence_ = capture::make_protocol({options.projector_size, 3});
    frames_ = testing::render_frames(scene_, sequence_, 3, 1.0, 9);
    manifest_ = testing::write_capture(capture_, scene_, sequence_, 3, frames_);
  }

  // Runs `transport` and returns the InputError message; the output must not exist afterwards.
  std::string transport_error() {
    std::string message = "(no InputError)";
    try {
      run_cli({"transport", capture_.string(), "-o", output_.string()});
    } catch (const InputError& error) {
      message = error.what();
    }
    EXPECT_FALSE(fs::exists(output_)) << "a failed run must leave no T.h5";
    return message;
  }

  fs::path frame_path(std::size_t i) const { return capture_ / manifest_.frames[i].file; }

  testing::TempDir dir_{"cli"};
  fs::path capture_ = dir_.path() / "capture";
  fs::path output_ = dir_.path() / "T.h5";
  testing::PlaneScene scene_;
  std::vector<capture::Pattern> sequence_;
  std::vector<cv::Mat> frames_;
  capture::CaptureManifest manifest_;
};

TEST_F(TransportCliTest, GoodCaptureGivesTransportAndDualAndPrimalImages) {
  run_cli({"transport", capture_.string(), "-o", output_.string()});
  const auto transport = read_transport(output_);
  EXPECT_EQ(transport.setup.camera_size, scene_.camera_size);
  EXPECT_EQ(transport.setup.dot_spacing, 3);
  const fs::path dual = dir_.path() / "dual.png";
  run_cli({"dual", output_.string(), "-o", dual.string()});
  EXPECT_EQ(cv::imread(dual.string(), cv::IMREAD_UNCHANGED).size(), scene_.projector_size);
  const fs::path primal = dir_.path() / "primal.tiff";
  run_cli({"dual", output_.string(), "-o", primal.string(), "--primal"});
  const cv::Mat primal_image = cv::imread(primal.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(primal_image.size(), scene_.camera_size);
  // T 1 is what the camera sees under full white minus black: albedo 0.8 on lit pixels. Per pixel it carries the
  // black frame's noise once per entry (K x 1 DN), so compare the mean over the pixels with entries: within 0.02 for
  // the ~2% of energy under the noise threshold and the remaining noise.
  double sum = 0.0;
  int count = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    if (std::isnan(transport.correspondence[2 * c])) continue;
    sum += primal_image.at<float>(static_cast<int>(c));
    ++count;
  }
  ASSERT_GT(count, primal_image.rows * primal_image.cols / 2);
  EXPECT_NEAR(sum / count, 0.8, 0.02);
}

// One count per outcome (docs/cli.md): they add up to the camera's pixels, "decoded" is exactly the pixels of T.h5
// with a correspondence, and the maps show them on the camera grid; the console prints the same decoded count.
TEST_F(TransportCliTest, OutcomeCountsAgreeWithTheCorrespondencesAndTheMaps) {
  for (const int dot_spacing : {3, 0}) {
    if (dot_spacing == 0) {
      sequence_ = capture::make_protocol({scene_.projector_size, 0});
      frames_ = testing::render_frames(scene_, sequence_, 0, 1.0, 9);
      fs::remove_all(capture_);
      manifest_ = testing::write_capture(capture_, scene_, sequence_, 0, frames_);
    }
    const fs::path summary = dir_.path() / "summary.json", maps = dir_.path() / "maps";
    ::testing::internal::CaptureStdout();
    run_cli({"transport", capture_.string(), "-o", output_.string(), "--summary", summary.string(), "--maps",
             maps.string(), "--force"});
    const std::string printed = ::testing::internal::GetCapturedStdout();
    const auto transport = read_transport(output_);
    std::size_t with_correspondence = 0;
    for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
      with_correspondence += std::isnan(transport.correspondence[2 * c]) ? 0 : 1;
    }
    ASSERT_GT(with_correspondence, transport.camera_pixels() / 2) << dot_spacing;
    const auto json = nlohmann::json::parse(std::ifstream(summary));
    std::size_t total = 0;
    for (const auto& [name, count] : json.at("pixels").items()) {
      if (name != "decoded_between_codes") total += count.get<std::size_t>();
    }
    EXPECT_EQ(total, transport.camera_pixels()) << dot_spacing;
    EXPECT_EQ(json.at("pixels").at("decoded").get<std::size_t>(), with_correspondence) << dot_spacing;
    EXPECT_EQ(json.at("decoded_pixels").get<std::size_t>(), with_correspondence) << dot_spacing;
    EXPECT_EQ(json.at("pixels").contains("decoded_between_codes"), dot_spacing == 0);
    EXPECT_THAT(printed, ::testing::HasSubstr(std::to_string(with_correspondence) + " of " +
                                              std::to_string(transport.camera_pixels()) + " camera pixels decoded"));
    for (const char* name : {"decoded.png", "outcomes.png"}) {
      const cv::Mat map = cv::imread((maps / name).string(), cv::IMREAD_UNCHANGED);
      ASSERT_FALSE(map.empty()) << name;
      EXPECT_EQ(map.cols, scene_.camera_size.width + outputs::kLegendWidth) << name << ": the grid, then its legend";
      EXPECT_EQ(map.rows, std::max(scene_.camera_size.height, outputs::kLegendMinHeight)) << name;
    }
    // decoded.png is black exactly where there is no correspondence.
    const cv::Mat decoded = cv::imread((maps / "decoded.png").string(), cv::IMREAD_COLOR);
    std::size_t coloured = 0;
    for (int y = 0; y < scene_.camera_size.height; ++y) {
      for (int x = 0; x < scene_.camera_size.width; ++x) coloured += decoded.at<cv::Vec3b>(y, x) != cv::Vec3b() ? 1 : 0;
    }
    // A correspondence at projector (0, 0) is black too: at most the pixels decoded there.
    EXPECT_LE(coloured, with_correspondence) << dot_spacing;
    EXPECT_GE(coloured + transport.camera_pixels() / 50, with_correspondence) << dot_spacing;
  }
}

// The program cache (docs/performance.md#program-cache): a second run loads the programs the first compiled.
TEST_F(TransportCliTest, ASecondRunLoadsItsProgramsFromTheProgramCache) {
  const rfrecon::testing::ScopedEnv store(cl::kProgramCacheEnv, (dir_.path() / "programs").c_str());
  ::testing::internal::CaptureStdout();
  run_cli({"transport", capture_.string(), "-o", output_.string()});
  const std::string first = ::testing::internal::GetCapturedStdout();
  // Something compiled into the empty store; with two identical devices (POCL_DEVICES="pthread pthread") one of them
  // may load a program the other has just stored, so the first run's loads are not always 0.
  EXPECT_THAT(first, ::testing::Not(::testing::HasSubstr("programs: 0 compiled"))) << first;
  ::testing::internal::CaptureStdout();
  run_cli({"transport", capture_.string(), "-o", (dir_.path() / "again.h5").string()});
  const std::string second = ::testing::internal::GetCapturedStdout();
  EXPECT_THAT(second, ::testing::HasSubstr("programs: 0 compiled")) << second;
  EXPECT_THAT(second, ::testing::HasSubstr("build programs")) << "the builds are a stage of their own";
}

TEST_F(TransportCliTest, OpencvLayoutWithoutManifestDecodesLikeTheManifest) {
  const fs::path opencv = dir_.path() / "opencv";
  fs::create_directories(opencv);
  const auto graycode = capture::opencv_graycode_protocol(scene_.projector_size);
  const auto frames = testing::render_frames(scene_, graycode, 0, 1.0, 9);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::imwrite((opencv / ("pattern_" + std::to_string(10 + i) + ".png")).string(), frames[i]);
  }
  run_cli(
      {"transport", opencv.string(), "-o", output_.string(), "--layout", "opencv-graycode", "--projector", "16x12"});
  const auto transport = read_transport(output_);
  EXPECT_EQ(transport.setup.dot_spacing, 0);
  // Without noise differences mattering for the integer decode, the coordinates agree with the manifest capture's
  // on pixels valid in both (same scene, same Gray frames).
  run_cli({"transport", capture_.string(), "-o", (dir_.path() / "T2.h5").string()});
  const auto reference = read_transport(dir_.path() / "T2.h5");
  std::size_t both = 0, same = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    if ((transport.flags[c] & reference.flags[c] & kFlagValid) == 0) continue;
    ++both;
    same += transport.pixel_x[c] == reference.pixel_x[c] && transport.pixel_y[c] == reference.pixel_y[c] ? 1 : 0;
  }
  EXPECT_GT(both, transport.camera_pixels() / 2);
  EXPECT_EQ(same, both);
  // And against the scene's true correspondences: the integer code is the projector pixel holding the true point.
  std::size_t valid = 0, right = 0;
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    const cv::Vec2f truth = scene_.correspondence.at<cv::Vec2f>(static_cast<int>(c));
    if ((transport.flags[c] & kFlagValid) == 0 || std::isnan(truth[0])) continue;
    ++valid;
    right += transport.pixel_x[c] == static_cast<std::uint32_t>(std::floor(truth[0] + 0.5f)) &&
                     transport.pixel_y[c] == static_cast<std::uint32_t>(std::floor(truth[1] + 0.5f))
                 ? 1
                 : 0;
  }
  EXPECT_GT(right, 0.95 * static_cast<double>(valid)) << right << " of " << valid;
}

TEST_F(TransportCliTest, MissingFrameIsNamed) {
  fs::remove(frame_path(5));
  EXPECT_NE(transport_error().find(manifest_.frames[5].file), std::string::npos);
}

TEST_F(TransportCliTest, FrameSizeMismatchIsNamed) {
  cv::imwrite(frame_path(7).string(), cv::Mat(10, 12, CV_8U, cv::Scalar(100)));
  EXPECT_NE(transport_error().find(manifest_.frames[7].file), std::string::npos);
}

TEST_F(TransportCliTest, BitDepthMismatchIsNamed) {
  cv::Mat sixteen;
  frames_[4].convertTo(sixteen, CV_16U, 256.0);
  cv::imwrite(frame_path(4).string(), sixteen);
  const std::string message = transport_error();
  EXPECT_NE(message.find(manifest_.frames[4].file), std::string::npos) << message;
  EXPECT_NE(message.find("bit"), std::string::npos) << message;
}

TEST_F(TransportCliTest, UnreadableImageIsNamed) {
  std::ofstream(frame_path(3), std::ios::trunc) << "garbage";
  EXPECT_NE(transport_error().find(manifest_.frames[3].file), std::string::npos);
}

// Inputs are checked by stat(2) before anything opens them: a FIFO with no writer would block the command forever.
TEST_F(TransportCliTest, AFrameOrATransportThatIsAFifoIsRefusedWithoutBlocking) {
  fs::remove(frame_path(6));
  ASSERT_EQ(::mkfifo(frame_path(6).c_str(), 0600), 0);
  std::string message = transport_error();
  EXPECT_NE(message.find(frame_path(6).string()), std::string::npos) << message;
  EXPECT_NE(message.find("regular file"), std::string::npos) << message;

  const fs::path fifo = dir_.path() / "fifo.h5";
  const fs::path dual = dir_.path() / "dual.tif";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  message = "(no InputError)";
  try {
    run_cli({"dual", fifo.string(), "-o", dual.string()});
  } catch (const InputError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find(fifo.string() + ": is a FIFO"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dual));
}

TEST_F(TransportCliTest, ManifestInconsistentWithProjectorSizeIsNamed) {
  auto manifest = manifest_;
  manifest.projector_size = {64, 12};  // 6 column bits, the capture has 4
  capture::write_manifest(manifest, capture_);
  EXPECT_NE(transport_error().find("manifest.json"), std::string::npos);
}

TEST_F(TransportCliTest, AllDarkCaptureIsNamed) {
  for (std::size_t i = 0; i < manifest_.frames.size(); ++i) {
    cv::imwrite(frame_path(i).string(), cv::Mat(scene_.camera_size, CV_8U, cv::Scalar(3)));
  }
  const std::string message = transport_error();
  EXPECT_NE(message.find("all-dark"), std::string::npos) << message;
  EXPECT_NE(message.find(manifest_.frames[0].file), std::string::npos) << message;  // the white frame
}

// The bytes of a file, to show that a refused command left it as it was.
std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename Error>
std::string error_of(const std::vector<std::string>& args) {
  try {
    run_cli(args);
  } catch (const Error& error) {
    return error.what();
  }
  return "(no error of the expected type)";
}

TEST_F(TransportCliTest, NoOutputReplacesADeviceOrAnInput) {
  const std::string manifest_bytes = bytes_of(capture_ / "manifest.json");
  const std::string frame_bytes = bytes_of(frame_path(2));
  for (const auto& output : {fs::path("/dev/null"), capture_ / "manifest.json", frame_path(2), capture_}) {
    const auto message = error_of<UsageError>({"transport", capture_.string(), "-o", output.string(), "--force"});
    EXPECT_NE(message.find(output.string()), std::string::npos) << message;
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(bytes_of(capture_ / "manifest.json"), manifest_bytes);
  EXPECT_EQ(bytes_of(frame_path(2)), frame_bytes);

  run_cli({"transport", capture_.string(), "-o", output_.string()});
  const std::string transport_bytes = bytes_of(output_);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"dual", output_.string(), "-o", output_.string(), "--force"},
           {"dual", output_.string(), "-o", (dir_.path() / "d.png").string(), "--summary", output_.string(), "--force"},
           {"transport", capture_.string(), "-o", output_.string()}}) {
    EXPECT_NE(error_of<UsageError>(args).find(output_.string()), std::string::npos) << args[0];
  }
  EXPECT_EQ(bytes_of(output_), transport_bytes);
  EXPECT_FALSE(fs::exists(dir_.path() / "d.png"));
}

TEST_F(TransportCliTest, AnExistingOutputIsReplacedOnlyWithForce) {
  run_cli({"transport", capture_.string(), "-o", output_.string()});
  EXPECT_NE(error_of<UsageError>({"transport", capture_.string(), "-o", output_.string()}).find("--force"),
            std::string::npos);
  const fs::path dual = dir_.path() / "dual.png";
  run_cli({"dual", output_.string(), "-o", dual.string()});
  EXPECT_NE(error_of<UsageError>({"dual", output_.string(), "-o", dual.string()}).find("--force"), std::string::npos);
  run_cli({"dual", output_.string(), "-o", dual.string(), "--force"});
  run_cli({"transport", capture_.string(), "-o", output_.string(), "--force"});
  EXPECT_EQ(read_transport(output_).setup.camera_size, scene_.camera_size);
}

TEST_F(TransportCliTest, ASummaryThatCannotBeWrittenFailsTheCommandBeforeTheMainOutput) {
  const std::string summary = "/proc/rfrecon-summary.json";  // no file can be created in /proc
  EXPECT_NE(error_of<OutputError>({"transport", capture_.string(), "-o", output_.string(), "--summary", summary})
                .find(summary),
            std::string::npos);
  EXPECT_FALSE(fs::exists(output_));
  run_cli({"transport", capture_.string(), "-o", output_.string()});
  const fs::path dual = dir_.path() / "dual.png";
  EXPECT_NE(error_of<OutputError>({"dual", output_.string(), "-o", dual.string(), "--summary", summary}).find(summary),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dual));
  for (const auto& entry : fs::directory_iterator(dir_.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

TEST_F(TransportCliTest, FramesMayNotLeaveTheCaptureDirectory) {
  std::ofstream(dir_.path() / "outside.png") << "x";
  for (const auto& name : {std::string("../outside.png"), (dir_.path() / "outside.png").string()}) {
    auto manifest = manifest_;
    manifest.frames[0].file = name;
    capture::write_manifest(manifest, capture_);
    EXPECT_NE(transport_error().find("--allow-outside-frames"), std::string::npos) << name;
  }
  fs::create_symlink(dir_.path() / "outside.png", capture_ / "link.png");
  auto manifest = manifest_;
  manifest.frames[0].file = "link.png";
  capture::write_manifest(manifest, capture_);
  EXPECT_NE(transport_error().find("link.png"), std::string::npos);
}

TEST_F(TransportCliTest, AFileListedForTwoPatternsIsRefused) {
  auto manifest = manifest_;
  manifest.frames[3].file = manifest.frames[2].file;
  capture::write_manifest(manifest, capture_);
  EXPECT_NE(transport_error().find("same file"), std::string::npos);
}

TEST_F(TransportCliTest, PatternsIdenticalToTheirInversesDecodeNothingAndWriteNothing) {
  for (std::size_t i = 0; i < manifest_.frames.size(); ++i) {
    const auto& pattern = manifest_.frames[i].pattern;
    if (pattern.kind != capture::pattern_kind::kGrayColumn && pattern.kind != capture::pattern_kind::kGrayRow) continue;
    if (!pattern.inverse) continue;
    for (std::size_t j = 0; j < manifest_.frames.size(); ++j) {
      const auto& other = manifest_.frames[j].pattern;
      if (other.kind == pattern.kind && other.bit == pattern.bit && !other.inverse) {
        fs::copy_file(frame_path(j), frame_path(i), fs::copy_options::overwrite_existing);
      }
    }
  }
  EXPECT_NE(error_of<ProcessingError>({"transport", capture_.string(), "-o", output_.string()}).find("no camera pixel"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(output_));
}

// Every Gray frame a copy of the white frame: nothing decodes, and the capture checks' finding (a pattern and its
// inverse add up to twice the white frame) says why in the error itself.
TEST_F(TransportCliTest, NothingDecodedNamesTheCaptureChecksFindings) {
  for (std::size_t i = 0; i < manifest_.frames.size(); ++i) {
    const auto kind = manifest_.frames[i].pattern.kind;
    if (kind == capture::pattern_kind::kGrayColumn || kind == capture::pattern_kind::kGrayRow) {
      fs::copy_file(frame_path(0), frame_path(i), fs::copy_options::overwrite_existing);
    }
  }
  const std::string message = error_of<ProcessingError>({"transport", capture_.string(), "-o", output_.string()});
  EXPECT_THAT(message, ::testing::HasSubstr("no camera pixel"));
  EXPECT_THAT(message, ::testing::HasSubstr("Capture check: "));
  EXPECT_THAT(message, ::testing::HasSubstr("pattern + inverse"));
  EXPECT_FALSE(fs::exists(output_));
}

TEST_F(TransportCliTest, WronglyTypedOptionalManifestFieldsAreNamed) {
  for (const auto& [field, value] : {std::pair{"dot_spacing", nlohmann::json("4")},
                                     {"bit_depth", nlohmann::json(nullptr)},
                                     {"black_level", nlohmann::json::array()},
                                     {"camera_response", nlohmann::json(1)}}) {
    std::ifstream in(capture_ / "manifest.json");
    nlohmann::json root = nlohmann::json::parse(in);
    in.close();
    const nlohmann::json original = root;
    root[field] = value;
    std::ofstream(capture_ / "manifest.json", std::ios::trunc) << root.dump();
    EXPECT_NE(transport_error().find(field), std::string::npos) << field;
    std::ofstream(capture_ / "manifest.json", std::ios::trunc) << original.dump();
  }
}

TEST_F(TransportCliTest, PatternsDecodeBackToTheirProjectorCoordinates) {
  const fs::path out = dir_.path() / "patterns";
  run_cli({"patterns", "--projector", "20x9", "-o", out.string(), "--dot-spacing", "4"});
  const auto manifest = capture::read_manifest(out);
  EXPECT_EQ(manifest.frames.size(), 2u + 2u * (5u + 4u) + 16u);
  // Decoding the written Gray images as a camera that sees the projector pixel for pixel gives every coordinate.
  std::vector<std::uint32_t> pixel_x(std::size_t{20} * 9, 0), pixel_y(std::size_t{20} * 9, 0);
  for (const auto& frame : manifest.frames) {
    if (frame.pattern.inverse || (frame.pattern.kind != capture::pattern_kind::kGrayColumn &&
                                  frame.pattern.kind != capture::pattern_kind::kGrayRow)) {
      continue;
    }
    const bool columns = frame.pattern.kind == capture::pattern_kind::kGrayColumn;
    const cv::Mat image = cv::imread((out / frame.file).string(), cv::IMREAD_GRAYSCALE);
    const int bits = columns ? 5 : 4;
    for (int i = 0; i < 20 * 9; ++i) {
      if (image.ptr<unsigned char>()[i] > 127) (columns ? pixel_x : pixel_y)[i] |= 1u << (bits - 1 - frame.pattern.bit);
    }
  }
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 20; ++x) {
      std::uint32_t bx = 0, by = 0;
      for (std::uint32_t g = pixel_x[y * 20 + x]; g != 0; g >>= 1) bx ^= g;
      for (std::uint32_t g = pixel_y[y * 20 + x]; g != 0; g >>= 1) by ^= g;
      EXPECT_EQ(bx, static_cast<std::uint32_t>(x));
      EXPECT_EQ(by, static_cast<std::uint32_t>(y));
    }
  }
}

}  // namespace
}  // namespace rfrecon::transport
