#pragma once
// A light path's label: the events it met, from the display to the eye (docs/path-expressions.md).
// The tracer, going backward, records them eye first; `at` reads them in the light's order.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

namespace airr {

// `ambient`: light from around the device (index: ambient_room, the room's uniform surround;
// ambient_sun; luminaire k: ambient_first_luminaire + k). `film`: the films on one face of a part,
// crossed together (index: films_on_display, films_on_half_mirror; sheet k's:
// films_on_first_sheet + k).
enum class path_event_kind : std::uint8_t { display, eye, half_mirror, sheet, prop, ambient, film };
inline constexpr std::uint16_t ambient_room = 0;
inline constexpr std::uint16_t ambient_sun = 1;
inline constexpr std::uint16_t ambient_first_luminaire = 2;
inline constexpr std::uint16_t films_on_display = 0;
inline constexpr std::uint16_t films_on_half_mirror = 1;
inline constexpr std::uint16_t films_on_first_sheet = 2;

// Trivially made (a label's unused room costs nothing); path_event{} is the display.
struct path_event {
  path_event() = default;
  constexpr path_event(path_event_kind kind, bool taken = false, bool front = false, std::uint16_t index = 0)
      : kind(kind), taken(taken), front(front), index(index) {}

  path_event_kind kind;
  // half_mirror: reflected (else transmitted); sheet: retroreflected (else sent back otherwise).
  bool taken;
  // half_mirror: the light arrived on the face its normal points to (else the back); film: the
  // films lie on that face.
  bool front;
  // half_mirror: the plate path's order (reflected: 0 the near face, k the far face after k - 1
  // round trips inside; transmitted: k round trips), 0 for a thin half mirror; sheet: its index
  // in the scene; prop: its index among the scene's props; ambient: which source; film: whose.
  std::uint16_t index;

  bool operator==(const path_event&) const = default;
};

// render.max_depth interactions at most (64), and the display and the eye; the films of the face
// the light arrived on and of the face it left by at each, and of the display's front.
inline constexpr int max_path_interactions = 64 + 2;
inline constexpr int max_path_events = 3 * 64 + 2 + 1;

struct path_label {
  std::array<path_event, max_path_events> events;  // in the order recorded: eye first; [0, count) set
  int count = 0;

  // Made, copied and assigned by the events it holds: paths split and copy their labels often.
  path_label() {}
  path_label(const path_label& o) : count(o.count) { std::copy_n(o.events.begin(), count, events.begin()); }
  path_label& operator=(const path_label& o) {
    count = o.count;
    std::copy_n(o.events.begin(), count, events.begin());
    return *this;
  }

  void push(const path_event& e) {
    if (count < max_path_events) events[std::size_t(count++)] = e;
  }
  // The i-th event the light met (0: where it started).
  const path_event& at(int i) const { return events[std::size_t(count - 1 - i)]; }
};

// Whether the path is a share of the aerial image: the display's light a sheet retroreflected on
// its way (ambient light a sheet returns is not).
inline bool aerial_image_path(const path_label& l) {
  if (l.count == 0 || l.at(0).kind != path_event_kind::display) return false;
  for (int i = 0; i < l.count; ++i) {
    const path_event& e = l.events[std::size_t(i)];
    if (e.kind == path_event_kind::sheet && e.taken) return true;
  }
  return false;
}

// An event as path expressions write it: D, E, H:r0:front, S1:retro, P3 ...
std::string event_text(const path_event& e);
// The whole label, events separated by spaces, e.g. "D H:r0:back S0:retro H:t0:front E".
std::string label_text(const path_label& l);

}  // namespace airr
