#include "airr/render/path_expression.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "airr/core/error.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

std::string event_text(const path_event& e) {
  switch (e.kind) {
    case path_event_kind::display:
      return "D";
    case path_event_kind::eye:
      return "E";
    case path_event_kind::half_mirror:
      return std::string("H:") + (e.taken ? "r" : "t") + std::to_string(e.index) + (e.front ? ":front" : ":back");
    case path_event_kind::sheet:
      return "S" + std::to_string(e.index) + (e.taken ? ":retro" : ":other");
    case path_event_kind::prop:
      return "P#" + std::to_string(e.index);
    case path_event_kind::ambient:
      if (e.index == ambient_room) return "A:room";
      if (e.index == ambient_sun) return "A:sun";
      return "A:luminaire" + std::to_string(e.index - ambient_first_luminaire);
    case path_event_kind::film: {
      const std::string whose = e.index == films_on_display ? "D"
                                : e.index == films_on_half_mirror
                                    ? "H"
                                    : "S" + std::to_string(e.index - films_on_first_sheet);
      return "F:" + whose + (e.front ? ":front" : ":back");
    }
  }
  return "?";
}

std::string label_text(const path_label& l) {
  std::string out;
  for (int i = 0; i < l.count; ++i) out += (i ? " " : "") + event_text(l.at(i));
  return out;
}

bool event_pattern::accepts(const path_event& e) const {
  return e.kind == kind && (taken < 0 || int(e.taken) == taken) && (front < 0 || int(e.front) == front) &&
         (index == -1 || int(e.index) == index || (index == any_luminaire && e.index >= ambient_first_luminaire) ||
          (index == any_sheets_films && e.index >= films_on_first_sheet));
}

// Recursive descent over the grammar of docs/path-expressions.md, building the Glushkov automaton:
// each sub-expression reports whether it can be empty and its first and last positions; sequences
// and repetitions link last positions to the first ones that may follow.
class path_expression_parser {
 public:
  explicit path_expression_parser(std::string_view text) : text_(text) { out_.text_ = std::string(text); }

  path_expression run() {
    skip_space();
    if (at_end()) fail("it is empty");
    const fragment f = alternation();
    if (!at_end()) fail(peek() == ')' ? "')' without '('" : "unexpected '" + std::string(1, peek()) + "'");
    out_.first_ = f.first;
    out_.last_ = f.last;
    out_.nullable_ = f.nullable;
    return std::move(out_);
  }

 private:
  using positions = path_expression::positions;
  struct fragment {
    bool nullable = true;
    positions first, last;
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw input_error("path expression '" + std::string(text_) + "': at character " + std::to_string(pos_ + 1) + ": " +
                      what);
  }
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  static bool ends_event(char c) {
    return c == '\0' || std::isspace(static_cast<unsigned char>(c)) ||
           std::string_view("()|*+?[]").find(c) != std::string_view::npos;
  }

  void link(const positions& from, const positions& to) {
    for (std::size_t p = 0; p < out_.positions_.size(); ++p)
      if (from.test(p)) out_.positions_[p].follow |= to;
  }

  fragment alternation() {
    fragment f = sequence();
    while (peek() == '|') {
      ++pos_;
      skip_space();
      const fragment g = sequence();
      f.nullable = f.nullable || g.nullable;
      f.first |= g.first;
      f.last |= g.last;
    }
    return f;
  }

  fragment sequence() {
    fragment f;  // the empty sequence
    bool any = false;
    while (!at_end() && peek() != '|' && peek() != ')') {
      const fragment g = repetition();
      if (f.nullable) f.first |= g.first;
      link(f.last, g.first);
      f.last = g.nullable ? (f.last | g.last) : g.last;
      f.nullable = f.nullable && g.nullable;
      any = true;
    }
    if (!any) fail("expected an event, '.', '(' or '['");
    return f;
  }

  fragment repetition() {
    fragment f = primary();
    skip_space();
    while (peek() == '*' || peek() == '+' || peek() == '?') {
      const char op = text_[pos_++];
      if (op != '?') link(f.last, f.first);
      if (op != '+') f.nullable = true;
      skip_space();
    }
    return f;
  }

  fragment primary() {
    const char c = peek();
    if (c == '(') {
      if (++depth_ > max_nesting) fail("groups nested more than " + std::to_string(max_nesting) + " deep");
      const std::size_t open = pos_++;
      skip_space();
      fragment f = alternation();
      --depth_;
      if (peek() != ')') {
        pos_ = open;
        fail("'(' is not closed");
      }
      ++pos_;
      return f;
    }
    path_expression::position p;
    if (c == '.') {
      ++pos_;
      p.negated = true;  // the complement of nothing: any event
    } else if (c == '[') {
      const std::size_t open = pos_++;
      if (peek() == '^') {
        p.negated = true;
        ++pos_;
      }
      skip_space();
      while (!at_end() && peek() != ']') {
        p.any_of.push_back(event());
        skip_space();
      }
      if (at_end()) {
        pos_ = open;
        fail("'[' is not closed");
      }
      if (p.any_of.empty()) fail("an empty set of events");
      ++pos_;
    } else {
      p.any_of.push_back(event());
    }
    if (out_.positions_.size() >= std::size_t(max_expression_events))
      fail("more than " + std::to_string(max_expression_events) + " events");
    out_.positions_.push_back(std::move(p));
    fragment f;
    f.nullable = false;
    f.first.set(out_.positions_.size() - 1);
    f.last = f.first;
    return f;
  }

  int number() {
    int n = 0;
    const std::size_t start = pos_;
    while (!at_end() && std::isdigit(static_cast<unsigned char>(peek()))) {
      if (pos_ - start >= 5) fail("a number too large");
      n = n * 10 + (text_[pos_++] - '0');
    }
    return n;
  }

  std::string word() {
    std::string w;
    if (peek() == '"') {
      const std::size_t open = pos_++;
      while (!at_end() && peek() != '"') w += text_[pos_++];
      if (at_end()) {
        pos_ = open;
        fail("'\"' is not closed");
      }
      ++pos_;
      return w;
    }
    while (!ends_event(peek()) && peek() != ':') w += text_[pos_++];
    return w;
  }

  event_pattern event() {
    event_pattern e;
    const std::size_t start = pos_;
    switch (peek()) {
      case 'D':
        e.kind = path_event_kind::display;
        break;
      case 'E':
        e.kind = path_event_kind::eye;
        break;
      case 'H':
        e.kind = path_event_kind::half_mirror;
        break;
      case 'S':
        e.kind = path_event_kind::sheet;
        break;
      case 'P':
        e.kind = path_event_kind::prop;
        break;
      case 'A':
        e.kind = path_event_kind::ambient;
        break;
      case 'F':
        e.kind = path_event_kind::film;
        out_.sees_films_ = true;
        break;
      default:
        fail("expected an event (D, E, H, S, P, A or F), '.', '(' or '['");
    }
    ++pos_;
    if (e.kind == path_event_kind::sheet && std::isdigit(static_cast<unsigned char>(peek()))) e.index = number();
    if (e.kind == path_event_kind::prop && peek() == '#') {
      ++pos_;
      if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a prop's number after '#'");
      e.index = number();
    }
    while (peek() == ':') {
      ++pos_;
      const std::size_t q = pos_;
      const std::string w = word();
      const auto bad = [&](const std::string& what) {
        pos_ = q;
        fail(what);
      };
      if (w.empty()) bad("expected a qualifier after ':'");
      if (e.kind == path_event_kind::half_mirror) {
        if (w == "front" || w == "back") {
          e.front = w == "front";
        } else if ((w[0] == 'r' || w[0] == 't') && w.find_first_not_of("0123456789", 1) == std::string::npos &&
                   w.size() <= 3) {
          e.taken = w[0] == 'r';
          if (w.size() > 1) e.index = std::stoi(w.substr(1));
        } else {
          bad("H takes r, t (with a plate order, e.g. r1), front or back, not '" + w + "'");
        }
      } else if (e.kind == path_event_kind::sheet) {
        if (w != "retro" && w != "other") bad("S takes retro or other, not '" + w + "'");
        e.taken = w == "retro";
      } else if (e.kind == path_event_kind::prop) {
        if (e.index != -1 || !e.prop_name.empty()) bad("a prop is named once");
        e.prop_name = w;
        e.index = -2;  // until bound to a scene's props
      } else if (e.kind == path_event_kind::ambient) {
        if (w == "room" || w == "sun") {
          e.index = w == "room" ? ambient_room : ambient_sun;
        } else if (w.starts_with("luminaire") && w.size() <= 12 &&
                   w.find_first_not_of("0123456789", 9) == std::string::npos) {
          e.index = w.size() == 9 ? event_pattern::any_luminaire : ambient_first_luminaire + std::stoi(w.substr(9));
        } else {
          bad("A takes room, sun, luminaire or luminaireK (e.g. luminaire0), not '" + w + "'");
        }
      } else if (e.kind == path_event_kind::film) {
        if (w == "front" || w == "back") {
          e.front = w == "front";
        } else if (e.index != -1) {
          bad("a film's part is named once");
        } else if (w == "D" || w == "H") {
          e.index = w == "D" ? films_on_display : films_on_half_mirror;
        } else if (w[0] == 'S' && w.size() <= 4 && w.find_first_not_of("0123456789", 1) == std::string::npos) {
          e.index = w.size() == 1 ? event_pattern::any_sheets_films : films_on_first_sheet + std::stoi(w.substr(1));
        } else {
          bad("F takes its part (D, H, S or a sheet, e.g. S0), front or back, not '" + w + "'");
        }
      } else {
        bad(std::string(e.kind == path_event_kind::display ? "D" : "E") + " takes no qualifier");
      }
    }
    if (!ends_event(peek())) {
      pos_ = start;
      fail("expected an event (D, E, H, S, P, A or F), '.', '(' or '[' followed by a space or an operator");
    }
    return e;
  }

  static constexpr int max_nesting = 32;
  std::string_view text_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  path_expression out_;
};

path_expression path_expression::parse(std::string_view text) { return path_expression_parser(text).run(); }

path_expression path_expression::bound(const scene& s, bool strict) const {
  path_expression out = *this;
  for (auto& p : out.positions_) {
    for (auto& e : p.any_of) {
      if (e.kind != path_event_kind::prop || e.prop_name.empty()) continue;
      e.index = -2;
      for (std::size_t i = 0; i < s.props.size(); ++i)
        if (s.props[i].name == e.prop_name) e.index = int(i);
      if (e.index == -2 && strict)
        throw input_error("path expression '" + text_ + "': the scene has no prop named '" + e.prop_name + "'");
    }
  }
  return out;
}

bool path_expression::matches(const path_label& l) const {
  positions current;
  bool started = false;
  for (int i = 0; i < l.count; ++i) {
    const path_event& e = l.at(i);
    if (e.kind == path_event_kind::film && !sees_films_) continue;
    positions reach = started ? positions() : first_;
    started = true;
    for (std::size_t p = 0; p < positions_.size(); ++p)
      if (current.test(p)) reach |= positions_[p].follow;
    positions next;
    for (std::size_t p = 0; p < positions_.size(); ++p) {
      if (!reach.test(p)) continue;
      bool any = false;
      for (const auto& pattern : positions_[p].any_of) any = any || pattern.accepts(e);
      if (any != positions_[p].negated) next.set(p);
    }
    if (next.none()) return false;
    current = next;
  }
  return started ? (current & last_).any() : nullable_;
}

std::uint64_t path_layers::select(const path_label& l) const {
  std::uint64_t mask = 0;
  for (std::size_t k = 0; k < layers.size(); ++k)
    if (layers[k].expression.matches(l)) mask |= std::uint64_t(1) << k;
  return mask ? mask : std::uint64_t(1) << layers.size();
}

path_layers path_layers::bound(const scene& s) const {
  path_layers out;
  for (const auto& l : layers) out.layers.push_back({l.name, l.expression.bound(s, false)});
  return out;
}

path_layers component_layers() {
  // tracer.hpp's image components: at least one retroreflection; no half-mirror reflection, prop
  // or sheet; one half-mirror reflection and nothing else; everything else; the room's, the sun's
  // and the luminaires' light.
  static const char* const expressions[] = {
      "D .* S:retro .* E", "D H:t* E",
      "D H:t* H:r H:t* E", "D [^S:retro]* (P | S:other) [^S:retro]* E | D H* H:r H* H:r H* E",
      "A:room .* E",       "A:sun .* E",
      "A:luminaire .* E",
  };
  path_layers out;
  for (int k = 0; k < component_count; ++k)
    out.layers.push_back({component_names[k], path_expression::parse(expressions[k])});
  return out;
}

path_layers parse_layer_arguments(const std::vector<std::string>& arguments, const scene& s,
                                  const std::vector<std::string>& taken) {
  path_layers out;
  std::set<std::string> names;
  for (const auto& a : arguments) {
    const std::size_t eq = a.find('=');
    if (eq == std::string::npos) throw input_error("--layer '" + a + "': expected NAME=EXPRESSION");
    const std::string name = a.substr(0, eq);
    if (name.empty() ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
      throw input_error("--layer '" + a + "': a layer's name is letters, digits, '_' and '-'");
    if (name == "unmatched") throw input_error("--layer '" + a + "': 'unmatched' names the paths no layer selects");
    if (std::find(taken.begin(), taken.end(), name) != taken.end())
      throw input_error("--layer '" + a + "': " + name + " names another of the render's outputs");
    if (!names.insert(name).second) throw input_error("--layer '" + a + "': the layer " + name + " is named twice");
    if (out.layers.size() >= std::size_t(max_path_layers))
      throw input_error("--layer: at most " + std::to_string(max_path_layers) + " layers");
    out.layers.push_back({name, path_expression::parse(a.substr(eq + 1)).bound(s, true)});
  }
  return out;
}

}  // namespace airr
