#pragma once
// The project's image: linear RGB floats, and its one loader and writer (OpenImageIO).
//
// Linearity rule for files: float and half files and integer files of more than 8 bits are
// linear; 8-bit files are sRGB-encoded unless the file tags itself linear (oiio:ColorSpace).
// A caller may force either reading (image_encoding).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace airr {

struct image_rgb {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // row-major from the top-left, 3 floats per pixel

  float* at(int x, int y) { return rgb.data() + 3 * (std::size_t(y) * width + x); }
  const float* at(int x, int y) const { return rgb.data() + 3 * (std::size_t(y) * width + x); }
};

// How a file's code values map to linear values: by the rule above, or forced.
enum class image_encoding { automatic, srgb, linear };

// Largest image the loader accepts, in pixels (checked before pixels are allocated).
inline constexpr std::int64_t max_image_pixels = 64LL * 1024 * 1024;

// Name of the metadata attribute the renderer writes with the pixel size on the aerial-image plane.
inline constexpr const char* mm_per_pixel_attribute = "airr:mm_per_pixel";

struct loaded_image {
  image_rgb pixels;                    // linear; grey replicated to RGB, alpha and extra channels dropped
  bool srgb_decoded = false;           // the code values went through the sRGB curve
  int channels = 0;                    // in the file
  std::string format;                  // the file's pixel type, e.g. "uint8", "half"
  std::optional<double> mm_per_pixel;  // from the mm_per_pixel_attribute, if present
};

// Reads EXR, PNG, TIFF, JPEG, HDR... Throws input_error "<path>: <problem>" for a missing,
// unreadable or truncated file, an absurd size, non-finite pixels or a bad pixel-size attribute.
// A caller may lower the pixel limit (the fuzz harness does, so that mutated headers stay cheap).
loaded_image load_image(const std::string& path, image_encoding encoding = image_encoding::automatic,
                        std::int64_t pixel_limit = max_image_pixels);
// An image's linear pixels (read as load_image reads them by default), kept while the file is
// unchanged: a file replaced on disk is read again at the next call.
std::shared_ptr<const image_rgb> cached_image_pixels(const std::string& path);

// String metadata written into the file (PNG text chunks, EXR header attributes).
using image_metadata = std::map<std::string, std::string>;

// Writes EXR (float, linear) or PNG (8-bit sRGB after scaling by `exposure`), chosen by the
// extension, atomically (temporary file then rename). Throws input_error.
// Named layers of the same size go into an EXR after RGB as channels "<name>.R", "<name>.G",
// "<name>.B" (a PNG takes none: input_error).
struct image_layer {
  std::string name;
  const image_rgb* image = nullptr;
  // Or, read in place rather than copied out: the `index`-th of `count` RGB triples a pixel of
  // `interleaved`, which has the image's size (a render's components or path layers).
  const float* interleaved = nullptr;
  std::size_t count = 0, index = 0;
  bool zeros = false;  // or zero everywhere (a render's component its scene cannot have)
};
void write_image(const std::string& path, const image_rgb& img, const image_metadata& meta, float exposure = 1.0f,
                 const std::vector<image_layer>& layers = {});

// The bytes of a PNG file holding the image (for embedding it in another file, e.g. a glTF
// layout): 8-bit sRGB-encoded, or with `sixteen_bit` its linear values in 16 bits, so that
// load_image reads either back as these pixels (to their precision; values are clamped to
// [0, 1]). Throws input_error "<what>: ...".
std::string encode_png(const image_rgb& img, bool sixteen_bit, const std::string& what);

// The layer names of an image file's channels "<name>.<channel>" (in order, each once).
std::vector<std::string> read_image_layer_names(const std::string& path);

// The layer "<name>" of an image file (channels "<name>.R", "<name>.G", "<name>.B", as write_image
// writes them), linear as written. Throws input_error "<path>: ..." when the file has no such
// layer or load_image would refuse it.
image_rgb load_image_layer(const std::string& path, const std::string& name);
// Every such layer of the file, in order, read at once.
std::vector<std::pair<std::string, image_rgb>> load_image_layers(const std::string& path);

// Rows [first, end) of an image.
image_rgb image_rows(const image_rgb& img, int first, int end);

// Reads back the string metadata of an image file (only keys starting with "airr:").
image_metadata read_image_metadata(const std::string& path);

}  // namespace airr
