#include "airr/render/ray_file.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <thread>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/parallel_rows.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/tracer.hpp"
#include "tracer_path.hpp"

namespace airr {

static_assert(std::endian::native == std::endian::little, "the ray file is written as the machine holds it");

void add_to_record(ray_record& r, ray_path path, const std::vector<ray_segment>& segments,
                   std::uint64_t segment_limit) {
  ++r.selected;
  if (!r.complete || r.segments.size() + segments.size() > segment_limit) {
    r.complete = false;  // the paths kept stay a prefix of the selected ones
    return;
  }
  path.first_segment = std::uint32_t(r.segments.size());
  path.segment_count = std::uint32_t(segments.size());
  r.paths.push_back(path);
  r.segments.insert(r.segments.end(), segments.begin(), segments.end());
}

namespace {

int workers(int threads) { return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())); }

// What the pass holds at most: each row of a wave of rows its own record up to the limit, and the
// whole record.
std::uint64_t record_memory_need(const ray_file_params& p) {
  return std::uint64_t(workers(p.threads) + 1) * p.segment_limit * (sizeof(ray_segment) + sizeof(ray_path));
}

std::uint64_t file_bytes_at_most(const ray_file_params& p) {
  // Every path has a segment at least, so there are no more paths than segments.
  return ray_header_bytes + p.select.size() + p.segment_limit * (ray_path_bytes + ray_segment_bytes);
}

std::string megabytes(std::uint64_t bytes) { return number_text(double(bytes) / 1e6, 4) + " MB"; }

}  // namespace

void check_ray_file(const std::string& path, const scene& s, const ray_file_params& p) {
  if (p.segment_limit < 1 || p.segment_limit > max_ray_segments)
    throw input_error(path + ": the ray limit must be in [1, " + std::to_string(max_ray_segments) + "] segments (is " +
                      std::to_string(p.segment_limit) + ")");
  path_expression::parse(p.select).bound(s, true);  // throws, pointing at the character
  const std::string reason = reason_cannot_create(path);
  if (!reason.empty()) throw input_error(path + ": cannot write the ray file: " + reason);
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  const std::filesystem::space_info space = std::filesystem::space(dir, ec);
  const std::uint64_t need = file_bytes_at_most(p);
  if (!ec && need > space.available)
    throw input_error(path + ": " + std::to_string(p.segment_limit) + " segments may need " + megabytes(need) +
                      ", and the disk holding " + dir.string() + " has " + megabytes(space.available) +
                      " free; give a smaller limit");
  check_memory_need("ray file of " + std::to_string(p.segment_limit) + " segments", record_memory_need(p));
}

std::vector<ray_record> record_rays(const scene& s, const std::vector<std::string>& expressions,
                                    const ray_file_params& p, const std::function<bool(double)>& progress) {
  if (expressions.size() > std::size_t(max_path_layers))
    throw input_error("rays of at most " + std::to_string(max_path_layers) + " expressions in one pass");
  path_layers select;
  for (std::size_t k = 0; k < expressions.size(); ++k)
    select.layers.push_back({"rays" + std::to_string(k), path_expression::parse(expressions[k]).bound(s, true)});
  embree_device device;
  tracer_scene ts;
  ts.use_model_image = false;
  build_tracer_scene(ts, device, s);
  const std::size_t classes = expressions.size();
  std::vector<ray_record> all(classes);
  const auto any_complete = [&] {
    return std::any_of(all.begin(), all.end(), [](const ray_record& r) { return r.complete; });
  };
  const int height = ts.camera.height, wave = workers(p.threads);
  const std::atomic<bool> never{false};
  for (int y0 = 0; y0 < height && any_complete(); y0 += wave) {
    const int rows = std::min(wave, height - y0);
    std::vector<std::uint64_t> left(classes);
    for (std::size_t k = 0; k < classes; ++k) left[k] = all[k].complete ? p.segment_limit - all[k].segments.size() : 0;
    std::vector<std::vector<ray_record>> records(static_cast<std::size_t>(rows), std::vector<ray_record>(classes));
    detail::parallel_rows(rows, p.threads, [&](int a, int b) {
      for (int r = a; r < b; ++r) {
        std::vector<glm::vec3> radiance(select.count());
        layer_sink sink{select, radiance.data()};
        sink.records = records[std::size_t(r)];
        sink.segment_limits = left;
        std::uint64_t rays = 0;
        tracer_path::label_rows(ts, y0 + r, y0 + r + 1, p.first_sample, p.spp, sink, never, rays);
      }
    });
    for (const std::vector<ray_record>& row : records) {
      for (std::size_t k = 0; k < classes; ++k) {
        const ray_record& r = row[k];
        for (const ray_path& path : r.paths) {
          const auto from = r.segments.begin() + path.first_segment;
          add_to_record(all[k], path, std::vector<ray_segment>(from, from + path.segment_count), p.segment_limit);
        }
        // The paths a row counted beyond its own limit do not fit either.
        all[k].selected += r.selected - r.paths.size();
        if (!r.complete) all[k].complete = false;
      }
    }
    if (progress && !progress(double(y0 + rows) / height)) {
      for (ray_record& r : all) r.complete = false;
      break;
    }
  }
  return all;
}

ray_record record_rays(const scene& s, const ray_file_params& p, const std::function<bool(double)>& progress) {
  return std::move(record_rays(s, {p.select}, p, progress).front());
}

namespace {

template <class T>
void put(std::string& out, T v) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  out.append(bytes, sizeof(T));
}

void put(std::string& out, const glm::vec3& v) {
  for (int c = 0; c < 3; ++c) put(out, v[c]);
}

}  // namespace

void write_ray_file(const std::string& path, const scene& s, const ray_file_params& p, const ray_record& r) {
  std::string out;
  out.reserve(ray_header_bytes + p.select.size() + r.paths.size() * ray_path_bytes +
              r.segments.size() * ray_segment_bytes);
  out.append("AIRRRAYS", 8);
  put(out, std::uint32_t(1));  // version
  put(out, std::uint32_t(s.observer.width));
  put(out, std::uint32_t(s.observer.height));
  put(out, std::uint32_t(r.complete ? 1 : 0));  // flags
  put(out, std::uint64_t(p.first_sample));
  put(out, std::uint64_t(p.spp));
  put(out, std::uint64_t(r.selected));
  put(out, std::uint64_t(r.paths.size()));
  put(out, std::uint64_t(r.segments.size()));
  put(out, std::uint32_t(p.select.size()));
  out.append(p.select);
  for (const ray_path& q : r.paths) {
    put(out, q.x);
    put(out, q.y);
    put(out, q.sample);
    put(out, q.first_segment);
    put(out, q.segment_count);
    put(out, q.contribution);
    put(out, std::uint32_t(0));
  }
  for (const ray_segment& g : r.segments) {
    put(out, g.start);
    put(out, g.direction);
    put(out, g.length);
    put(out, g.radiance);
    put(out, std::uint8_t(g.event.kind));
    put(out, std::uint8_t(g.event.taken));
    put(out, std::uint8_t(g.event.front));
    put(out, std::uint8_t(0));
    put(out, g.event.index);
    put(out, std::uint16_t(0));
  }
  write_file_atomic(path, out);
}

}  // namespace airr
