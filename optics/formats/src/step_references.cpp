#include "step_references.hpp"

#include <cctype>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace airr {

namespace {

struct instance {
  std::string type;                  // the keyword after '=' (empty for a complex instance)
  std::vector<std::uint64_t> names;  // the entities its parameters name
};

}  // namespace

std::string step_reference_fault(std::string_view text) {
  std::unordered_map<std::uint64_t, instance> defined;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> references;  // (from, to) in file order
  std::uint64_t current = 0;                                        // the instance being read, when `inside` is set
  const std::size_t n = text.size();
  instance* inside = nullptr;
  // The whole text, not the DATA section alone: the reader also takes instances it finds elsewhere.
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\'') {  // a string: '' stands for one quote
      for (++i; i < n; ++i) {
        if (text[i] != '\'') continue;
        if (i + 1 < n && text[i + 1] == '\'') {
          ++i;
          continue;
        }
        break;
      }
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      const std::size_t end = text.find("*/", i + 2);
      if (end == std::string_view::npos) break;
      i = end + 1;
    } else if (c == ';') {
      inside = nullptr;
    } else if (c == '#') {
      std::uint64_t id = 0;
      std::size_t j = i + 1;
      for (; j < n && std::isdigit(static_cast<unsigned char>(text[j])) && id < (std::uint64_t(1) << 60); ++j)
        id = id * 10 + std::uint64_t(text[j] - '0');
      std::size_t k = j;
      while (k < n && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      if (!inside && k < n && text[k] == '=') {
        if (defined.count(id)) return "entity #" + std::to_string(id) + " is defined twice";
        current = id;
        inside = &defined[id];
        for (++k; k < n && std::isspace(static_cast<unsigned char>(text[k])); ++k) {
        }
        while (k < n && (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '_'))
          inside->type += text[k++];
      } else if (inside) {
        inside->names.push_back(id);
        references.emplace_back(current, id);
      }
      i = j - 1;
    }
  }
  for (const auto& [from, to] : references) {
    if (!defined.count(to)) {
      return "entity #" + std::to_string(from) + " refers to #" + std::to_string(to) +
             ", which the file does not define";
    }
  }
  for (const auto& [id, inst] : defined) {
    if (inst.type != "ORIENTED_EDGE") continue;
    for (std::uint64_t to : inst.names) {
      if (defined.at(to).type == "ORIENTED_EDGE")
        return "entity #" + std::to_string(id) + ", an oriented edge, is built on the oriented edge #" +
               std::to_string(to) + " (STEP asks for an edge)";
    }
  }
  return {};
}

}  // namespace airr
