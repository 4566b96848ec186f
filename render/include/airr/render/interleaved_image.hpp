#pragma once
// A render's components and layers are kept interleaved: per pixel, `count` RGB triples one after
// the other. One of them as an image of its own.
#include <algorithm>
#include <cstddef>

#include "airr/formats/image.hpp"

namespace airr {

// The k-th of the `count` RGB triples of each of width x height pixels.
template <class T>
image_rgb interleaved_image(const T* data, int width, int height, std::size_t count, std::size_t k) {
  image_rgb img;
  img.width = width;
  img.height = height;
  img.rgb.resize(std::size_t(width) * height * 3);
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
    const T* v = data + 3 * (count * i + k);
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = float(v[c]);
  }
  return img;
}

}  // namespace airr
