#include "airr/analysis/onnx_inputs.hpp"
#include "airr/core/error.hpp"

#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace airr::analysis {

namespace {

// Just enough of the protobuf wire format to walk an ONNX ModelProto.
struct malformed {
  size_t offset = 0;
};

struct field {
  std::uint32_t number = 0;
  int wire = 0;
  std::uint64_t varint = 0;
  std::string_view bytes;  // length-delimited payload
};

class wire_reader {
 public:
  wire_reader(std::string_view data, size_t base) : data_(data), base_(base) {}

  bool next(field& f) {
    if (pos_ >= data_.size()) return false;
    const std::uint64_t key = varint();
    f.number = static_cast<std::uint32_t>(key >> 3);
    f.wire = static_cast<int>(key & 7);
    if (f.number == 0) throw malformed{base_ + pos_};
    switch (f.wire) {
      case 0:
        f.varint = varint();
        break;
      case 1:
        skip(8);
        break;
      case 5:
        skip(4);
        break;
      case 2: {
        const std::uint64_t len = varint();
        if (len > data_.size() - pos_) throw malformed{base_ + pos_};
        f.bytes = data_.substr(pos_, static_cast<size_t>(len));
        f.varint = base_ + pos_;  // offset of the payload, for nested readers
        pos_ += static_cast<size_t>(len);
        break;
      }
      default:
        throw malformed{base_ + pos_};  // groups and reserved wire types
    }
    return true;
  }

 private:
  std::uint64_t varint() {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (pos_ >= data_.size()) throw malformed{base_ + pos_};
      const auto byte = static_cast<unsigned char>(data_[pos_++]);
      v |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if (!(byte & 0x80)) return v;
    }
    throw malformed{base_ + pos_};
  }
  void skip(size_t n) {
    if (n > data_.size() - pos_) throw malformed{base_ + pos_};
    pos_ += n;
  }

  std::string_view data_;
  size_t base_ = 0;
  size_t pos_ = 0;
};

wire_reader nested(const field& f) { return wire_reader(f.bytes, static_cast<size_t>(f.varint)); }

std::string tensor_name(const field& tensor) {
  std::string name;
  auto r = nested(tensor);
  for (field f; r.next(f);)
    if (f.number == 8 && f.wire == 2) name = std::string(f.bytes);
  return name;
}

onnx_input parse_value_info(const field& value_info) {
  onnx_input in;
  auto r = nested(value_info);
  for (field f; r.next(f);) {
    if (f.number == 1 && f.wire == 2) in.name = std::string(f.bytes);
    if (f.number != 2 || f.wire != 2) continue;
    auto type = nested(f);  // TypeProto
    for (field t; type.next(t);) {
      if (t.number != 1 || t.wire != 2) continue;
      auto tensor = nested(t);  // TypeProto.Tensor
      for (field s; tensor.next(s);) {
        if (s.number != 2 || s.wire != 2) continue;
        in.shape_known = true;
        in.shape.clear();
        auto shape = nested(s);  // TensorShapeProto
        for (field d; shape.next(d);) {
          if (d.number != 1 || d.wire != 2) continue;
          std::int64_t size = -1;
          auto dim = nested(d);
          for (field v; dim.next(v);)
            if (v.number == 1 && v.wire == 0) size = static_cast<std::int64_t>(v.varint);
          in.shape.push_back(size > 0 ? size : -1);
        }
      }
    }
  }
  return in;
}

}  // namespace

std::vector<onnx_input> read_onnx_inputs(const std::filesystem::path& path) {
  const std::string where = path.string() + ": ";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw input_error(where + (std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file"));
  std::ifstream file(path, std::ios::binary);
  if (!file) throw input_error(where + "cannot open file");
  const std::string data{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (data.empty()) throw input_error(where + "file is empty, not an ONNX model");

  std::vector<onnx_input> inputs;
  try {
    bool has_ir_version = false, has_graph = false;
    std::set<std::string> initializers;
    wire_reader model(data, 0);
    for (field f; model.next(f);) {
      if (f.number == 1 && f.wire == 0) has_ir_version = f.varint > 0;
      if (f.number != 7 || f.wire != 2) continue;
      has_graph = true;
      inputs.clear();
      auto graph = nested(f);
      for (field g; graph.next(g);) {
        if (g.wire != 2) continue;
        if (g.number == 5) initializers.insert(tensor_name(g));
        if (g.number == 15) {  // sparse initializer: its values tensor carries the name
          auto sparse = nested(g);
          for (field s; sparse.next(s);)
            if (s.number == 1 && s.wire == 2) initializers.insert(tensor_name(s));
        }
        if (g.number == 11) inputs.push_back(parse_value_info(g));
      }
    }
    if (!has_ir_version || !has_graph) throw input_error(where + "not an ONNX model (no IR version or graph)");
    std::erase_if(inputs, [&](const onnx_input& in) { return initializers.count(in.name) > 0; });
  } catch (const malformed& m) {
    throw input_error(where + "not an ONNX model (malformed protobuf at byte " + std::to_string(m.offset) + ")");
  }
  return inputs;
}

}  // namespace airr::analysis
