// HDF5 reading and writing of the compressed light transport (H5Cpp): every call guarded, every value checked.
#include "host/transport/transport_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <H5Cpp.h>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/input_file.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"

namespace rfrecon::transport {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "rfrecon-transport";
constexpr int kFirstChecksummedVersion = 2;
constexpr hsize_t kMaxStringBytes = 256;          // longest string attribute
constexpr std::size_t kMaxQuotedHdf5Chars = 160;  // of an HDF5 error description, which may quote the file
constexpr hsize_t kMaxElementBytes = 8;           // largest integer or float element
constexpr hsize_t kMaxDeflateRatio = 1032;        // zlib's largest compression ratio
constexpr hsize_t kRowsPerChunk = 32;             // bands of camera rows: compress well, read row by row
constexpr std::size_t kMemoryIncrementBytes = std::size_t{1} << 20;

template <typename T>
const H5::PredType& h5_type();
template <>
const H5::PredType& h5_type<std::int32_t>() {
  return H5::PredType::NATIVE_INT32;
}
template <>
const H5::PredType& h5_type<std::int64_t>() {
  return H5::PredType::NATIVE_INT64;
}
template <>
const H5::PredType& h5_type<std::uint32_t>() {
  return H5::PredType::NATIVE_UINT32;
}
template <>
const H5::PredType& h5_type<float>() {
  return H5::PredType::NATIVE_FLOAT;
}
template <>
const H5::PredType& h5_type<std::uint8_t>() {
  return H5::PredType::NATIVE_UINT8;
}
template <>
const H5::PredType& h5_type<double>() {
  return H5::PredType::NATIVE_DOUBLE;
}

// The type class a file's values need to be read as T (HDF5 converts sizes and byte orders within a class).
template <typename T>
constexpr H5T_class_t kClassOf = std::is_floating_point_v<T> ? H5T_FLOAT : H5T_INTEGER;

std::string class_name(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_INTEGER:
      return "integer";
    case H5T_FLOAT:
      return "float";
    case H5T_STRING:
      return "string";
    default:
      return "of type class " + std::to_string(static_cast<int>(type_class));
  }
}

std::string describe(const std::vector<hsize_t>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i > 0 ? ", " : "") + std::to_string(shape[i]);
  return text + ")";
}

hsize_t element_count(const std::vector<hsize_t>& shape) {
  hsize_t count = 1;
  for (const hsize_t extent : shape) count *= extent;
  return count;
}

// Shape (height, width[, depth]) of a per-camera-pixel dataset.
std::vector<hsize_t> pixel_shape(const TransportSetup& setup, hsize_t depth) {
  std::vector<hsize_t> shape{static_cast<hsize_t>(setup.camera_size.height),
                             static_cast<hsize_t>(setup.camera_size.width)};
  if (depth > 0) shape.push_back(depth);
  return shape;
}

// The shapes of the datasets: indices and weights, correspondence and decoded, flags and direct_energy.
struct Shapes {
  explicit Shapes(const TransportSetup& setup)
      : entries(pixel_shape(setup, static_cast<hsize_t>(setup.entries_per_pixel))),
        pairs(pixel_shape(setup, 2)),
        pixels(pixel_shape(setup, 0)) {}
  std::vector<hsize_t> entries;  // (H, W, K)
  std::vector<hsize_t> pairs;    // (H, W, 2)
  std::vector<hsize_t> pixels;   // (H, W)
};

// The dataset's filters, in pipeline order.
std::vector<H5Z_filter_t> filters(const H5::DSetCreatPropList& properties) {
  std::vector<H5Z_filter_t> ids;
  for (int i = 0; i < properties.getNfilters(); ++i) {
    unsigned flags = 0;
    unsigned config = 0;
    std::size_t value_count = 0;
    ids.push_back(properties.getFilter(i, flags, value_count, nullptr, 0, nullptr, config));
  }
  return ids;
}

// HDF5's own filters (deflate, shuffle, Fletcher32, szip, n-bit, scale-offset): any other would make HDF5 look for a
// plugin library to load.
bool built_in(H5Z_filter_t filter) { return filter >= H5Z_FILTER_DEFLATE && filter <= H5Z_FILTER_SCALEOFFSET; }

// Flag combinations the accumulators produce (kernels/transport/flags.h): valid only without shadow, low contrast
// or out of range; no signal only for compressible pixels.
bool allowed_flags(std::uint8_t flags) {
  constexpr unsigned kAll = kFlagValid | kFlagShadow | kFlagLowContrast | kFlagOutOfRange | kFlagNoSignal;
  return (flags & ~kAll) == 0 &&
         ((flags & kFlagValid) == 0 || (flags & (kFlagShadow | kFlagLowContrast | kFlagOutOfRange)) == 0) &&
         ((flags & kFlagNoSignal) == 0 || compressible(flags));
}

template <typename T>
void write_dataset(H5::H5File& file, const char* name, const std::vector<hsize_t>& shape, const std::vector<T>& data,
                   int deflate_level) {
  if (data.size() != element_count(shape)) {
    throw std::logic_error(std::string("write_transport: '") + name + "' holds " + std::to_string(data.size()) +
                           " values, its shape " + describe(shape) + " needs " + std::to_string(element_count(shape)));
  }
  H5::DataSpace space(static_cast<int>(shape.size()), shape.data());
  H5::DSetCreatPropList properties;
  std::vector<hsize_t> chunk = shape;
  chunk[0] = std::min(shape[0], kRowsPerChunk);
  properties.setChunk(static_cast<int>(chunk.size()), chunk.data());
  if (deflate_level > 0) properties.setDeflate(deflate_level);
  properties.setFletcher32();  // after deflate: checks the stored bytes before they are inflated
  // No times in the dataset's object header (MemoryFile::create).
  if (H5Pset_obj_track_times(properties.getId(), 0) < 0) {
    throw H5::PropListIException("H5Pset_obj_track_times", "cannot leave the times out of T.h5");
  }
  H5::DataSet dataset = file.createDataSet(name, h5_type<T>(), space, properties);
  dataset.write(data.data(), h5_type<T>());
}

template <typename T>
void write_attribute(H5::H5File& file, const char* name, T value) {
  H5::Attribute attribute = file.createAttribute(name, h5_type<T>(), H5::DataSpace(H5S_SCALAR));
  attribute.write(h5_type<T>(), &value);
}

void write_attribute(H5::H5File& file, const char* name, const std::string& value) {
  const H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(value.size(), 1));
  H5::Attribute attribute = file.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, value);
}

// An HDF5 file built in memory (core driver) whose bytes, as the closing file leaves them, are kept here: the driver
// hands its buffer to release() instead of freeing it.
class MemoryFile {
 public:
  MemoryFile(const MemoryFile&) = delete;  // the driver's callbacks point to it
  MemoryFile& operator=(const MemoryFile&) = delete;
  MemoryFile() {
    access_.setCore(kMemoryIncrementBytes, false);
    access_.setLibverBounds(H5F_LIBVER_V18, H5F_LIBVER_V18);  // checksummed metadata, readable by HDF5 1.8 and later
    H5FD_file_image_callbacks_t callbacks{&allocate, &copy, &resize, &release, &share, &unshare, this};
    if (H5Pset_file_image_callbacks(access_.getId(), &callbacks) < 0) {
      throw H5::PropListIException("H5Pset_file_image_callbacks", "cannot keep the file in memory");
    }
  }

  // Creates the file; `name` (a path that does not exist) only names it: nothing is written there. Its root group
  // holds no times (nor do the datasets, write_dataset): the same T gives the same file, byte for byte.
  H5::H5File create(const fs::path& name) const {
    const H5::FileCreatPropList creation;
    if (H5Pset_obj_track_times(creation.getId(), 0) < 0) {
      throw H5::PropListIException("H5Pset_obj_track_times", "cannot leave the times out of T.h5");
    }
    return H5::H5File(name.string(), H5F_ACC_TRUNC, creation, access_);
  }

  // The closed file's bytes, up to the end-of-file address of its superblock (version 2, 8-byte addresses: at byte
  // 28; the buffer itself is a multiple of kMemoryIncrementBytes).
  std::string_view bytes() const {
    constexpr std::string_view kSignature("\211HDF\r\n\032\n", 8);
    constexpr std::size_t kEofOffset = 28;
    std::uint64_t eof = 0;
    const char* image = kept_.get();
    if (kept_size_ < kEofOffset + sizeof eof || std::string_view(image, 8) != kSignature || image[8] != 2 ||
        image[9] != static_cast<char>(sizeof eof)) {
      throw H5::FileIException("MemoryFile::bytes", "the closed file does not start with a version 2 superblock");
    }
    std::memcpy(&eof, image + kEofOffset, sizeof eof);  // little-endian, as the format
    if (eof > kept_size_) throw H5::FileIException("MemoryFile::bytes", "superblock end of file beyond the image");
    return {image, static_cast<std::size_t>(eof)};
  }

 private:
  static void* allocate(std::size_t size, H5FD_file_image_op_t /*op*/, void* self) {
    static_cast<MemoryFile*>(self)->size_ = size;
    return std::malloc(size);
  }
  static void* copy(void* to, const void* from, std::size_t size, H5FD_file_image_op_t /*op*/, void* /*self*/) {
    return std::memcpy(to, from, size);
  }
  static void* resize(void* memory, std::size_t size, H5FD_file_image_op_t /*op*/, void* self) {
    static_cast<MemoryFile*>(self)->size_ = size;
    return std::realloc(memory, size);
  }
  static herr_t release(void* memory, H5FD_file_image_op_t op, void* self) {
    if (op != H5FD_FILE_IMAGE_OP_FILE_CLOSE) {
      std::free(memory);
      return 0;
    }
    auto* file = static_cast<MemoryFile*>(self);
    file->kept_.reset(static_cast<char*>(memory));
    file->kept_size_ = file->size_;
    return 0;
  }
  static void* share(void* self) { return self; }  // the property list's copies all point to this object
  static herr_t unshare(void* /*self*/) { return 0; }

  H5::FileAccPropList access_;
  std::size_t size_ = 0;  // of the buffer the driver holds
  std::unique_ptr<char, decltype(&std::free)> kept_{nullptr, &std::free};
  std::size_t kept_size_ = 0;
};

// While it lives, HDF5 hands the error stack of each failing call to this object instead of printing it: the reader
// quotes the innermost error and recognises checksum failures.
class Hdf5Errors {
 public:
  Hdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &saved_handler_, &saved_data_);
    H5Eset_auto2(H5E_DEFAULT, &Hdf5Errors::record, this);
  }
  ~Hdf5Errors() { H5Eset_auto2(H5E_DEFAULT, saved_handler_, saved_data_); }
  Hdf5Errors(const Hdf5Errors&) = delete;
  Hdf5Errors& operator=(const Hdf5Errors&) = delete;

  // The descriptions of the last failure, from the API call down to where HDF5 detected it; forgets them.
  std::vector<std::string> take() { return std::exchange(last_, {}); }
  void clear() { last_.clear(); }

 private:
  static herr_t record(hid_t stack, void* self) noexcept {
    auto& last = static_cast<Hdf5Errors*>(self)->last_;
    last.clear();
    H5Ewalk2(stack, H5E_WALK_DOWNWARD, &Hdf5Errors::add, &last);
    return 0;
  }
  static herr_t add(unsigned /*depth*/, const H5E_error2_t* error, void* last) noexcept {
    try {
      static_cast<std::vector<std::string>*>(last)->emplace_back(error->desc != nullptr ? error->desc : "");
    } catch (const std::bad_alloc&) {
      return -1;  // stops the walk: the descriptions are a courtesy
    }
    return 0;
  }

  H5E_auto2_t saved_handler_ = nullptr;
  void* saved_data_ = nullptr;
  std::vector<std::string> last_;
};

// Reading: every HDF5 call inside guarded(), every failure an InputError naming the file and the object.
class Reader {
 public:
  explicit Reader(fs::path path) : path_(std::move(path)) {
    check_input_file(path_);  // before HDF5 opens it: a FIFO would block
    std::error_code error;
    file_bytes_ = fs::file_size(path_, error);
    if (error) fail("cannot be read (" + error.message() + ")");
    guarded("the HDF5 file", [&] { file_ = H5::H5File(path_.string(), H5F_ACC_RDONLY); });
  }

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_.string() + ": " + what); }

  // Runs `step`, HDF5 calls about `object`, turning every exception but our own InputErrors into one.
  template <typename Step>
  auto guarded(const std::string& object, Step&& step) -> decltype(step()) {
    errors_.clear();
    try {
      return step();
    } catch (const InputError&) {
      throw;
    } catch (const H5::Exception& error) {
      fail_reading(object, error.getDetailMsg());
    } catch (const std::exception& error) {
      fail_reading(object, error.what());
    }
  }

  // format_version, which says whether the datasets carry checksums.
  void read_version() {
    const auto version = number<std::int64_t>("format_version");
    if (version < 1 || version > kTransportFileVersion) {
      fail("format_version " + std::to_string(version) + " is not supported (this build reads 1 to " +
           std::to_string(kTransportFileVersion) + ")");
    }
    checksums_ = version >= kFirstChecksummedVersion;
  }

  // An integer attribute in [min, max].
  int integer(const char* name, int min, int max) {
    const auto value = number<std::int64_t>(name);
    if (value < min || value > max) {
      fail(std::string("attribute '") + name + "' is " + std::to_string(value) + ", outside [" + std::to_string(min) +
           ", " + std::to_string(max) + "]");
    }
    return static_cast<int>(value);
  }

  double finite(const char* name) {
    const auto value = number<double>(name);
    if (!std::isfinite(value)) fail(std::string("attribute '") + name + "' is " + text(value) + ", not finite");
    return value;
  }

  std::string string(const char* name) {
    return guarded(std::string("attribute '") + name + "'", [&] {
      const H5::Attribute attribute = single_value(name, H5T_STRING);
      const H5::StrType type = attribute.getStrType();
      if (!type.isVariableStr() && type.getSize() > kMaxStringBytes) {
        fail(std::string("attribute '") + name + "' is a string of " + std::to_string(type.getSize()) +
             " bytes, more than " + std::to_string(kMaxStringBytes));
      }
      std::string value;
      attribute.read(type, value);  // a variable-length string is read from the file: no longer than the file
      value.resize(std::min(value.size(), value.find('\0')));  // drop any NUL padding
      if (value.size() > kMaxStringBytes) {
        fail(std::string("attribute '") + name + "' is a string of " + std::to_string(value.size()) +
             " bytes, more than " + std::to_string(kMaxStringBytes));
      }
      return value;
    });
  }

  // Dataset `name`, which must have `shape`, read as T. Its link, storage, type, shape, chunks, filters and stored
  // size are checked before anything is allocated or any other file opened: the data lies in this file, which
  // cannot claim more data than it holds (deflate compresses at most 1032:1).
  template <typename T>
  std::vector<T> dataset(const char* name, const std::vector<hsize_t>& shape) {
    const std::string label = std::string("dataset '") + name + "'";
    return guarded(label, [&] {
      if (!file_.nameExists(name)) fail("missing " + label);
      check_hard_link(name, label);
      const H5::DataSet dataset = file_.openDataSet(name);
      const H5::DataType type = dataset.getDataType();
      check_type(label, type, kClassOf<T>);
      const H5::DataSpace space = dataset.getSpace();
      std::vector<hsize_t> extent(static_cast<std::size_t>(space.getSimpleExtentNdims()));
      space.getSimpleExtentDims(extent.data());
      if (extent != shape) {
        fail(label + " has shape " + describe(extent) + ", the attributes require " + describe(shape));
      }
      const H5::DSetCreatPropList properties = dataset.getCreatePlist();
      check_storage(label, properties);
      if (properties.getLayout() == H5D_CHUNKED) {
        std::vector<hsize_t> chunk(shape.size());
        properties.getChunk(static_cast<int>(chunk.size()), chunk.data());
        if (!std::equal(chunk.begin(), chunk.end(), shape.begin(), std::less_equal<>())) {
          fail(label + " has chunks " + describe(chunk) + " larger than its shape " + describe(shape));
        }
      }
      const hsize_t bytes = element_count(shape) * type.getSize();
      const hsize_t stored_bytes = dataset.getStorageSize();
      if (stored_bytes > file_bytes_) {
        fail(label + " stores " + std::to_string(stored_bytes) + " bytes, more than the file's " +
             std::to_string(file_bytes_) + " (corrupt chunk index?)");
      }
      if (stored_bytes * kMaxDeflateRatio < bytes) {
        fail(label + " stores " + std::to_string(stored_bytes) + " bytes, too few for its " + std::to_string(bytes) +
             " (truncated or corrupt file?)");
      }
      std::vector<T> values(element_count(shape));
      dataset.read(values.data(), h5_type<T>());
      return values;
    });
  }

  // Fails at the first element of dataset `name` for which valid(i) is false, naming its index and value.
  template <typename T, typename Valid>
  void check(const char* name, const std::vector<hsize_t>& shape, const std::vector<T>& values, Valid&& valid,
             const std::string& rule) const {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (valid(i)) continue;
      std::vector<hsize_t> index(shape.size());
      hsize_t rest = i;
      for (std::size_t d = shape.size(); d-- > 0;) {
        index[d] = rest % shape[d];
        rest /= shape[d];
      }
      fail(std::string("dataset '") + name + "' element " + describe(index) + " is " + text(values[i]) + ": " + rule);
    }
  }

  // Whether the file holds an object `name` (for the optional datasets).
  bool has(const char* name) {
    return guarded(std::string("dataset '") + name + "'", [&] { return file_.nameExists(name); });
  }
  bool has_attribute(const char* name) {
    return guarded(std::string("attribute '") + name + "'", [&] { return file_.attrExists(name); });
  }

  void close() {
    guarded("the HDF5 file", [&] { file_.close(); });
  }

 private:
  template <typename T>
  static std::string text(T value) {
    std::ostringstream out;
    out << +value;  // uint8 as a number
    return out.str();
  }

  // Object `name` is a hard link: a soft or external link could lead to another file (a FIFO, a device).
  void check_hard_link(const char* name, const std::string& label) const {
    H5L_info_t link{};
    if (H5Lget_info(file_.getId(), name, &link, H5P_DEFAULT) < 0) fail(label + " has an unreadable link");
    if (link.type != H5L_TYPE_HARD) {
      fail(label + (link.type == H5L_TYPE_SOFT ? " is a soft link" : " is an external link") +
           "; a transport file holds its datasets itself");
    }
  }

  // The data is stored in this file (no external raw data files, no virtual dataset's source files), through
  // HDF5's built-in filters, with checksums when the version requires them.
  void check_storage(const std::string& label, const H5::DSetCreatPropList& properties) const {
    const H5D_layout_t layout = properties.getLayout();
    if (layout != H5D_CHUNKED && layout != H5D_CONTIGUOUS && layout != H5D_COMPACT) {
      fail(label + " is a virtual dataset; a transport file holds its data itself");
    }
    if (properties.getExternalCount() > 0) {
      fail(label + " keeps its data in external files; a transport file holds its data itself");
    }
    const auto ids = filters(properties);
    const auto other = std::find_if_not(ids.begin(), ids.end(), built_in);
    if (other != ids.end()) {
      fail(label + " uses HDF5 filter " + std::to_string(*other) + ", which is not one of HDF5's built-in filters");
    }
    if (checksums_ && std::find(ids.begin(), ids.end(), H5Z_FILTER_FLETCHER32) == ids.end()) {
      fail(label + " has no checksum, which format_version 2 requires");
    }
  }

  void check_type(const std::string& label, const H5::DataType& type, H5T_class_t type_class) const {
    if (type.getClass() != type_class) {
      fail(label + " is " + class_name(type.getClass()) + ", expected " + class_name(type_class));
    }
    if (type_class != H5T_STRING && type.getSize() > kMaxElementBytes) {
      fail(label + " has " + std::to_string(type.getSize()) + "-byte values");
    }
  }

  // Attribute `name`: one value (scalar, or one element) of `type_class`.
  H5::Attribute single_value(const char* name, H5T_class_t type_class) {
    const std::string label = std::string("attribute '") + name + "'";
    if (!file_.attrExists(name)) fail("missing " + label);
    H5::Attribute attribute = file_.openAttribute(name);
    check_type(label, attribute.getDataType(), type_class);
    const H5::DataSpace space = attribute.getSpace();
    if (space.getSimpleExtentNpoints() != 1 || space.getSimpleExtentNdims() > 1) fail(label + " is not one value");
    return attribute;
  }

  template <typename T>
  T number(const char* name) {
    return guarded(std::string("attribute '") + name + "'", [&] {
      T value{};
      single_value(name, kClassOf<T>).read(h5_type<T>(), &value);
      return value;
    });
  }

  [[noreturn]] void fail_reading(const std::string& object, const std::string& detail) {
    const std::vector<std::string> stack = errors_.take();
    if (std::any_of(stack.begin(), stack.end(),
                    [](const std::string& error) { return error.find("checksum") != std::string::npos; })) {
      fail(object + " fails its checksum (the file is corrupt)");
    }
    fail(object + " is unreadable (truncated or corrupt file?): HDF5: " +
         excerpt(stack.empty() ? detail : stack.back(), kMaxQuotedHdf5Chars));
  }

  fs::path path_;
  std::uintmax_t file_bytes_ = 0;
  Hdf5Errors errors_;
  H5::H5File file_;
  bool checksums_ = false;
};

// The value rules of docs/formats.md, in the order of the datasets; decoded is (H, W, 2).
void check_values(const Reader& reader, const CompressedTransport& transport, const std::vector<std::uint32_t>& decoded,
                  const Shapes& shapes) {
  const auto projector_pixels = static_cast<std::int64_t>(transport.projector_pixels());
  const auto& indices = transport.indices;
  const auto& weights = transport.weights;
  const auto& correspondence = transport.correspondence;
  const auto& flags = transport.flags;
  const auto& energy = transport.direct_energy;
  const cv::Size projector = transport.setup.projector_size;
  // The extent of coordinate i of a (H, W, 2) dataset: projector width for x, height for y.
  const auto axis_extent = [&](std::size_t i) { return i % 2 == 0 ? projector.width : projector.height; };
  reader.check(
      "indices", shapes.entries, indices,
      [&](std::size_t i) { return indices[i] >= -1 && indices[i] < projector_pixels; },
      "must be -1 (empty slot) or a projector pixel in [0, " + std::to_string(projector_pixels) + ")");
  reader.check(
      "weights", shapes.entries, weights,
      [&](std::size_t i) {
        return std::isfinite(weights[i]) && weights[i] >= 0.0f && (indices[i] >= 0 || weights[i] == 0.0f);
      },
      "must be finite and >= 0, and 0 in empty slots (index -1)");
  reader.check(
      "correspondence", shapes.pairs, correspondence,
      [&](std::size_t i) {
        const float value = correspondence[i];
        const bool other_nan = std::isnan(correspondence[i ^ 1]);
        return std::isnan(value) ? other_nan
                                 : !other_nan && value >= -1.0f && value <= static_cast<float>(axis_extent(i));
      },
      "(x, y) must both be NaN or lie within 1 px of the projector image, [-1, " + std::to_string(projector.width) +
          "] x [-1, " + std::to_string(projector.height) + "]");
  reader.check(
      "flags", shapes.pixels, flags, [&](std::size_t i) { return allowed_flags(flags[i]); },
      "not a combination of the flag bits that docs/formats.md allows");
  reader.check(
      "decoded", shapes.pairs, decoded,
      [&](std::size_t i) {
        return (flags[i / 2] & kFlagValid) == 0 || decoded[i] < static_cast<std::uint32_t>(axis_extent(i));
      },
      "the pixel's flags say valid, so its decoded coordinate must lie inside the projector");
  reader.check(
      "direct_energy", shapes.pixels, energy,
      [&](std::size_t i) { return std::isfinite(energy[i]) && energy[i] >= 0.0f; }, "must be finite and >= 0");
  const auto& white = transport.white;
  reader.check(
      "white", shapes.pixels, white, [&](std::size_t i) { return std::isfinite(white[i]); }, "must be finite");
}

}  // namespace

void write_transport(const CompressedTransport& transport, const fs::path& file, int deflate_level) {
  if (deflate_level < 0 || deflate_level > 9) {
    throw std::invalid_argument("write_transport: deflate level " + std::to_string(deflate_level) + " is not 0 to 9");
  }
  const TransportSetup& setup = transport.setup;
  H5::Exception::dontPrint();
  try {
    AtomicFile output(file);
    // Built in memory, so that HDF5 never meets a full disk, then written by plain file I/O, whole or not at all.
    MemoryFile memory;
    H5::H5File h5 = memory.create(output.temp_path());
    write_attribute(h5, "format", std::string(kFormat));
    write_attribute(h5, "format_version", std::int32_t{kTransportFileVersion});
    write_attribute(h5, "software_version", std::string("rfrecon ") + RFRECON_VERSION);
    write_attribute(h5, "protocol", transport.protocol());
    write_attribute(h5, "camera_width", std::int32_t{setup.camera_size.width});
    write_attribute(h5, "camera_height", std::int32_t{setup.camera_size.height});
    write_attribute(h5, "projector_width", std::int32_t{setup.projector_size.width});
    write_attribute(h5, "projector_height", std::int32_t{setup.projector_size.height});
    write_attribute(h5, "entries_per_pixel", std::int32_t{setup.entries_per_pixel});
    write_attribute(h5, "dot_spacing", std::int32_t{setup.dot_spacing});
    write_attribute(h5, "black_threshold", double{setup.thresholds.black});
    write_attribute(h5, "white_threshold", double{setup.thresholds.white});
    write_attribute(h5, "noise_threshold", double{setup.thresholds.noise});
    if (transport.camera_noise.known()) {
      write_attribute(h5, "noise_read_variance", transport.camera_noise.read_variance);
      write_attribute(h5, "noise_variance_per_signal", transport.camera_noise.variance_per_signal);
    }
    const Shapes shapes(setup);
    write_dataset(h5, "indices", shapes.entries, transport.indices, deflate_level);
    write_dataset(h5, "weights", shapes.entries, transport.weights, deflate_level);
    write_dataset(h5, "correspondence", shapes.pairs, transport.correspondence, deflate_level);
    std::vector<std::uint32_t> decoded(2 * transport.camera_pixels());
    for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
      decoded[2 * c] = transport.pixel_x[c];
      decoded[2 * c + 1] = transport.pixel_y[c];
    }
    write_dataset(h5, "decoded", shapes.pairs, decoded, deflate_level);
    write_dataset(h5, "flags", shapes.pixels, transport.flags, deflate_level);
    write_dataset(h5, "direct_energy", shapes.pixels, transport.direct_energy, deflate_level);
    if (!transport.white.empty()) write_dataset(h5, "white", shapes.pixels, transport.white, deflate_level);
    h5.close();
    output.write(memory.bytes());
    output.commit();
  } catch (const H5::Exception& error) {
    throw OutputError("cannot write " + file.string() + ": HDF5: " + error.getDetailMsg());
  }
}

CompressedTransport read_transport(const fs::path& file) {
  H5::Exception::dontPrint();
  Reader reader(file);
  if (reader.string("format") != kFormat) reader.fail("not an rfrecon transport file (attribute 'format')");
  reader.read_version();
  TransportSetup setup;
  setup.camera_size = {reader.integer("camera_width", 1, kMaxTransportImageSide),
                       reader.integer("camera_height", 1, kMaxTransportImageSide)};
  setup.projector_size = {reader.integer("projector_width", 1, kMaxTransportImageSide),
                          reader.integer("projector_height", 1, kMaxTransportImageSide)};
  setup.entries_per_pixel = reader.integer("entries_per_pixel", 1, kMaxEntriesPerPixel);
  setup.dot_spacing = reader.integer("dot_spacing", 0, kMaxTransportImageSide);
  if (setup.dot_spacing == 1) reader.fail("attribute 'dot_spacing' is 1 (must be 0 or at least 2)");
  const std::int64_t entries = std::int64_t{setup.camera_size.area()} * setup.entries_per_pixel;
  if (entries > kMaxTransportEntries) {
    reader.fail("camera_width x camera_height x entries_per_pixel = " + std::to_string(entries) + " exceeds " +
                std::to_string(kMaxTransportEntries));
  }
  // indices and weights per entry; correspondence, decoded, flags, direct_energy, white and pixel_x/y per pixel
  const double transport_bytes = 8.0 * static_cast<double>(entries) + 33.0 * setup.camera_size.area();
  check_memory(transport_bytes, file.string() + ": its " + std::to_string(setup.camera_size.width) + "x" +
                                    std::to_string(setup.camera_size.height) + " camera pixels of " +
                                    std::to_string(setup.entries_per_pixel) + " entries");
  setup.thresholds.black = static_cast<float>(reader.finite("black_threshold"));
  setup.thresholds.white = static_cast<float>(reader.finite("white_threshold"));
  setup.thresholds.noise = static_cast<float>(reader.finite("noise_threshold"));

  CompressedTransport transport;
  transport.setup = setup;
  const std::string protocol = reader.string("protocol");
  // "gray", "gray+dots", or another family's name, with "+dots" for its dot grid.
  const std::string suffix = "+dots";
  const bool dots =
      protocol.size() > suffix.size() && protocol.compare(protocol.size() - suffix.size(), suffix.size(), suffix) == 0;
  const std::string family = dots ? protocol.substr(0, protocol.size() - suffix.size()) : protocol;
  if (family != "gray") transport.setup.family = family;
  if (family.empty() || protocol != transport.protocol()) {
    reader.fail("attribute 'protocol' is '" + excerpt(protocol) + "': with dot_spacing " +
                std::to_string(setup.dot_spacing) + " it is " +
                (setup.dot_spacing > 0 ? "'gray+dots' or a family's name and '+dots'" : "'gray' or a family's name"));
  }
  const Shapes shapes(setup);
  transport.indices = reader.dataset<std::int32_t>("indices", shapes.entries);
  transport.weights = reader.dataset<float>("weights", shapes.entries);
  transport.correspondence = reader.dataset<float>("correspondence", shapes.pairs);
  const auto decoded = reader.dataset<std::uint32_t>("decoded", shapes.pairs);
  transport.flags = reader.dataset<std::uint8_t>("flags", shapes.pixels);
  transport.direct_energy = reader.dataset<float>("direct_energy", shapes.pixels);
  if (reader.has("white")) transport.white = reader.dataset<float>("white", shapes.pixels);
  if (reader.has_attribute("noise_read_variance")) {
    transport.camera_noise.read_variance = reader.finite("noise_read_variance");
    transport.camera_noise.variance_per_signal = reader.finite("noise_variance_per_signal");
    if (!transport.camera_noise.known()) {
      reader.fail("attributes 'noise_read_variance' and 'noise_variance_per_signal' must be at least 0");
    }
  }
  reader.close();

  check_values(reader, transport, decoded, shapes);
  transport.pixel_x.resize(transport.camera_pixels());
  transport.pixel_y.resize(transport.camera_pixels());
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    transport.pixel_x[c] = decoded[2 * c];
    transport.pixel_y[c] = decoded[2 * c + 1];
  }
  return transport;
}

}  // namespace rfrecon::transport
