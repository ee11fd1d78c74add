// T.h5 round trip, and clear InputErrors naming the file for missing, truncated, foreign and mis-shaped files.
#include "host/transport/transport_file.h"

#include <cstring>
#include <fstream>

#include <H5Cpp.h>
#include <gtest/gtest.h>

#include "host/capture/protocol.h"
#include "host/core/errors.h"
#include "tests/transport/synthetic_capture.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::transport {
namespace {

namespace fs = std::filesystem;

CompressedTransport small_transport() {
  testing::SceneOptions options;
  options.camera_size = {24, 20};
  options.projector_size = {16, 12};
  const auto scene = testing::make_plane_scene(options);
  const auto sequence = capture::make_protocol({options.projector_size, 3});
  const auto linear = testing::linearize(testing::render_frames(scene, sequence, 3, 1.0, 5));
  auto accumulator = make_reference_accumulator(testing::setup_for(linear, options.projector_size, 3, 4));
  return testing::feed_all(*accumulator, sequence, linear);
}

// Bitwise equality, NaN included (correspondence of unlit pixels).
template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <typename F>
std::string input_error_of(F&& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no InputError)";
}

TEST(TransportFileTest, RoundTripPreservesEveryArrayAndAttribute) {
  testing::TempDir dir("roundtrip");
  const auto written = small_transport();
  const fs::path file = dir.path() / "T.h5";
  write_transport(written, file);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1) << "no temporary left";
  const auto read = read_transport(file);
  EXPECT_EQ(read.setup.camera_size, written.setup.camera_size);
  EXPECT_EQ(read.setup.projector_size, written.setup.projector_size);
  EXPECT_EQ(read.setup.entries_per_pixel, 4);
  EXPECT_EQ(read.setup.dot_spacing, 3);
  EXPECT_EQ(read.setup.thresholds.noise, written.setup.thresholds.noise);  // float -> double -> float is exact
  EXPECT_TRUE(same_bits(read.indices, written.indices));
  EXPECT_TRUE(same_bits(read.weights, written.weights));
  EXPECT_TRUE(same_bits(read.correspondence, written.correspondence));
  EXPECT_TRUE(same_bits(read.gray_x, written.gray_x));
  EXPECT_TRUE(same_bits(read.gray_y, written.gray_y));
  EXPECT_TRUE(same_bits(read.flags, written.flags));
  EXPECT_TRUE(same_bits(read.direct_energy, written.direct_energy));
}

TEST(TransportFileTest, MissingForeignAndTruncatedFilesFailNamingTheFile) {
  testing::TempDir dir("corrupt");
  const fs::path missing = dir.path() / "missing.h5";
  EXPECT_NE(input_error_of([&] { read_transport(missing); }).find(missing.string()), std::string::npos);

  const fs::path text = dir.path() / "text.h5";
  std::ofstream(text) << "not HDF5\n";
  EXPECT_NE(input_error_of([&] { read_transport(text); }).find(text.string()), std::string::npos);

  const fs::path truncated = dir.path() / "truncated.h5";
  write_transport(small_transport(), truncated);
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const std::string message = input_error_of([&] { read_transport(truncated); });
  EXPECT_NE(message.find(truncated.string()), std::string::npos) << message;
}

TEST(TransportFileTest, DatasetShapeDisagreeingWithAttributesFailsNamingDataset) {
  testing::TempDir dir("shape");
  const fs::path file = dir.path() / "T.h5";
  const auto transport = small_transport();
  write_transport(transport, file);
  {
    H5::H5File h5(file.string(), H5F_ACC_RDWR);
    h5.unlink("weights");
    const hsize_t shape[3] = {20, 24, 5};  // K + 1 entries per pixel
    h5.createDataSet("weights", H5::PredType::NATIVE_FLOAT, H5::DataSpace(3, shape));
  }
  const std::string message = input_error_of([&] { read_transport(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("'weights'"), std::string::npos) << message;
}

TEST(TransportFileTest, IndicesOutsideTheProjectorFail) {
  testing::TempDir dir("indices");
  auto transport = small_transport();
  transport.indices[0] = static_cast<std::int32_t>(transport.projector_pixels());
  const fs::path file = dir.path() / "T.h5";
  write_transport(transport, file);
  EXPECT_NE(input_error_of([&] { read_transport(file); }).find("'indices'"), std::string::npos);
}

}  // namespace
}  // namespace rfrecon::transport
