// T.h5 round trip and checksums; every damaged, hostile or out-of-range file is an InputError naming the file and the
// attribute or dataset (and its first bad element); write failures leave nothing behind.
#include "host/transport/transport_file.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <thread>

#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>

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

template <typename Error, typename F>
std::string error_of(F&& action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "(no error of the expected type)";
}

template <typename F>
std::string input_error_of(F&& action) {
  return error_of<InputError>(action);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::size_t entries_in(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

void flip_byte(const fs::path& file, std::uint64_t offset) {
  std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
  stream.seekg(static_cast<std::streamoff>(offset));
  const char byte = static_cast<char>(stream.get() ^ 0x5a);
  stream.seekp(static_cast<std::streamoff>(offset));
  stream.put(byte);
}

// Replaces root attribute `name` of `file` by one of `type` holding *value.
void replace_attribute(const fs::path& file, const char* name, const H5::DataType& type, const void* value) {
  H5::H5File h5(file.string(), H5F_ACC_RDWR);
  h5.removeAttr(name);
  h5.createAttribute(name, type, H5::DataSpace(H5S_SCALAR)).write(type, value);
}

void replace_int_attribute(const fs::path& file, const char* name, std::int32_t value) {
  replace_attribute(file, name, H5::PredType::NATIVE_INT32, &value);
}

class TransportFileTest : public ::testing::Test {
 protected:
  // Writes `transport` after `damage`, then returns the InputError of reading it (which must name the file).
  std::string read_error(const std::function<void(CompressedTransport&)>& damage) {
    auto transport = small_transport();
    damage(transport);
    write_transport(transport, file_);
    return read_error();
  }

  std::string read_error() const {
    const std::string message = input_error_of([&] { read_transport(file_); });
    EXPECT_TRUE(contains(message, file_.string())) << message;
    return message;
  }

  testing::TempDir dir_{"transport_file"};
  fs::path file_ = dir_.path() / "T.h5";
};

TEST_F(TransportFileTest, RoundTripPreservesEveryArrayAndAttribute) {
  const auto written = small_transport();
  write_transport(written, file_);
  EXPECT_EQ(entries_in(dir_.path()), 1u) << "no temporary left";
  const auto read = read_transport(file_);
  EXPECT_EQ(read.setup.camera_size, written.setup.camera_size);
  EXPECT_EQ(read.setup.projector_size, written.setup.projector_size);
  EXPECT_EQ(read.setup.entries_per_pixel, 4);
  EXPECT_EQ(read.setup.dot_spacing, 3);
  EXPECT_EQ(read.setup.thresholds.noise, written.setup.thresholds.noise);  // float -> double -> float is exact
  EXPECT_TRUE(same_bits(read.indices, written.indices));
  EXPECT_TRUE(same_bits(read.weights, written.weights));
  EXPECT_TRUE(same_bits(read.correspondence, written.correspondence));
  EXPECT_TRUE(same_bits(read.pixel_x, written.pixel_x));
  EXPECT_TRUE(same_bits(read.pixel_y, written.pixel_y));
  EXPECT_TRUE(same_bits(read.flags, written.flags));
  EXPECT_TRUE(same_bits(read.direct_energy, written.direct_energy));
}

// T.h5 holds no times: the same transport written a second later is the same file, byte for byte (a batch's stage
// keyed by its file, a reproducible result).
TEST_F(TransportFileTest, TheSameTransportGivesTheSameBytes) {
  const auto transport = small_transport();
  write_transport(transport, file_);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // HDF5's object times have whole seconds
  const fs::path again = dir_.path() / "again.h5";
  write_transport(transport, again);
  const auto bytes = [](const fs::path& file) {
    std::ifstream stream(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(stream), {});
  };
  EXPECT_EQ(bytes(file_), bytes(again));
}

// The white frame is optional: a file without it reads with `white` empty, one with it gives it back bit for bit,
// checksummed like every dataset, and a value that is not finite fails naming its element.
TEST_F(TransportFileTest, TheWhiteFrameIsOptionalAndChecked) {
  auto transport = small_transport();
  ASSERT_TRUE(transport.white.empty());
  write_transport(transport, file_);
  EXPECT_TRUE(read_transport(file_).white.empty());

  transport.white.resize(transport.camera_pixels());
  for (std::size_t c = 0; c < transport.white.size(); ++c) transport.white[c] = 0.001f * static_cast<float>(c) - 0.01f;
  write_transport(transport, file_);
  EXPECT_TRUE(same_bits(read_transport(file_).white, transport.white));
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDONLY);
    const H5::DSetCreatPropList properties = h5.openDataSet("white").getCreatePlist();
    unsigned flags = 0;
    unsigned config = 0;
    std::size_t value_count = 0;
    EXPECT_NO_THROW(properties.getFilterById(H5Z_FILTER_FLETCHER32, flags, value_count, nullptr, 0, nullptr, config));
  }
  const std::string message = read_error([](CompressedTransport& t) {
    t.white.assign(t.camera_pixels(), 0.5f);
    t.white[24 * 4 + 10] = std::numeric_limits<float>::infinity();
  });
  EXPECT_TRUE(contains(message, "dataset 'white' element (4, 10) is inf")) << message;
}

TEST_F(TransportFileTest, EveryDatasetCarriesAChecksum) {
  write_transport(small_transport(), file_);
  H5::H5File h5(file_.string(), H5F_ACC_RDONLY);
  std::int32_t version = 0;
  h5.openAttribute("format_version").read(H5::PredType::NATIVE_INT32, &version);
  EXPECT_EQ(version, kTransportFileVersion);
  for (const char* name : {"indices", "weights", "correspondence", "decoded", "flags", "direct_energy"}) {
    const H5::DSetCreatPropList properties = h5.openDataSet(name).getCreatePlist();
    EXPECT_TRUE(properties.allFiltersAvail());
    unsigned flags = 0;
    unsigned config = 0;
    std::size_t value_count = 0;
    EXPECT_NO_THROW(properties.getFilterById(H5Z_FILTER_FLETCHER32, flags, value_count, nullptr, 0, nullptr, config))
        << name;
  }
}

// --deflate 0: the same arrays, every dataset still checksummed, none deflated; a level outside zlib's is a bug.
TEST_F(TransportFileTest, UncompressedFilesRoundTripWithChecksums) {
  const auto written = small_transport();
  write_transport(written, file_, 0);
  const auto read = read_transport(file_);
  EXPECT_TRUE(same_bits(read.indices, written.indices));
  EXPECT_TRUE(same_bits(read.weights, written.weights));
  EXPECT_TRUE(same_bits(read.correspondence, written.correspondence));
  EXPECT_TRUE(same_bits(read.direct_energy, written.direct_energy));
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDONLY);
    for (const char* name : {"indices", "weights", "correspondence", "decoded", "flags", "direct_energy"}) {
      const H5::DSetCreatPropList properties = h5.openDataSet(name).getCreatePlist();
      unsigned flags = 0;
      unsigned config = 0;
      std::size_t value_count = 0;
      EXPECT_NO_THROW(properties.getFilterById(H5Z_FILTER_FLETCHER32, flags, value_count, nullptr, 0, nullptr, config))
          << name;
      EXPECT_THROW(properties.getFilterById(H5Z_FILTER_DEFLATE, flags, value_count, nullptr, 0, nullptr, config),
                   H5::Exception)
          << name;
    }
  }
  EXPECT_THROW(write_transport(written, dir_.path() / "other.h5", 10), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_.path() / "other.h5"));
}

// Format version 1: the same layout without checksums (contiguous datasets here).
TEST_F(TransportFileTest, VersionOneFilesWithoutChecksumsStillRead) {
  const auto written = small_transport();
  write_transport(written, file_);
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDWR);
    for (const char* name : {"indices", "weights", "correspondence", "decoded", "flags", "direct_energy"}) {
      const H5::DataSet old = h5.openDataSet(name);
      const H5::DataType type = old.getDataType();
      const H5::DataSpace space = old.getSpace();
      std::vector<char> bytes(static_cast<std::size_t>(space.getSimpleExtentNpoints()) * type.getSize());
      old.read(bytes.data(), type);
      h5.unlink(name);
      h5.createDataSet(name, type, space).write(bytes.data(), type);
    }
  }
  replace_int_attribute(file_, "format_version", 1);
  const auto read = read_transport(file_);
  EXPECT_TRUE(same_bits(read.weights, written.weights));
  EXPECT_TRUE(same_bits(read.flags, written.flags));

  // ... but a version 2 file must have them.
  replace_int_attribute(file_, "format_version", 2);
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "dataset 'indices' has no checksum")) << message;
}

TEST_F(TransportFileTest, MissingForeignAndTruncatedFilesFail) {
  const fs::path missing = dir_.path() / "missing.h5";
  EXPECT_TRUE(contains(input_error_of([&] { read_transport(missing); }), missing.string()));

  const fs::path text = dir_.path() / "text.h5";
  std::ofstream(text) << "not HDF5\n";
  EXPECT_TRUE(contains(input_error_of([&] { read_transport(text); }), text.string()));

  write_transport(small_transport(), file_);
  const auto size = fs::file_size(file_);
  for (int eighth = 7; eighth >= 0; --eighth) {
    fs::resize_file(file_, size * static_cast<std::uintmax_t>(eighth) / 8);
    read_error();
  }
}

TEST_F(TransportFileTest, AFlippedByteInADatasetFailsItsChecksum) {
  write_transport(small_transport(), file_);
  haddr_t address = 0;
  hsize_t size = 0;
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDONLY);
    const H5::DataSet weights = h5.openDataSet("weights");
    hsize_t offset[3] = {};
    unsigned filter_mask = 0;
    ASSERT_GE(H5Dget_chunk_info(weights.getId(), weights.getSpace().getId(), 0, offset, &filter_mask, &address, &size),
              0);
  }
  flip_byte(file_, address + size / 2);
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "dataset 'weights' fails its checksum (the file is corrupt)")) << message;
}

TEST_F(TransportFileTest, AFlippedByteInTheMetadataFailsItsChecksum) {
  write_transport(small_transport(), file_);
  flip_byte(file_, 30);  // the superblock's end-of-file address
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "the HDF5 file fails its checksum (the file is corrupt)")) << message;
}

TEST_F(TransportFileTest, WeightsMustBeFiniteNonNegativeAndZeroInEmptySlots) {
  // small_transport() is 24 x 20 with K = 4; slot 4 * (24 * 2 + 3) + 1 is pixel (x 3, y 2), entry 1.
  constexpr std::size_t kSlot = 4 * (24 * 2 + 3) + 1;
  for (const float weight : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), -0.5f}) {
    const std::string message = read_error([&](CompressedTransport& t) {
      t.indices[kSlot] = 0;
      t.weights[kSlot] = weight;
    });
    std::ostringstream value;
    value << weight;
    EXPECT_TRUE(contains(message, "dataset 'weights' element (2, 3, 1) is " + value.str())) << message;
  }
  const std::string message = read_error([&](CompressedTransport& t) {
    t.indices[kSlot] = -1;
    t.weights[kSlot] = 0.25f;
  });
  EXPECT_TRUE(contains(message, "dataset 'weights' element (2, 3, 1) is 0.25")) << message;
}

TEST_F(TransportFileTest, IndicesOutsideTheProjectorFail) {
  for (const std::int32_t index : {16 * 12, -2}) {
    const std::string message = read_error([&](CompressedTransport& t) { t.indices[5] = index; });
    EXPECT_TRUE(contains(message, "dataset 'indices' element (0, 1, 1) is " + std::to_string(index))) << message;
  }
}

TEST_F(TransportFileTest, FlagsDecodedCorrespondenceAndEnergyOutOfRangeFail) {
  const std::size_t pixel = 24 * 4 + 10;  // (x 10, y 4)
  ASSERT_FALSE(std::isnan(small_transport().correspondence[2 * pixel])) << "the pixel has a correspondence";
  const struct {
    std::function<void(CompressedTransport&)> damage;
    std::string expected;
  } cases[] = {
      {[&](CompressedTransport& t) { t.flags[pixel] = 32; }, "dataset 'flags' element (4, 10) is 32"},
      {[&](CompressedTransport& t) { t.flags[pixel] = kFlagValid | kFlagShadow; },
       "dataset 'flags' element (4, 10) is 3"},
      {[&](CompressedTransport& t) {
         t.flags[pixel] = kFlagValid;
         t.pixel_y[pixel] = 12;
       },
       "dataset 'decoded' element (4, 10, 1) is 12"},
      {[&](CompressedTransport& t) { t.correspondence[2 * pixel] = std::numeric_limits<float>::infinity(); },
       "dataset 'correspondence' element (4, 10, 0) is inf"},
      {[&](CompressedTransport& t) { t.correspondence[2 * pixel + 1] = std::numeric_limits<float>::quiet_NaN(); },
       "dataset 'correspondence' element (4, 10, 0) is"},  // x without y
      {[&](CompressedTransport& t) { t.direct_energy[pixel] = -1.0f; },
       "dataset 'direct_energy' element (4, 10) is -1"},
  };
  for (const auto& c : cases) {
    const std::string message = read_error(c.damage);
    EXPECT_TRUE(contains(message, c.expected)) << message;
  }
}

TEST_F(TransportFileTest, DatasetShapeDisagreeingWithAttributesFails) {
  write_transport(small_transport(), file_);
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDWR);
    h5.unlink("weights");
    const hsize_t shape[3] = {20, 24, 5};  // K + 1 entries per pixel
    h5.createDataSet("weights", H5::PredType::NATIVE_FLOAT, H5::DataSpace(3, shape));
  }
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "dataset 'weights' has shape (20, 24, 5), the attributes require (20, 24, 4)"))
      << message;
}

TEST_F(TransportFileTest, WrongAttributeOrDatasetTypesFail) {
  write_transport(small_transport(), file_);
  const double width = 24.0;
  replace_attribute(file_, "camera_width", H5::PredType::NATIVE_DOUBLE, &width);
  EXPECT_TRUE(contains(read_error(), "attribute 'camera_width' is float, expected integer"));

  write_transport(small_transport(), file_);
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDWR);
    h5.unlink("flags");
    const hsize_t shape[2] = {20, 24};
    h5.createDataSet("flags", H5::PredType::NATIVE_FLOAT, H5::DataSpace(2, shape));
  }
  EXPECT_TRUE(contains(read_error(), "dataset 'flags' is float, expected integer"));

  write_transport(small_transport(), file_);
  const H5::StrType text(H5::PredType::C_S1, 4);
  replace_attribute(file_, "format_version", text, "two");
  EXPECT_TRUE(contains(read_error(), "attribute 'format_version' is string, expected integer"));
}

TEST_F(TransportFileTest, SizesBeyondTheMaximaFailBeforeAllocating) {
  write_transport(small_transport(), file_);
  replace_int_attribute(file_, "camera_width", 1000000);
  EXPECT_TRUE(contains(read_error(), "attribute 'camera_width' is 1000000, outside [1, 16384]"));
  replace_int_attribute(file_, "camera_width", 24);
  replace_int_attribute(file_, "entries_per_pixel", 1000);
  EXPECT_TRUE(contains(read_error(), "attribute 'entries_per_pixel' is 1000, outside [1, 64]"));
}

// A tiny file claiming the largest camera: its datasets' chunks were never written (HDF5 would read fill values).
TEST_F(TransportFileTest, DatasetsHoldingLessThanTheyClaimFailBeforeAllocating) {
  write_transport(small_transport(), file_);
  replace_int_attribute(file_, "camera_width", kMaxTransportImageSide);
  replace_int_attribute(file_, "camera_height", kMaxTransportImageSide);
  replace_int_attribute(file_, "entries_per_pixel", 1);
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDWR);
    h5.unlink("indices");
    const hsize_t shape[3] = {kMaxTransportImageSide, kMaxTransportImageSide, 1};
    const hsize_t chunk[3] = {32, kMaxTransportImageSide, 1};
    H5::DSetCreatPropList properties;
    properties.setChunk(3, chunk);
    properties.setFletcher32();
    h5.createDataSet("indices", H5::PredType::NATIVE_INT32, H5::DataSpace(3, shape), properties);
  }
  EXPECT_LT(fs::file_size(file_), 100000u);
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "dataset 'indices' stores 0 bytes, too few for its 1073741824")) << message;
}

// stat(2) decides before HDF5 opens anything: opening a FIFO with no writer would wait forever.
TEST_F(TransportFileTest, AFifoIsRefusedWithoutOpeningIt) {
  ASSERT_EQ(::mkfifo(file_.c_str(), 0600), 0);
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "is a FIFO (a named pipe)")) << message;
}

// A dataset reached through a soft or external link, or keeping its data in external files: the reader refuses it
// before HDF5 follows it, so another file (here a FIFO, which would block) is never opened.
TEST_F(TransportFileTest, DatasetsMustLiveInTheFileItself) {
  const fs::path fifo = dir_.path() / "elsewhere";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const struct {
    std::function<void(H5::H5File&)> change;
    std::string expected;
  } cases[] = {
      {[&](H5::H5File& h5) {
         h5.unlink("weights");
         ASSERT_GE(H5Lcreate_external(fifo.c_str(), "/weights", h5.getId(), "weights", H5P_DEFAULT, H5P_DEFAULT), 0);
       },
       "dataset 'weights' is an external link"},
      {[&](H5::H5File& h5) {
         h5.unlink("weights");
         h5.link(H5L_TYPE_SOFT, "/indices", "weights");
       },
       "dataset 'weights' is a soft link"},
      {[&](H5::H5File& h5) {
         h5.unlink("flags");
         const hsize_t shape[2] = {20, 24};
         H5::DSetCreatPropList properties;
         properties.setExternal(fifo.c_str(), 0, 20 * 24);
         h5.createDataSet("flags", H5::PredType::NATIVE_UINT8, H5::DataSpace(2, shape), properties);
       },
       "dataset 'flags' keeps its data in external files"},
  };
  for (const auto& c : cases) {
    write_transport(small_transport(), file_);
    {
      H5::H5File h5(file_.string(), H5F_ACC_RDWR);
      c.change(h5);
    }
    const std::string message = read_error();
    EXPECT_TRUE(contains(message, c.expected)) << message;
  }
}

// A filter HDF5 does not have built in would make it search its plugin directories for a library to load.
TEST_F(TransportFileTest, DatasetsWithFiltersThatAreNotBuiltInFail) {
  write_transport(small_transport(), file_);
  {
    H5::H5File h5(file_.string(), H5F_ACC_RDWR);
    h5.unlink("flags");
    const hsize_t shape[2] = {20, 24};
    H5::DSetCreatPropList properties;
    properties.setChunk(2, shape);
    properties.setFilter(32000, H5Z_FLAG_OPTIONAL);  // LZF's registered ID, which HDF5 itself lacks
    properties.setFletcher32();
    h5.createDataSet("flags", H5::PredType::NATIVE_UINT8, H5::DataSpace(2, shape), properties);
  }
  const std::string message = read_error();
  EXPECT_TRUE(contains(message, "dataset 'flags' uses HDF5 filter 32000")) << message;
}

// Strings of any storage are at most 256 bytes; a variable-length one is read first (it cannot be longer than the
// file), a fixed-length one is refused from its type. Messages quote a string attribute only in part.
TEST_F(TransportFileTest, LongStringAttributesFailAndAreQuotedInPart) {
  write_transport(small_transport(), file_);
  const std::string long_text(100000, 'x');
  const char* text = long_text.c_str();
  replace_attribute(file_, "format", H5::StrType(H5::PredType::C_S1, H5T_VARIABLE), &text);
  std::string message = read_error();
  EXPECT_TRUE(contains(message, "attribute 'format' is a string of 100000 bytes, more than 256")) << message;

  replace_attribute(file_, "format", H5::StrType(H5::PredType::C_S1, long_text.size()), text);
  message = read_error();
  EXPECT_TRUE(contains(message, "attribute 'format' is a string of 100000 bytes, more than 256")) << message;

  write_transport(small_transport(), file_);
  const std::string protocol(250, 'p');
  replace_attribute(file_, "protocol", H5::StrType(H5::PredType::C_S1, protocol.size()), protocol.c_str());
  message = read_error();
  EXPECT_TRUE(contains(message, "attribute 'protocol' is 'ppp")) << message;
  EXPECT_TRUE(contains(message, "(250 bytes)")) << message;
  EXPECT_LT(message.size(), file_.string().size() + 200) << message;

  // A family's name without "+dots" where the file has a dot grid (dot_spacing 3).
  write_transport(small_transport(), file_);
  const std::string phase = "phase";
  replace_attribute(file_, "protocol", H5::StrType(H5::PredType::C_S1, phase.size()), phase.c_str());
  message = read_error();
  EXPECT_TRUE(contains(message, "'phase': with dot_spacing 3 it is 'gray+dots' or a family's name and '+dots'"))
      << message;
}

TEST_F(TransportFileTest, UnwritableOutputsFailNamingThePathAndLeaveNothing) {
  const fs::path blocker = dir_.path() / "blocker";
  std::ofstream(blocker) << "a file where a directory should be\n";
  EXPECT_TRUE(
      contains(error_of<OutputError>([&] { write_transport(small_transport(), blocker / "T.h5"); }), blocker.string()));

  fs::create_directories(file_ / "inside");  // the output path is a non-empty directory
  EXPECT_TRUE(contains(error_of<OutputError>([&] { write_transport(small_transport(), file_); }), file_.string()));
  EXPECT_EQ(entries_in(dir_.path()), 2u) << "blocker and T.h5/ only: no temporary left";
}

// A full disk: a tmpfs smaller than the file. Mounting needs root (CAP_SYS_ADMIN); the test skips without it.
TEST_F(TransportFileTest, AFullDiskFailsNamingTheOutputAndLeavesNoTemporary) {
  const fs::path disk = dir_.path() / "disk";
  fs::create_directories(disk);
  if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=4k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs: " << std::strerror(errno);
  }
  struct Unmount {
    const fs::path& path;
    ~Unmount() { ::umount2(path.c_str(), MNT_DETACH); }
  } unmount{disk};
  const fs::path file = disk / "T.h5";
  const std::string message = error_of<OutputError>([&] { write_transport(small_transport(), file); });
  EXPECT_TRUE(contains(message, file.string())) << message;
  EXPECT_EQ(entries_in(disk), 0u) << "no temporary left";
}

}  // namespace
}  // namespace rfrecon::transport
