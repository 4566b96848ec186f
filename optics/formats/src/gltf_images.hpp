#pragma once
// Images in glTF files (private to the formats library): the bytes a layout embeds, and the files
// the one image loader (image.hpp) reads a glTF's images from.
//
// An image stored inside a glTF (in a buffer view, as a GLB's are, or as a data URI) is extracted
// once into the cache, <XDG cache>/airr-studio/embedded/ (default ~/.cache/airr-studio/embedded/),
// as a file named by its content's hash and size (e.g. 3f2a...-48213.png), written atomically; a
// file already there with the same bytes is reused. An image the glTF names by URI is that file,
// relative to the glTF's folder.
#include <functional>
#include <string>

#include "gltf_read.hpp"

namespace airr::gltf {

// The folder embedded images are extracted into (created).
std::string embedded_image_dir();

// The image texture `texture` shows. Throws input_error "<file>: <what>: texture N ..." when the
// texture or its image does not exist.
int texture_image(const file& f, int texture, const std::string& what);

// Whether the image is stored inside the glTF (not named by URI).
bool is_embedded_image(const file& f, int image);

// Calls `read` with the path of a file holding image `image` (see the top): an embedded one must
// be PNG or JPEG. Any input_error, from finding the image or from `read`, is rethrown as
// "<file>: <what>: image N: <problem>" (never naming the cache's copy), and a copy `read` refused
// is removed from the cache.
void read_image_file(const file& f, int image, const std::string& what,
                     const std::function<void(const std::string& path)>& read);

// An image file as a glTF layout embeds it: the file's own bytes when it is PNG or JPEG (so its
// pixels stay exactly the same), else its pixels as PNG (encode_png; 16-bit when the file has more
// than 8 bits per channel). Throws input_error naming the file.
struct embedded_image {
  std::string bytes;
  std::string mime_type;  // "image/png" or "image/jpeg"
};
embedded_image image_to_embed(const std::string& path);

}  // namespace airr::gltf
