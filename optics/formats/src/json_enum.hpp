#pragma once
// An enumeration read from a JSON string by its names (private to the formats library).
#include <array>
#include <string>

#include "airr/core/json_reader.hpp"

namespace airr {

// Sets `out` to the enumerator whose name the key holds; absent keys leave it. An unknown name is
// an error that lists the names.
template <class Enum, std::size_t N>
void read_enum(json_reader& r, const std::string& key, Enum& out, const std::array<const char*, N>& names) {
  if (!r.has(key)) return;
  std::string v;
  r.string(key, v);
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (v == names[i]) {
      out = static_cast<Enum>(i);
      return;
    }
    list += (i ? ", " : "") + std::string(names[i]);
  }
  r.fail(r.field(key), "unknown value '" + v + "' (" + list + ")");
}

}  // namespace airr
