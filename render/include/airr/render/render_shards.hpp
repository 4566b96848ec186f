#pragma once
// A render split across processes (Slurm array tasks, cluster nodes): shard i of N traces rows
// [i h / N, (i + 1) h / N) and writes them, with the render's metadata and their place, to an EXR;
// merge_render_shards puts the shards together into the image one process would have written,
// and refuses shards that are missing, repeated, or of another render.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "airr/formats/image.hpp"

namespace airr {

struct shard_index {
  int index = 0;
  int count = 1;
};

// Parses "i/N" (0 <= i < N); throws input_error "<what>: ...".
shard_index parse_shard(const std::string& text, const std::string& what);

// The rows [first, end) shard s holds of an image `height` rows high.
std::pair<int, int> shard_rows(const shard_index& s, int height);

// Which file holds each shard, as a merge takes them in: a shard given twice is refused naming
// both files, and a missing one naming the files given.
class shard_roll {
 public:
  // Throws input_error "<path>: shard i/N again (<other> holds it too)".
  void add(const std::string& path, const shard_index& s);
  // Throws input_error "merge: shard i/N is missing; given <files>" unless all `count` were added.
  void check_complete(int count) const;

 private:
  std::map<int, std::string> held_;
};

// A render's pixels, its layers (the image's components) and its metadata.
struct render_image {
  image_rgb rgb;
  std::vector<std::pair<std::string, image_rgb>> layers;
  image_metadata meta;
};

// Writes shard s's rows of a whole-size render to `path` (EXR), marked with their place and the
// program's `version` (shards of different builds are not merged). Throws input_error.
void write_render_shard(const std::string& path, const render_image& whole, const shard_index& s,
                        const std::string& version);

// A shard as its header tells: its place, the whole image's height, its own pixels' size, the
// render's metadata (without the shard's own keys) and its layers' names.
struct render_shard_header {
  shard_index place;
  int height = 0;
  int width = 0, rows = 0;
  image_metadata meta;
  std::vector<std::string> layers;
};

// Checks what a shard file holds: its shard keys, the whole image's height (within the render's
// size limits), and that its `rows` are its place's. Throws input_error "<path>: <key>: <problem>".
render_shard_header check_shard_header(const std::string& path, image_metadata meta, int width, int rows,
                                       std::vector<std::string> layers);

// Why shard b is not of the render shard a is of (empty when it is).
std::string shard_mismatch(const render_shard_header& a, const render_shard_header& b);

// The whole render from its shards (paths in any order), with the metadata one process would
// have written. Throws input_error "<file>: <problem>" for a file that is no shard, a shard of
// another render (another scene, seed, samples, size, layers or version) or one given twice, and
// names a missing shard and the files given.
render_image merge_render_shards(const std::vector<std::string>& paths);

}  // namespace airr
