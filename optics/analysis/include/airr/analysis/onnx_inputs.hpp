#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace airr::analysis {

struct onnx_input {
  std::string name;
  // One entry per axis; -1 where the size is symbolic or not given.
  std::vector<std::int64_t> shape;
  bool shape_known = false;  // the model declares a tensor shape for this input
};

// Graph inputs of an ONNX model (weights stored as initializers are left out), read from the
// protobuf file directly. Throws std::runtime_error naming the file when it is missing or not an
// ONNX model.
std::vector<onnx_input> read_onnx_inputs(const std::filesystem::path& path);

}  // namespace airr::analysis
