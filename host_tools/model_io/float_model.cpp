#include "host_tools/model_io/float_model.hpp"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/bounded_read.hpp"

namespace curio::model_io {
namespace {

// Dims beyond this are surely corruption (and would overflow the element count).
constexpr uint32_t kMaxDims = 8;
constexpr uint32_t kMaxNameLength = 4096;

std::string dims_text(const std::vector<int64_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) {
    if (i) s += ",";
    s += std::to_string(dims[i]);
  }
  return s + "]";
}

// Bounds-checked little-endian reader over the file's bytes.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& origin) : bytes_(bytes), origin_(origin) {}

  std::string_view take(size_t n, const char* what) {
    if (bytes_.size() - pos_ < n) {
      throw ModelFormatError(origin_ + ": truncated at byte " + std::to_string(pos_) +
                             " while reading " + what + " (need " + std::to_string(n) + " bytes, " +
                             std::to_string(bytes_.size() - pos_) + " left)");
    }
    std::string_view s = bytes_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  uint32_t u32(const char* what) {
    const auto s = take(4, what);
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<uint8_t>(s[static_cast<size_t>(i)]);
    return v;
  }
  int64_t i64(const char* what) {
    const auto s = take(8, what);
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<uint8_t>(s[static_cast<size_t>(i)]);
    return static_cast<int64_t>(v);
  }
  size_t pos() const { return pos_; }
  size_t left() const { return bytes_.size() - pos_; }

 private:
  std::string_view bytes_;
  const std::string& origin_;
  size_t pos_ = 0;
};

void put_u32(std::string* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
}
void put_i64(std::string* out, int64_t v) {
  const auto u = static_cast<uint64_t>(v);
  for (int i = 0; i < 8; ++i) out->push_back(static_cast<char>((u >> (8 * i)) & 0xFFu));
}

// Element count of dims, or -1 when a dim is negative or the product overflows.
int64_t checked_count(const std::vector<int64_t>& dims) {
  int64_t n = 1;
  for (int64_t d : dims) {
    if (d < 0) return -1;
    if (d != 0 && n > std::numeric_limits<int64_t>::max() / d) return -1;
    n *= d;
  }
  return n;
}

}  // namespace

int64_t FloatTensor::element_count() const {
  return checked_count(dims);
}

const FloatTensor* FloatModel::find(std::string_view name) const {
  for (const auto& t : tensors) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

const FloatTensor& FloatModel::require(std::string_view name,
                                       const std::vector<int64_t>& dims) const {
  const FloatTensor* t = find(name);
  if (!t) {
    throw ModelFormatError("missing tensor '" + std::string(name) + "' (expected shape " +
                           dims_text(dims) + ")");
  }
  if (t->dims != dims) {
    throw ModelFormatError("wrong shape for tensor '" + std::string(name) + "': file has " +
                           dims_text(t->dims) + ", expected " + dims_text(dims));
  }
  return *t;
}

FloatModel parse_float_model(std::string_view bytes, const std::string& origin) {
  static_assert(std::numeric_limits<float>::is_iec559, "float32 must be IEEE 754");
  Reader r(bytes, origin);
  const auto magic = r.take(sizeof kFloatModelMagic, "magic");
  if (std::memcmp(magic.data(), kFloatModelMagic, sizeof kFloatModelMagic) != 0) {
    throw ModelFormatError(origin + ": bad magic (not a CURIOFM1 float model file)");
  }
  const uint32_t count = r.u32("tensor count");
  // Each tensor takes at least 8 bytes (name length + ndim).
  if (count > r.left() / 8) {
    throw ModelFormatError(origin + ": tensor count " + std::to_string(count) +
                           " does not fit in the " + std::to_string(r.left()) +
                           " bytes that follow");
  }
  FloatModel model;
  model.tensors.reserve(count);
  std::set<std::string, std::less<>> seen;
  for (uint32_t i = 0; i < count; ++i) {
    FloatTensor t;
    const uint32_t name_len = r.u32("tensor name length");
    if (name_len == 0 || name_len > kMaxNameLength) {
      throw ModelFormatError(origin + ": tensor #" + std::to_string(i) +
                             " has an invalid name length " + std::to_string(name_len));
    }
    t.name = std::string(r.take(name_len, "tensor name"));
    if (!seen.insert(t.name).second) {
      throw ModelFormatError(origin + ": duplicate tensor '" + t.name + "'");
    }
    const uint32_t ndim = r.u32("ndim");
    if (ndim > kMaxDims) {
      throw ModelFormatError(origin + ": tensor '" + t.name + "' has ndim " + std::to_string(ndim) +
                             " (at most " + std::to_string(kMaxDims) + ")");
    }
    for (uint32_t d = 0; d < ndim; ++d) t.dims.push_back(r.i64("dims"));
    const int64_t n = checked_count(t.dims);
    if (n < 0 || static_cast<uint64_t>(n) > r.left() / 4) {
      throw ModelFormatError(origin + ": tensor '" + t.name + "' with shape " + dims_text(t.dims) +
                             " needs more data than the " + std::to_string(r.left()) +
                             " bytes left (truncated or corrupt)");
    }
    const auto raw = r.take(static_cast<size_t>(n) * 4, "tensor data");
    t.data.resize(static_cast<size_t>(n));
    for (size_t k = 0; k < t.data.size(); ++k) {
      uint32_t u = 0;
      for (int b = 3; b >= 0; --b)
        u = (u << 8) | static_cast<uint8_t>(raw[4 * k + static_cast<size_t>(b)]);
      t.data[k] = std::bit_cast<float>(u);
    }
    model.tensors.push_back(std::move(t));
  }
  if (r.left() != 0) {
    throw ModelFormatError(origin + ": " + std::to_string(r.left()) +
                           " unexpected bytes after the last tensor (corrupt file?)");
  }
  return model;
}

FloatModel read_float_model(const std::string& path) {
  std::string bytes, error;
  if (!host::read_file_bounded(path, host::kModelFileLimit, &bytes, &error, "float model file"))
    throw ModelFormatError(error);
  return parse_float_model(bytes, path);
}

std::string serialize_float_model(const std::vector<FloatTensor>& tensors) {
  std::string out(kFloatModelMagic, sizeof kFloatModelMagic);
  put_u32(&out, static_cast<uint32_t>(tensors.size()));
  std::set<std::string, std::less<>> seen;
  for (const auto& t : tensors) {
    if (t.name.empty() || t.name.size() > kMaxNameLength) {
      throw ModelFormatError("write_float_model: invalid tensor name '" + t.name + "'");
    }
    if (!seen.insert(t.name).second) {
      throw ModelFormatError("write_float_model: duplicate tensor '" + t.name + "'");
    }
    if (t.dims.size() > kMaxDims) {
      throw ModelFormatError("write_float_model: tensor '" + t.name + "' has too many dims");
    }
    const int64_t n = checked_count(t.dims);
    if (n < 0 || static_cast<uint64_t>(n) != t.data.size()) {
      throw ModelFormatError("write_float_model: tensor '" + t.name + "' has shape " +
                             dims_text(t.dims) + " but " + std::to_string(t.data.size()) +
                             " values");
    }
    put_u32(&out, static_cast<uint32_t>(t.name.size()));
    out += t.name;
    put_u32(&out, static_cast<uint32_t>(t.dims.size()));
    for (int64_t d : t.dims) put_i64(&out, d);
    for (float v : t.data) put_u32(&out, std::bit_cast<uint32_t>(v));
  }
  return out;
}

void write_float_model(const std::string& path, const std::vector<FloatTensor>& tensors) {
  const std::string bytes = serialize_float_model(tensors);
  // Temp + fsync + rename: a kill leaves the old model or the new one, never half of one.
  std::string error;
  if (!host::write_file_atomically(path, bytes, &error))
    throw ModelFormatError("cannot write the float model: " + error);
}

}  // namespace curio::model_io
