#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <mutex>
#include <system_error>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include "airr/core/color.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "image_header_check.hpp"

namespace airr {

namespace fs = std::filesystem;
using namespace OIIO;

// libpng and libjpeg inside OpenImageIO print their own complaints ("libpng error: ...") to
// stderr before OpenImageIO reports the error, which the project's one error line then says.
// While a file is read, stderr goes to a temporary file; afterwards every line of it that is not
// such a complaint is passed on (another thread's message is delayed, never lost).
class library_chatter_filter {
 public:
  library_chatter_filter() : lock_(mutex()) {
    std::fflush(stderr);
    capture_ = std::tmpfile();
    saved_ = capture_ ? ::dup(2) : -1;
    if (saved_ < 0 || ::dup2(::fileno(capture_), 2) < 0) release();
  }
  ~library_chatter_filter() {
    if (!capture_) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    std::rewind(capture_);
    char line[1024];
    while (std::fgets(line, sizeof line, capture_)) {
      const std::string_view l(line);
      if (l.rfind("libpng ", 0) == 0 || l.rfind("Corrupt JPEG", 0) == 0 || l.rfind("Premature end of JPEG", 0) == 0)
        continue;
      std::fputs(line, stderr);
    }
    release();
  }
  library_chatter_filter(const library_chatter_filter&) = delete;
  library_chatter_filter& operator=(const library_chatter_filter&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  void release() {
    if (saved_ >= 0) ::close(saved_);
    if (capture_) std::fclose(capture_);
    saved_ = -1;
    capture_ = nullptr;
  }
  std::lock_guard<std::mutex> lock_;
  std::FILE* capture_ = nullptr;
  int saved_ = -1;
};

static void refuse_damaged_header(const std::string& path,
                                  std::int64_t pixel_limit = std::numeric_limits<std::int64_t>::max()) {
  if (const auto problem = image_header_problem(path, pixel_limit)) throw input_error(path + ": " + *problem);
}

static bool is_float_format(TypeDesc t) {
  return t.basetype == TypeDesc::FLOAT || t.basetype == TypeDesc::HALF || t.basetype == TypeDesc::DOUBLE;
}

// The pixel-size attribute, written as a decimal string (or stored as a number).
static std::optional<double> read_mm_per_pixel(const std::string& path, const ImageSpec& spec) {
  const ParamValue* p = spec.find_attribute(mm_per_pixel_attribute);
  if (!p) return std::nullopt;
  double value = std::nan("");
  std::string text;
  if (p->type() == TypeString) {
    text = p->get_string();
    const char* begin = text.data();
    const char* end = begin + text.size();
    while (begin != end && *begin == ' ') ++begin;
    while (end != begin && end[-1] == ' ') --end;
    auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc{} || ptr != end) value = std::nan("");
  } else if (p->type().basetype == TypeDesc::FLOAT || p->type().basetype == TypeDesc::DOUBLE ||
             p->type().basetype == TypeDesc::HALF || p->type().basetype == TypeDesc::INT) {
    value = p->get_float();
    text = std::to_string(value);
  } else {
    throw input_error(path + ": attribute " + mm_per_pixel_attribute + " has unsupported type " + p->type().c_str());
  }
  if (!std::isfinite(value) || value <= 0) {
    throw input_error(path + ": attribute " + mm_per_pixel_attribute + " is not a positive number ('" + text + "')");
  }
  return value;
}

loaded_image load_image(const std::string& path, image_encoding encoding, std::int64_t pixel_limit) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw input_error(path + ": no such file");
  if (fs::is_directory(path, ec)) throw input_error(path + ": is a directory, not an image");
  // OpenImageIO's own size limit would refuse a huge header first, naming its attribute; the
  // project's limit (checked below, before any pixel is allocated) names ours.
  static const bool own_limit = OIIO::attribute("limits:imagesize_MB", std::numeric_limits<int>::max());
  (void)own_limit;
  refuse_damaged_header(path, pixel_limit);
  const library_chatter_filter quiet;
  auto in = ImageInput::open(path);
  if (!in) {
    const std::string why = one_line(geterror());
    // Beyond even that raised limit, OpenImageIO refuses the header itself; say it in our terms.
    if (why.find("limits:imagesize_MB") != std::string::npos)
      throw input_error(path + ": image too large (its header declares more than " +
                        std::to_string(std::numeric_limits<int>::max()) + " MB of pixels; the limit is " +
                        std::to_string(max_image_pixels) + " pixels)");
    throw input_error(path + ": cannot read image: " + (why.empty() ? "unknown format" : why));
  }
  const ImageSpec spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw input_error(path + ": image has no pixels");
  if (spec.depth > 1) throw input_error(path + ": volume images are not supported");
  if (std::int64_t(spec.width) * spec.height > pixel_limit) {
    throw input_error(path + ": image too large (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                      "; the limit is " + std::to_string(pixel_limit) + " pixels)");
  }
  loaded_image out;
  out.channels = spec.nchannels;
  out.format = spec.format.c_str();
  out.mm_per_pixel = read_mm_per_pixel(path, spec);
  // Only RGB (or grey) is read: a file's other channels, however many it declares, take no memory.
  const int nc = spec.nchannels >= 3 ? 3 : 1;
  std::vector<float> px(std::size_t(spec.width) * spec.height * nc);
  if (!in->read_image(0, 0, 0, nc, TypeDesc::FLOAT, px.data())) {
    const std::string why = one_line(in->geterror());
    throw input_error(path + ": cannot read pixels: " + (why.empty() ? std::string("truncated or corrupt file") : why));
  }
  const bool wide = is_float_format(spec.format) || spec.format.size() > 1;
  const bool tagged_linear = Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
  out.srgb_decoded =
      encoding == image_encoding::srgb || (encoding == image_encoding::automatic && !wide && !tagged_linear);

  image_rgb& img = out.pixels;
  img.width = spec.width;
  img.height = spec.height;
  img.rgb.resize(std::size_t(spec.width) * spec.height * 3);
  for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float v = px[i * nc + (nc == 3 ? c : 0)];
      if (!std::isfinite(v)) {
        throw input_error(path + ": image contains NaN or infinite values (first at pixel (" +
                          std::to_string(i % std::size_t(spec.width)) + ", " +
                          std::to_string(i / std::size_t(spec.width)) + "))");
      }
      img.rgb[i * 3 + c] = out.srgb_decoded ? float(srgb_decode(v)) : v;
    }
  }
  return out;
}

std::shared_ptr<const image_rgb> cached_image_pixels(const std::string& path) {
  static file_cache<image_rgb> cache;
  return cache.get(path, path, [&] { return std::make_shared<const image_rgb>(load_image(path).pixels); });
}

void write_image(const std::string& path, const image_rgb& img, const image_metadata& meta, float exposure,
                 const std::vector<image_layer>& layers) {
  const fs::path p(path);
  std::string ext = p.extension().string();
  for (auto& c : ext) c = char(std::tolower(c));
  const bool exr = ext == ".exr";
  if (!exr && ext != ".png") throw input_error(path + ": output must be .exr or .png");
  if (!exr && !layers.empty()) throw input_error(path + ": only EXR files take layers");
  for (const image_layer& l : layers) {
    const bool sized = l.zeros || (l.image ? l.image->width == img.width && l.image->height == img.height
                                           : l.interleaved && l.index < l.count);
    if (!sized || l.name.empty())
      throw input_error(path + ": layer '" + l.name + "' is missing or not the image's size");
  }
  const int channels = 3 * (1 + int(layers.size()));
  ImageSpec spec(img.width, img.height, channels, exr ? TypeDesc::FLOAT : TypeDesc::UINT8);
  spec.channelnames = {"R", "G", "B"};
  for (const image_layer& l : layers) {
    for (const char* c : {"R", "G", "B"}) spec.channelnames.push_back(l.name + "." + c);
  }
  for (const auto& [k, v] : meta) spec.attribute(k, v);
  spec.attribute("oiio:ColorSpace", exr ? "linear" : "sRGB");
  if (exr) spec.attribute("compression", "zip");

  // The channels interleaved a strip of rows at a time: a whole image's copy would take as much
  // memory again as the image and its layers.
  const int strip_rows = 64;
  std::vector<float> strip(std::size_t(img.width) * std::size_t(std::min(strip_rows, img.height)) * channels);
  auto fill_strip = [&](int y0, int y1) {
    for (std::size_t px = std::size_t(y0) * img.width; px < std::size_t(y1) * img.width; ++px) {
      float* o = strip.data() + (px - std::size_t(y0) * img.width) * channels;
      for (int c = 0; c < 3; ++c) {
        const float v = img.rgb[3 * px + c];
        o[c] = exr ? v : float(srgb_encode(std::clamp(v * exposure, 0.0f, 1.0f)));
      }
      for (std::size_t l = 0; l < layers.size(); ++l) {
        const image_layer& from = layers[l];
        if (from.zeros) {
          std::fill_n(o + 3 * (l + 1), 3, 0.0f);
          continue;
        }
        const float* v =
            from.image ? from.image->rgb.data() + 3 * px : from.interleaved + 3 * (from.count * px + from.index);
        std::copy_n(v, 3, o + 3 * (l + 1));
      }
    }
  };

  // A folder that is missing or not writable is said before anything is encoded.
  const fs::path probe = p.parent_path() / (".tmp." + std::to_string(::getpid()) + "." + p.stem().string() + ext);
  if (const std::string os = reason_cannot_create(probe.string()); !os.empty())
    throw input_error(path + ": cannot write image: " + os);
  // Encoded in memory, then written as every file is (write_file_atomic): a write that fails (a
  // full disk, a file too large) says the system's reason and leaves the old file, where the PNG
  // writer would leave a truncated file and report success.
  std::vector<unsigned char> bytes;
  Filesystem::IOVecOutput proxy(bytes);
  auto o = ImageOutput::create(exr ? "exr" : "png", &proxy);
  bool ok = o && o->supports("ioproxy") && o->open(p.filename().string(), spec);
  for (int y0 = 0; ok && y0 < img.height; y0 += strip_rows) {
    const int y1 = std::min(img.height, y0 + strip_rows);
    fill_strip(y0, y1);
    ok = o->write_scanlines(y0, y1, 0, TypeDesc::FLOAT, strip.data());
  }
  ok = ok && o->close();
  if (!ok) {
    const std::string why = one_line(o ? o->geterror() : geterror());
    throw input_error(path + ": cannot write image: " + (why.empty() ? "the writer refused the image" : why));
  }
  o.reset();
  write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

std::string encode_png(const image_rgb& img, bool sixteen_bit, const std::string& what) {
  ImageSpec spec(img.width, img.height, 3, sixteen_bit ? TypeDesc::UINT16 : TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", sixteen_bit ? "linear" : "sRGB");
  std::vector<float> px(img.rgb.size());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const float v = std::clamp(img.rgb[i], 0.0f, 1.0f);
    px[i] = sixteen_bit ? v : float(srgb_encode(v));
  }
  std::vector<unsigned char> bytes;
  Filesystem::IOVecOutput proxy(bytes);
  auto out = ImageOutput::create("png", &proxy);
  const bool ok =
      out && out->open("embedded.png", spec) && out->write_image(TypeDesc::FLOAT, px.data()) && out->close();
  if (!ok) {
    const std::string why = one_line(out ? out->geterror() : geterror());
    throw input_error(what + ": cannot encode PNG: " + (why.empty() ? "write failed" : why));
  }
  return std::string(bytes.begin(), bytes.end());
}

std::vector<std::string> read_image_layer_names(const std::string& path) {
  refuse_damaged_header(path);
  const library_chatter_filter quiet;
  auto in = ImageInput::open(path);
  if (!in) throw input_error(path + ": cannot read image: " + one_line(geterror()));
  std::vector<std::string> names;
  for (const std::string& c : in->spec().channelnames) {
    const auto dot = c.rfind('.');
    if (dot == std::string::npos) continue;
    const std::string name = c.substr(0, dot);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

std::vector<std::pair<std::string, image_rgb>> load_image_layers(const std::string& path) {
  refuse_damaged_header(path, max_image_pixels);
  const std::vector<std::string> names = read_image_layer_names(path);  // before `quiet`: it holds a lock
  const library_chatter_filter quiet;
  auto in = ImageInput::open(path);
  if (!in) throw input_error(path + ": cannot read image: " + one_line(geterror()));
  const ImageSpec spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || std::int64_t(spec.width) * spec.height > max_image_pixels)
    throw input_error(path + ": no pixels, or more than " + std::to_string(max_image_pixels));
  const std::size_t pixels = std::size_t(spec.width) * std::size_t(spec.height), nc = std::size_t(spec.nchannels);
  std::vector<float> px(pixels * nc);
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, px.data()))
    throw input_error(path + ": cannot read pixels: " + one_line(in->geterror()));
  std::vector<std::pair<std::string, image_rgb>> layers;
  for (const std::string& name : names) {
    std::array<int, 3> at{-1, -1, -1};
    for (std::size_t c = 0; c < nc; ++c) {
      for (std::size_t k = 0; k < 3; ++k)
        if (spec.channelnames[c] == name + "." + "RGB"[k]) at[k] = int(c);
    }
    if (std::find(at.begin(), at.end(), -1) != at.end()) continue;  // not an RGB layer
    image_rgb img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgb.resize(3 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      for (std::size_t k = 0; k < 3; ++k) {
        const float v = px[i * nc + std::size_t(at[k])];
        if (!std::isfinite(v)) throw input_error(path + ": layer '" + name + "' contains NaN or infinite values");
        img.rgb[3 * i + k] = v;
      }
    }
    layers.emplace_back(name, std::move(img));
  }
  return layers;
}

image_rgb load_image_layer(const std::string& path, const std::string& name) {
  for (auto& [n, img] : load_image_layers(path))
    if (n == name) return std::move(img);
  throw input_error(path + ": no layer '" + name + "'");
}

image_rgb image_rows(const image_rgb& img, int first, int end) {
  image_rgb out;
  out.width = img.width;
  out.height = end - first;
  out.rgb.assign(img.rgb.begin() + std::ptrdiff_t(3) * img.width * first,
                 img.rgb.begin() + std::ptrdiff_t(3) * img.width * end);
  return out;
}

image_metadata read_image_metadata(const std::string& path) {
  refuse_damaged_header(path);
  const library_chatter_filter quiet;
  auto in = ImageInput::open(path);
  if (!in) throw input_error(path + ": cannot read image: " + one_line(geterror()));
  image_metadata meta;
  for (const auto& a : in->spec().extra_attribs) {
    const std::string name = a.name().string();
    if (name.rfind("airr:", 0) == 0) meta[name] = a.get_string();
  }
  return meta;
}

}  // namespace airr
