#pragma once
// airr bench --memory: the peak resident memory of `airr render` (1 spp) at two sizes, with and
// without the image's components, for this build and, side by side, another. The bytes a pixel
// costs are the rise in the peak from the smaller size to the larger over the pixels added, so
// that what does not grow with the image (the scene, the sheets' models, the libraries) is apart.
#include <string>

struct memory_bench_options {
  std::string scene_path;
  int size = 4096;      // the larger image's width and height; the smaller is half of it
  std::string compare;  // another build's airr; empty: this build only
  int threads = 0;
};

// Prints the table and the bytes per pixel; throws input_error naming the render that failed.
void run_memory_bench(const memory_bench_options& o);
