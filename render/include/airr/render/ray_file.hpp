#pragma once
// The ray file: the traced paths a path expression selects, segment by segment in the light's
// order, for users who post-process elsewhere (format: docs/ray-file.md; reader: airr.read_rays).
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/layout/scene.hpp"
#include "airr/render/path_label.hpp"

namespace airr {

// One straight piece of a path, as the light travels it: from `start` along `direction` for
// `length` mm, carrying `radiance` (relative to the display's, as renders), having left the event
// `event` at `start` (the first piece leaves the display; the last ends at the eye).
struct ray_segment {
  glm::vec3 start{0.0f};
  glm::vec3 direction{0.0f};
  float length = 0;
  glm::vec3 radiance{0.0f};
  path_event event{};
};

// A path of pixel (x, y)'s sample `sample`: its segments [first_segment, first_segment +
// segment_count) of the record, and what it brought the pixel (the radiance reaching the eye).
struct ray_path {
  std::uint32_t x = 0, y = 0;
  std::uint64_t sample = 0;
  std::uint32_t first_segment = 0, segment_count = 0;
  glm::vec3 contribution{0.0f};
};

struct ray_record {
  std::vector<ray_path> paths;
  std::vector<ray_segment> segments;
  std::uint64_t selected = 0;  // paths the expression selected, recorded or not
  bool complete = true;        // every selected path is recorded
};

// Keeps `path` (light order) in `r` if its segments fit within `segment_limit`; counts it anyway.
void add_to_record(ray_record& r, ray_path path, const std::vector<ray_segment>& segments, std::uint64_t segment_limit);

struct ray_file_params {
  std::string select = ".*";  // a path expression (docs/path-expressions.md)
  std::uint64_t segment_limit = 1'000'000;
  std::uint64_t first_sample = 0, spp = 64;
  int threads = 0;
};

// The most segments a file may be asked to hold.
inline constexpr std::uint64_t max_ray_segments = std::uint64_t(1) << 32;
// Bytes of a file header (without the expression), a path record and a segment record.
inline constexpr std::uint64_t ray_header_bytes = 68, ray_path_bytes = 40, ray_segment_bytes = 48;

// Throws input_error naming `path` when p's expression does not parse (pointing at the character)
// or its limit is out of range, or when a file of p.segment_limit segments might not fit the free
// space of the disk `path` is on; nothing is written.
void check_ray_file(const std::string& path, const scene& s, const ray_file_params& p);

// Traces samples [p.first_sample, p.first_sample + p.spp) of every pixel of the observer's image
// (the same paths a render with the same scene and seed traces, without the control variate) and
// keeps the paths p.select selects, in row, pixel and sample order, until p.segment_limit segments
// are kept. `progress` gets the fraction of rows done and may stop the pass (returns false: the
// record is left incomplete).
ray_record record_rays(const scene& s, const ray_file_params& p, const std::function<bool(double)>& progress = {});
// The same pass keeping the paths of each of `expressions` in a record of its own (p.select
// unused), each up to p.segment_limit segments, as record_rays would one by one; a record's
// `selected` counts the rows the pass traced, which goes on while a record has room.
std::vector<ray_record> record_rays(const scene& s, const std::vector<std::string>& expressions,
                                    const ray_file_params& p, const std::function<bool(double)>& progress = {});

// Writes the record atomically; throws input_error naming the file and the system's reason.
void write_ray_file(const std::string& path, const scene& s, const ray_file_params& p, const ray_record& r);

}  // namespace airr
