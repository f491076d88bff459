// The float model file the trainer exports and the quantizer reads ("CURIOFM1").
//
// Layout, all integers and floats little-endian:
//   char     magic[8] = "CURIOFM1"           (no terminating NUL)
//   uint32   tensor_count
//   tensor_count × {
//     uint32 name_length, char name[name_length]   (UTF-8, no NUL)
//     uint32 ndim,        int64 dims[ndim]           (each ≥ 0)
//     float32 data[prod(dims)]                       (row-major, PyTorch layout)
//   }
// and nothing after the last tensor. Names and shapes of the encoder tensors are in
// encoder_spec.hpp; decoder tensors ("dec.*") may follow and are carried as-is.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace curio::model_io {

inline constexpr char kFloatModelMagic[8] = {'C', 'U', 'R', 'I', 'O', 'F', 'M', '1'};

// One named tensor: dims as PyTorch reports them, data row-major (size = product of dims).
struct FloatTensor {
  std::string name;
  std::vector<int64_t> dims;
  std::vector<float> data;

  int64_t element_count() const;  // product of dims (1 for a scalar)
};

struct FloatModel {
  std::vector<FloatTensor> tensors;

  // nullptr when absent.
  const FloatTensor* find(std::string_view name) const;
  // The tensor with this name and exactly these dims; throws ModelFormatError
  // ("missing tensor" / "wrong shape") otherwise.
  const FloatTensor& require(std::string_view name, const std::vector<int64_t>& dims) const;
};

// Thrown for anything wrong with a model file or its contents; what() names the file,
// the tensor and what was expected.
class ModelFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads a whole CURIOFM1 file. Throws ModelFormatError on a missing file, bad magic,
// truncation, sizes that do not add up, duplicate names or trailing bytes.
FloatModel read_float_model(const std::string& path);

// Parses CURIOFM1 bytes already in memory (what read_float_model does after reading);
// `origin` only labels error messages.
FloatModel parse_float_model(std::string_view bytes, const std::string& origin);

// Writes tensors in the given order. Throws ModelFormatError if a tensor's data size
// does not match its dims, a name is empty or duplicated, or the file cannot be written.
// Usage (trainer): write_float_model("m.cfm", {{"enc.conv0.weight", {32,3,4,4}, w}, ...});
void write_float_model(const std::string& path, const std::vector<FloatTensor>& tensors);

// The bytes write_float_model would write.
std::string serialize_float_model(const std::vector<FloatTensor>& tensors);

}  // namespace curio::model_io
