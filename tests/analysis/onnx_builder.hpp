#pragma once
// Hand-encoded ONNX models (protobuf wire format) for testing the LPIPS plumbing without a
// downloaded network.
#include <cstdint>
#include <string>
#include <vector>

namespace airr::analysis::testing::onnx {

inline std::string varint(std::uint64_t v) {
  std::string out;
  do {
    unsigned char b = v & 0x7f;
    v >>= 7;
    if (v) b |= 0x80;
    out.push_back(static_cast<char>(b));
  } while (v);
  return out;
}

inline std::string int_field(int number, std::uint64_t v) { return varint(std::uint64_t(number) << 3) + varint(v); }

inline std::string bytes_field(int number, const std::string& payload) {
  return varint((std::uint64_t(number) << 3) | 2) + varint(payload.size()) + payload;
}

// ValueInfoProto of a float tensor; a dimension <= 0 is written as a symbolic size.
inline std::string tensor_info(const std::string& name, const std::vector<std::int64_t>& dims) {
  std::string shape;
  for (size_t i = 0; i < dims.size(); ++i)
    shape +=
        bytes_field(1, dims[i] > 0 ? int_field(1, std::uint64_t(dims[i])) : bytes_field(2, "d" + std::to_string(i)));
  const std::string tensor = int_field(1, 1) + bytes_field(2, shape);  // elem_type FLOAT
  return bytes_field(1, name) + bytes_field(2, bytes_field(1, tensor));
}

inline std::string node(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
                        const std::string& op_type) {
  std::string n;
  for (const auto& i : inputs) n += bytes_field(1, i);
  for (const auto& o : outputs) n += bytes_field(2, o);
  return n + bytes_field(3, op_type + "_" + outputs.front()) + bytes_field(4, op_type);
}

struct graph_spec {
  std::vector<std::string> nodes;
  std::vector<std::string> inputs;   // tensor_info
  std::vector<std::string> outputs;  // tensor_info
};

inline std::string model(const graph_spec& g, int opset = 13) {
  std::string graph;
  for (const auto& n : g.nodes) graph += bytes_field(1, n);
  graph += bytes_field(2, "test_graph");
  for (const auto& i : g.inputs) graph += bytes_field(11, i);
  for (const auto& o : g.outputs) graph += bytes_field(12, o);
  return int_field(1, 7) + bytes_field(2, "airr-test") + bytes_field(7, graph) +
         bytes_field(8, bytes_field(1, "") + int_field(2, std::uint64_t(opset)));
}

// Two N x 3 x H x W inputs; output: per-channel mean of the squared difference (1 x 3 x 1 x 1).
inline std::string squared_difference_model(std::int64_t h, std::int64_t w) {
  graph_spec g;
  g.inputs = {tensor_info("image_a", {1, 3, h, w}), tensor_info("image_b", {1, 3, h, w})};
  g.nodes = {node({"image_a", "image_b"}, {"diff"}, "Sub"), node({"diff", "diff"}, {"sq"}, "Mul"),
             node({"sq"}, {"distance"}, "GlobalAveragePool")};
  g.outputs = {tensor_info("distance", {1, 3, 1, 1})};
  return model(g);
}

}  // namespace airr::analysis::testing::onnx
