// HDF5 reading and writing of the compressed light transport (H5Cpp).
#include "host/transport/transport_file.h"

#include <algorithm>
#include <string>
#include <vector>

#include <H5Cpp.h>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"

namespace rfrecon::transport {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "rfrecon-transport";

template <typename T>
const H5::PredType& h5_type();
template <>
const H5::PredType& h5_type<std::int32_t>() {
  return H5::PredType::NATIVE_INT32;
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

// Shape (height, width[, depth]) of a per-camera-pixel dataset.
std::vector<hsize_t> pixel_shape(const TransportSetup& setup, hsize_t depth) {
  std::vector<hsize_t> shape{static_cast<hsize_t>(setup.camera_size.height),
                             static_cast<hsize_t>(setup.camera_size.width)};
  if (depth > 0) shape.push_back(depth);
  return shape;
}

template <typename T>
void write_dataset(H5::H5File& file, const char* name, const std::vector<hsize_t>& shape, const std::vector<T>& data) {
  H5::DataSpace space(static_cast<int>(shape.size()), shape.data());
  H5::DSetCreatPropList properties;
  if (!data.empty()) {
    std::vector<hsize_t> chunk = shape;
    chunk[0] = std::min<hsize_t>(shape[0], 32);  // bands of rows: compresses well, reads row by row
    properties.setChunk(static_cast<int>(chunk.size()), chunk.data());
    properties.setDeflate(1);
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

// Reading, with every failure turned into an InputError naming the file and the object.
class Reader {
 public:
  explicit Reader(const fs::path& path) : path_(path) {
    if (!fs::is_regular_file(path)) fail("file not found");
    try {
      file_ = H5::H5File(path.string(), H5F_ACC_RDONLY);
    } catch (const H5::Exception&) {
      fail("not a readable HDF5 file (truncated or corrupt?)");
    }
  }

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_.string() + ": " + what); }

  template <typename T>
  T attribute(const char* name) {
    if (!file_.attrExists(name)) fail(std::string("missing attribute '") + name + "'");
    T value{};
    try {
      file_.openAttribute(name).read(h5_type<T>(), &value);
    } catch (const H5::Exception&) {
      fail(std::string("attribute '") + name + "' is unreadable or not numeric");
    }
    return value;
  }

  std::string string_attribute(const char* name) {
    if (!file_.attrExists(name)) fail(std::string("missing attribute '") + name + "'");
    try {
      H5::Attribute attribute = file_.openAttribute(name);
      std::string value;
      attribute.read(attribute.getStrType(), value);
      return value.substr(0, value.find('\0'));  // drop any NUL padding
    } catch (const H5::Exception&) {
      fail(std::string("attribute '") + name + "' is unreadable or not a string");
    }
  }

  template <typename T>
  std::vector<T> dataset(const char* name, const std::vector<hsize_t>& expected_shape) {
    if (!file_.nameExists(name)) fail(std::string("missing dataset '") + name + "'");
    try {
      H5::DataSet dataset = file_.openDataSet(name);
      const H5::DataSpace space = dataset.getSpace();
      std::vector<hsize_t> shape(static_cast<std::size_t>(space.getSimpleExtentNdims()));
      space.getSimpleExtentDims(shape.data());
      if (shape != expected_shape) {
        fail(std::string("dataset '") + name + "' has shape " + describe(shape) + ", the attributes require " +
             describe(expected_shape));
      }
      hsize_t count = 1;
      for (const hsize_t extent : shape) count *= extent;
      std::vector<T> data(count);
      dataset.read(data.data(), h5_type<T>());
      return data;
    } catch (const H5::Exception&) {
      fail(std::string("dataset '") + name + "' is unreadable (truncated or corrupt file?)");
    }
  }

 private:
  static std::string describe(const std::vector<hsize_t>& shape) {
    std::string text = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) text += (i > 0 ? ", " : "") + std::to_string(shape[i]);
    return text + ")";
  }

  fs::path path_;
  H5::H5File file_;
};

}  // namespace

void write_transport(const CompressedTransport& transport, const fs::path& file) {
  const TransportSetup& setup = transport.setup;
  AtomicFile output(file);
  try {
    H5::Exception::dontPrint();
    H5::H5File h5(output.temp_path().string(), H5F_ACC_TRUNC);
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
    const auto k = static_cast<hsize_t>(setup.entries_per_pixel);
    write_dataset(h5, "indices", pixel_shape(setup, k), transport.indices);
    write_dataset(h5, "weights", pixel_shape(setup, k), transport.weights);
    write_dataset(h5, "correspondence", pixel_shape(setup, 2), transport.correspondence);
    std::vector<std::uint32_t> decoded(2 * transport.camera_pixels());
    for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
      decoded[2 * c] = transport.gray_x[c];
      decoded[2 * c + 1] = transport.gray_y[c];
    }
    write_dataset(h5, "decoded", pixel_shape(setup, 2), decoded);
    write_dataset(h5, "flags", pixel_shape(setup, 0), transport.flags);
    write_dataset(h5, "direct_energy", pixel_shape(setup, 0), transport.direct_energy);
    h5.close();
  } catch (const H5::Exception& error) {
    throw InputError("cannot write " + file.string() + ": " + error.getDetailMsg());
  }
  output.commit();
}

CompressedTransport read_transport(const fs::path& file) {
  H5::Exception::dontPrint();
  Reader reader(file);
  if (reader.string_attribute("format") != kFormat) reader.fail("not an rfrecon transport file (attribute 'format')");
  const auto version = reader.attribute<std::int32_t>("format_version");
  if (version != kTransportFileVersion) {
    reader.fail("format_version " + std::to_string(version) + " is not supported (expected " +
                std::to_string(kTransportFileVersion) + ")");
  }
  TransportSetup setup;
  setup.camera_size = {reader.attribute<std::int32_t>("camera_width"), reader.attribute<std::int32_t>("camera_height")};
  setup.projector_size = {reader.attribute<std::int32_t>("projector_width"),
                          reader.attribute<std::int32_t>("projector_height")};
  setup.entries_per_pixel = reader.attribute<std::int32_t>("entries_per_pixel");
  setup.dot_spacing = reader.attribute<std::int32_t>("dot_spacing");
  setup.thresholds.black = static_cast<float>(reader.attribute<double>("black_threshold"));
  setup.thresholds.white = static_cast<float>(reader.attribute<double>("white_threshold"));
  setup.thresholds.noise = static_cast<float>(reader.attribute<double>("noise_threshold"));
  if (setup.camera_size.width < 1 || setup.camera_size.height < 1 || setup.projector_size.width < 1 ||
      setup.projector_size.height < 1 || setup.entries_per_pixel < 1 || setup.dot_spacing < 0) {
    reader.fail("sizes, entries_per_pixel or dot_spacing out of range");
  }

  CompressedTransport transport;
  transport.setup = setup;
  const auto k = static_cast<hsize_t>(setup.entries_per_pixel);
  transport.indices = reader.dataset<std::int32_t>("indices", pixel_shape(setup, k));
  transport.weights = reader.dataset<float>("weights", pixel_shape(setup, k));
  transport.correspondence = reader.dataset<float>("correspondence", pixel_shape(setup, 2));
  const auto decoded = reader.dataset<std::uint32_t>("decoded", pixel_shape(setup, 2));
  transport.flags = reader.dataset<std::uint8_t>("flags", pixel_shape(setup, 0));
  transport.direct_energy = reader.dataset<float>("direct_energy", pixel_shape(setup, 0));
  const auto projector_pixels = static_cast<std::int32_t>(transport.projector_pixels());
  if (std::any_of(transport.indices.begin(), transport.indices.end(),
                  [&](std::int32_t q) { return q < -1 || q >= projector_pixels; })) {
    reader.fail("dataset 'indices' holds values outside [-1, projector pixels)");
  }
  transport.gray_x.resize(transport.camera_pixels());
  transport.gray_y.resize(transport.camera_pixels());
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    transport.gray_x[c] = decoded[2 * c];
    transport.gray_y[c] = decoded[2 * c + 1];
  }
  return transport;
}

}  // namespace rfrecon::transport
