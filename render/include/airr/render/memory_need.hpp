#pragma once
// What a render will hold in memory, estimated before it starts, against what this process may
// still take, so that a render too large for the machine (or for the process's limit) is refused
// with one line instead of failing half-way.
#include <cstdint>
#include <exception>
#include <string>

#include "airr/layout/scene.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

// What this process may still take: the smaller of what its address-space limit (ulimit -v)
// leaves and the machine's available memory and swap; `source` says which.
struct memory_allowance {
  std::uint64_t bytes = 0;
  std::string source;
};
memory_allowance process_memory_allowance();

// The peak a render of `s` with `p` holds (accumulators, their even/odd halves and components,
// the model image, the shown mix), from measured per-pixel costs (docs/architecture.md).
std::uint64_t render_memory_need(const scene& s, const session_params& p);
// The part of that the pixels hold: `pixels` traced with this many components held (0: none), by a
// session publishing images every wave or only at its target (session_params::final_images_only).
std::uint64_t traced_pixels_memory_need(std::uint64_t pixels, int components, bool final_images_only = false);

// Throws input_error "render: W x H ... needs about N GB of memory; this process may take M GB
// more (source)" when the need exceeds the allowance.
void check_render_memory(const scene& s, const session_params& p);

// What a measuring command (sweep, zone pass) holds before it measures, measured on the default
// scene.
inline constexpr std::uint64_t measuring_process_bytes = 150'000'000;

// What one model PSF of `samples` samples holds at its peak (its samples as they grow, and the
// sheets' shares), measured on the default scene (docs/architecture.md).
std::uint64_t psf_memory_need(std::uint64_t samples);

// Throws input_error "<what> needs about N GB of memory; this process may take M GB more
// (source)" when `need` bytes exceed the allowance.
void check_memory_need(const std::string& what, std::uint64_t need);

// One line for an allocation that failed after the checks let a job start: what ran out, and what
// the process may still take.
std::string out_of_memory_message(const std::string& what);

// What a failed job says: the out-of-memory line for a failed allocation, else the exception's text.
std::string failure_message(const std::exception& e, const std::string& what);

}  // namespace airr
