#include "airr/render/render_shards.hpp"

#include <charconv>
#include <map>
#include <optional>

#include "airr/core/error.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

namespace {

constexpr const char* shard_key = "airr:shard";
constexpr const char* rows_key = "airr:rows";
constexpr const char* height_key = "airr:height";
constexpr const char* version_key = "airr:version";

std::optional<int> whole_number(const std::string& text) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

struct read_shard {
  std::string path;
  render_shard_header header;
  render_image image;
};

read_shard read_one(const std::string& path) {
  read_shard s;
  s.path = path;
  image_metadata meta = read_image_metadata(path);
  if (!meta.count(shard_key))
    throw input_error(path + ": not a render shard (no " + shard_key + "; shards are written by airr render --shard)");
  s.image.rgb = load_image(path, image_encoding::linear).pixels;
  s.image.layers = load_image_layers(path);
  std::vector<std::string> names;
  for (const auto& [name, layer] : s.image.layers) {
    if (layer.width != s.image.rgb.width || layer.height != s.image.rgb.height)
      throw input_error(path + ": layer " + name + " is " + std::to_string(layer.width) + " x " +
                        std::to_string(layer.height) + ", not the image's " + std::to_string(s.image.rgb.width) +
                        " x " + std::to_string(s.image.rgb.height));
    names.push_back(name);
  }
  s.header = check_shard_header(path, std::move(meta), s.image.rgb.width, s.image.rgb.height, std::move(names));
  s.image.meta = s.header.meta;
  return s;
}

}  // namespace

render_shard_header check_shard_header(const std::string& path, image_metadata meta, int width, int rows,
                                       std::vector<std::string> layers) {
  render_shard_header h;
  auto take = [&](const char* key) {
    const auto it = meta.find(key);
    if (it == meta.end())
      throw input_error(path + ": not a render shard (no " + key + "; shards are written by airr render --shard)");
    std::string v = it->second;
    meta.erase(it);
    return v;
  };
  h.place = parse_shard(take(shard_key), path + ": " + shard_key);
  const std::string row_text = take(rows_key);
  const std::string height_text = take(height_key);
  const auto height = whole_number(height_text);
  if (!height || *height < 1 || *height > max_resolution_side)
    throw input_error(path + ": " + height_key + ": '" + height_text + "' is not an image height of 1 to " +
                      std::to_string(max_resolution_side));
  if (h.place.count > *height)
    throw input_error(path + ": " + shard_key + ": " + std::to_string(h.place.count) + " shards of an image " +
                      std::to_string(*height) + " rows high");
  if (width < 1 || width > max_resolution_side)
    throw input_error(path + ": the render, " + std::to_string(width) + " x " + std::to_string(*height) +
                      ", is beyond the render's limits (" + std::to_string(max_resolution_side) + " a side)");
  h.height = *height;
  const auto [first, end] = shard_rows(h.place, h.height);
  if (row_text != std::to_string(first) + " " + std::to_string(end))
    throw input_error(path + ": " + rows_key + ": '" + row_text + "' are not shard " + std::to_string(h.place.index) +
                      "/" + std::to_string(h.place.count) + "'s rows of " + std::to_string(h.height));
  if (rows != end - first)
    throw input_error(path + ": holds " + std::to_string(rows) + " rows, not its shard's " +
                      std::to_string(end - first));
  h.width = width;
  h.rows = rows;
  h.meta = std::move(meta);
  h.layers = std::move(layers);
  return h;
}

std::string shard_mismatch(const render_shard_header& a, const render_shard_header& b) {
  if (a.place.count != b.place.count)
    return "split into " + std::to_string(b.place.count) + " shards, not " + std::to_string(a.place.count);
  if (a.height != b.height || a.width != b.width) return "an image of another size";
  // The likeliest differences first, each said in its own words.
  const std::pair<const char*, const char*> named[] = {{version_key, "written by another build"},
                                                       {"airr:seed", "another seed"},
                                                       {"airr:spp", "another number of samples"},
                                                       {"airr:layout", "another scene"}};
  auto value_of = [](const render_shard_header& s, const std::string& key) {
    const auto it = s.meta.find(key);
    return it == s.meta.end() ? std::optional<std::string>() : it->second;
  };
  for (const auto& [key, what] : named) {
    if (value_of(a, key) != value_of(b, key)) return std::string(what) + " (" + key + " differs)";
  }
  for (const auto& [key, value] : a.meta) {
    if (value_of(b, key) != value) return "another render (" + key + " differs)";
  }
  if (a.meta.size() != b.meta.size()) return "another render (its metadata differs)";
  if (a.layers != b.layers) return "a render with other layers";
  return "";
}

shard_index parse_shard(const std::string& text, const std::string& what) {
  const auto slash = text.find('/');
  const auto i = whole_number(text.substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : whole_number(text.substr(slash + 1));
  if (!i || !n || *n < 1 || *i < 0 || *i >= *n)
    throw input_error(what + ": '" + text + "' is not a shard i/N with 0 <= i < N");
  return {*i, *n};
}

std::pair<int, int> shard_rows(const shard_index& s, int height) {
  const auto at = [&](int i) { return int(std::int64_t(i) * height / s.count); };
  return {at(s.index), at(s.index + 1)};
}

void write_render_shard(const std::string& path, const render_image& whole, const shard_index& s,
                        const std::string& version) {
  if (s.count > whole.rgb.height)
    throw input_error(path + ": " + std::to_string(s.count) + " shards of an image " +
                      std::to_string(whole.rgb.height) + " rows high (at most one shard per row)");
  const auto [first, end] = shard_rows(s, whole.rgb.height);
  image_metadata meta = whole.meta;
  meta[shard_key] = std::to_string(s.index) + "/" + std::to_string(s.count);
  meta[rows_key] = std::to_string(first) + " " + std::to_string(end);
  meta[height_key] = std::to_string(whole.rgb.height);
  meta[version_key] = version;
  std::vector<image_rgb> layer_rows;
  for (const auto& l : whole.layers) layer_rows.push_back(image_rows(l.second, first, end));
  std::vector<image_layer> layers;
  for (std::size_t k = 0; k < layer_rows.size(); ++k) layers.push_back({whole.layers[k].first, &layer_rows[k]});
  write_image(path, image_rows(whole.rgb, first, end), meta, 1.0f, layers);
}

void shard_roll::add(const std::string& path, const shard_index& s) {
  if (const auto it = held_.find(s.index); it != held_.end())
    throw input_error(path + ": shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + " again (" +
                      it->second + " holds it too)");
  held_[s.index] = path;
}

void shard_roll::check_complete(int count) const {
  for (int i = 0; i < count; ++i) {
    if (held_.count(i)) continue;
    std::string given;
    for (const auto& [k, p] : held_) given += (given.empty() ? "" : ", ") + p + " (" + std::to_string(k) + ")";
    throw input_error("merge: shard " + std::to_string(i) + "/" + std::to_string(count) + " is missing; given " +
                      given);
  }
}

render_image merge_render_shards(const std::vector<std::string>& paths) {
  if (paths.empty()) throw input_error("merge: no shards given");
  std::vector<read_shard> shards;
  shard_roll roll;
  for (const std::string& p : paths) {
    read_shard s = read_one(p);
    if (!shards.empty()) {
      if (const std::string why = shard_mismatch(shards.front().header, s.header); !why.empty())
        throw input_error(p + ": not a shard of the render " + shards.front().path + " is a shard of: " + why);
    }
    roll.add(p, s.header.place);
    shards.push_back(std::move(s));
  }
  roll.check_complete(shards.front().header.place.count);
  const read_shard& first = shards.front();
  render_image out;
  out.meta = first.image.meta;
  out.meta.erase(version_key);
  auto blank = [&] {
    image_rgb img;
    img.width = first.image.rgb.width;
    img.height = first.header.height;
    img.rgb.assign(std::size_t(3) * img.width * img.height, 0.0f);
    return img;
  };
  out.rgb = blank();
  for (const auto& l : first.image.layers) out.layers.emplace_back(l.first, blank());
  for (const read_shard& s : shards) {
    const std::size_t at =
        std::size_t(3) * out.rgb.width * std::size_t(shard_rows(s.header.place, s.header.height).first);
    std::copy(s.image.rgb.rgb.begin(), s.image.rgb.rgb.end(), out.rgb.rgb.begin() + std::ptrdiff_t(at));
    for (std::size_t k = 0; k < s.image.layers.size(); ++k)
      std::copy(s.image.layers[k].second.rgb.begin(), s.image.layers[k].second.rgb.end(),
                out.layers[k].second.rgb.begin() + std::ptrdiff_t(at));
  }
  return out;
}

}  // namespace airr
