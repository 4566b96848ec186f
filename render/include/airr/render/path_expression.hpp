#pragma once
// Path expressions: a small regular grammar over path labels that selects light paths into image
// layers (docs/path-expressions.md), e.g. "D H:r S0:retro H:t E" for the aerial image through
// sheet 0.
#include <bitset>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "airr/layout/scene.hpp"
#include "airr/render/path_label.hpp"

namespace airr {

// What one event of an expression accepts; -1 (or empty) leaves a property free.
struct event_pattern {
  path_event_kind kind = path_event_kind::display;
  int taken = -1;  // H: r 1, t 0; S: retro 1, other 0
  int front = -1;
  // H: the plate order; S: the sheet; P: the prop (from its name when bound); A: the source
  // (any_luminaire: every luminaire); F: whose films (any_sheets_films: any sheet's).
  int index = -1;
  std::string prop_name;  // P:name, resolved to `index` by bind

  static constexpr int any_luminaire = -3;
  static constexpr int any_sheets_films = -4;
  bool accepts(const path_event& e) const;
};

// The most events an expression may write.
inline constexpr int max_expression_events = 128;

class path_expression {
 public:
  // Throws input_error "path expression 'TEXT': at character N: WHAT" when it does not parse.
  static path_expression parse(std::string_view text);
  // Prop names resolved against the scene's props; a name no prop has throws input_error when
  // `strict`, else matches nothing.
  path_expression bound(const scene& s, bool strict) const;

  // Whether the whole label, display to eye, is one the expression describes. An expression that
  // names no film (F) reads labels without their film events.
  bool matches(const path_label& l) const;
  const std::string& text() const { return text_; }

 private:
  using positions = std::bitset<max_expression_events>;
  // One position per event written (Glushkov's construction): what it accepts, whether it is a
  // set ([...]) or its complement ([^...], and '.'), and the positions that may follow it.
  struct position {
    std::vector<event_pattern> any_of;
    bool negated = false;
    positions follow;
  };
  friend class path_expression_parser;
  std::string text_;
  std::vector<position> positions_;
  positions first_, last_;
  bool nullable_ = false;
  bool sees_films_ = false;
};

// Named expressions whose images a render keeps as layers, and the paths none of them selects as
// one more layer, "unmatched".
struct path_layer {
  std::string name;
  path_expression expression;
};
struct path_layers {
  std::vector<path_layer> layers;
  // The layers whose expressions select `l` (bit k for layer k, bit layers.size() when none does).
  std::uint64_t select(const path_label& l) const;
  std::size_t count() const { return layers.size() + 1; }  // with the unmatched layer
  std::string name(std::size_t k) const { return k < layers.size() ? layers[k].name : "unmatched"; }
  // The same layers with their prop names resolved against `s` (a name no prop has matches nothing).
  path_layers bound(const scene& s) const;
};
inline constexpr int max_path_layers = 63;

// The four image components (tracer.hpp's image_component) as path expressions, in that order.
path_layers component_layers();

// Layers from "NAME=EXPR" arguments bound to the scene: a bad expression, an empty, repeated or
// reserved name, a name in `taken` (the render's other outputs: its components, Stokes images),
// an unknown prop or too many layers throw input_error naming the argument.
path_layers parse_layer_arguments(const std::vector<std::string>& arguments, const scene& s,
                                  const std::vector<std::string>& taken = {});

}  // namespace airr
