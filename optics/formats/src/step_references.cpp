#include "step_references.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace airr {

namespace {

// Where a string that opens at `open` ends, as Open CASCADE's reader (7.6) reads it: at the first
// quote followed by blanks and then ',' or ')' (a quote elsewhere, '' included, stays in the string;
// a string never closed runs to the end). Read any other way, the scan would skip what the reader
// takes as instances, or take what it skips.
std::size_t string_end(std::string_view text, std::size_t open) {
  const std::size_t n = text.size();
  for (std::size_t q = text.find('\'', open + 1); q != std::string_view::npos; q = text.find('\'', q + 1)) {
    std::size_t k = q + 1;
    while (k < n && (text[k] == ' ' || text[k] == '"' || text[k] == '\n' || text[k] == '\r')) ++k;
    if (k < n && (text[k] == ',' || text[k] == ')')) return q;
  }
  return std::string_view::npos;
}

// The blanks the reader allows between an instance's name and its '='.
bool blank(char c) { return c == ' ' || c == '\t'; }

// Whether an instance of these keywords crashes the reader's own checks when one of its lists is
// empty (the reader leaves the list unset): directions, edge loops, surface curves, polylines and
// the spline families (found by emptying each list of each kind a CAD file holds).
bool needs_members(const std::string& keywords) {
  static const char* const exact[] = {"DIRECTION",          "EDGE_LOOP", "SURFACE_CURVE", "SEAM_CURVE",
                                      "INTERSECTION_CURVE", "POLY_LOOP", "POLYLINE",      "BOUNDED_SURFACE_CURVE"};
  static const char* const prefixes[] = {"B_SPLINE_", "RATIONAL_B_SPLINE_", "BEZIER_",
                                         "UNIFORM_",  "QUASI_UNIFORM_",     "PIECEWISE_BEZIER_"};
  std::size_t at = 0;
  while (at < keywords.size()) {
    const std::size_t end = std::min(keywords.find(' ', at), keywords.size());
    const std::string_view word = std::string_view(keywords).substr(at, end - at);
    for (const char* e : exact)
      if (word == e) return true;
    for (const char* p : prefixes)
      if (word.substr(0, std::string_view(p).size()) == p) return true;
    at = end + 1;
  }
  return false;
}

// A loop of references, as "entity #12 refers back to #34, which refers to it": the reader
// follows references depth first and would go round for ever. Depth first here too, on a stack of
// our own (a file may nest millions deep).
std::string reference_loop(const std::vector<std::uint64_t>& ids,
                           const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  const std::size_t m = ids.size();
  std::vector<std::uint32_t> first(m + 1, 0), targets(edges.size());
  for (const auto& [from, to] : edges) ++first[from + 1];
  for (std::size_t i = 0; i < m; ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (const auto& [from, to] : edges) targets[fill[from]++] = to;
  enum : std::uint8_t { unseen, on_path, done };
  std::vector<std::uint8_t> state(m, unseen);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> path;  // (entity, its next reference)
  for (std::uint32_t root = 0; root < m; ++root) {
    if (state[root] != unseen) continue;
    state[root] = on_path;
    path.push_back({root, first[root]});
    while (!path.empty()) {
      const std::uint32_t u = path.back().first, e = path.back().second;
      if (e == first[u + 1]) {
        state[u] = done;
        path.pop_back();
        continue;
      }
      ++path.back().second;
      const std::uint32_t v = targets[e];
      if (state[v] == on_path)
        return "entity #" + std::to_string(ids[u]) + " refers back to #" + std::to_string(ids[v]) +
               ", which refers to it (its references go round in a loop)";
      if (state[v] == unseen) {
        state[v] = on_path;
        path.push_back({v, first[v]});
      }
    }
  }
  return {};
}

}  // namespace

std::string step_reference_fault(std::string_view text) {
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;  // id -> its place in `ids` and `types`
  std::vector<std::uint64_t> ids;
  std::vector<std::string> types;  // the keyword after '='; for a complex instance, all its keywords
  std::vector<bool> empty_list;    // whether a parameter of the instance is an empty list
  std::vector<std::pair<std::uint32_t, std::uint64_t>> references;  // (from's index, to's id) in file order
  bool inside = false, complex = false;                             // within the last instance defined
  char last = ' ';  // the last character read outside strings and comments that is not a blank
  const std::size_t n = text.size();
  const auto skip_blanks = [&](std::size_t k) {
    while (k < n && (blank(text[k]) || text[k] == '\n' || text[k] == '\r')) ++k;
    return k;
  };
  // The whole text, not the DATA section alone: the reader also takes instances it finds elsewhere.
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\'') {
      i = string_end(text, i);
      if (i == std::string_view::npos) break;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      const std::size_t end = text.find("*/", i + 2);
      if (end == std::string_view::npos) break;
      i = end + 1;
      continue;
    } else if (c == ';') {
      inside = false;
    } else if (c == '(' && inside && (last == '(' || last == ',')) {
      const std::size_t k = skip_blanks(i + 1);
      if (k < n && text[k] == ')') empty_list.back() = true;
    } else if (complex && (std::isalpha(static_cast<unsigned char>(c)) || c == '_')) {
      std::size_t j = i;
      while (j < n && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      types.back() += ' ';
      types.back().append(text.substr(i, j - i));
      i = j - 1;
    } else if (c == '#') {
      std::uint64_t id = 0;
      std::size_t j = i + 1;
      for (; j < n && std::isdigit(static_cast<unsigned char>(text[j])) && id < (std::uint64_t(1) << 60); ++j)
        id = id * 10 + std::uint64_t(text[j] - '0');
      std::size_t k = j;
      while (k < n && blank(text[k])) ++k;
      if (!inside && k < n && text[k] == '=') {
        if (ids.size() >= std::numeric_limits<std::uint32_t>::max()) return "more entities than a file may hold";
        if (!index_of.emplace(id, std::uint32_t(ids.size())).second)
          return "entity #" + std::to_string(id) + " is defined twice";
        ids.push_back(id);
        types.emplace_back();
        empty_list.push_back(false);
        inside = true;
        for (++k; k < n && std::isspace(static_cast<unsigned char>(text[k])); ++k) {
        }
        while (k < n && (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '_'))
          types.back() += text[k++];
        complex = types.back().empty();
        j = k;
      } else if (inside) {
        references.emplace_back(std::uint32_t(ids.size() - 1), id);
      }
      i = j - 1;
    }
    if (!blank(c) && c != '\n' && c != '\r') last = c;
    if (!inside) complex = false;
  }
  for (std::size_t e = 0; e < ids.size(); ++e) {
    if (empty_list[e] && needs_members(types[e]))
      return "entity #" + std::to_string(ids[e]) + ", " +
             (types[e].empty() || types[e].front() == ' ' ? std::string("a complex instance") : "a " + types[e]) +
             ", has an empty list where it needs members";
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(references.size());
  for (const auto& [from, to] : references) {
    const auto found = index_of.find(to);
    if (found == index_of.end()) {
      return "entity #" + std::to_string(ids[from]) + " refers to #" + std::to_string(to) +
             ", which the file does not define";
    }
    edges.emplace_back(from, found->second);
  }
  for (const auto& [from, to] : edges) {
    if (types[from] == "ORIENTED_EDGE" && types[to] == "ORIENTED_EDGE")
      return "entity #" + std::to_string(ids[from]) + ", an oriented edge, is built on the oriented edge #" +
             std::to_string(ids[to]) + " (STEP asks for an edge)";
  }
  return reference_loop(ids, edges);
}

}  // namespace airr
