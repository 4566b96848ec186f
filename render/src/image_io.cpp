#include <cmath>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include "airr/optics/error.hpp"
#include "airr/optics/srgb.hpp"
#include "airr/render/image.hpp"

namespace airr {

namespace fs = std::filesystem;
using namespace OIIO;

float srgb_to_linear(float v) { return float(srgb_decode(v)); }
float linear_to_srgb(float v) { return float(srgb_encode(std::clamp(v, 0.0f, 1.0f))); }

static bool is_float_format(TypeDesc t) { return t.basetype == TypeDesc::FLOAT || t.basetype == TypeDesc::HALF || t.basetype == TypeDesc::DOUBLE; }

image_rgb load_image_linear(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw input_error(path + ": image file not found");
  auto in = ImageInput::open(path);
  if (!in) throw input_error(path + ": cannot read image: " + geterror());
  const ImageSpec spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw input_error(path + ": image has no pixels");
  if (std::int64_t(spec.width) * spec.height > 64LL * 1024 * 1024) {
    throw input_error(path + ": image too large (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ")");
  }
  std::vector<float> px(std::size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, px.data())) {
    throw input_error(path + ": cannot decode image: " + in->geterror());
  }
  const bool linear = is_float_format(spec.format) ||
                      Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
  image_rgb img;
  img.width = spec.width;
  img.height = spec.height;
  img.rgb.resize(std::size_t(spec.width) * spec.height * 3);
  const int nc = spec.nchannels;
  for (std::size_t i = 0; i < std::size_t(spec.width) * spec.height; ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = px[i * nc + (nc >= 3 ? c : 0)];
      if (!std::isfinite(v)) throw input_error(path + ": image contains NaN or infinite values");
      img.rgb[i * 3 + c] = linear ? v : srgb_to_linear(v);
    }
  }
  return img;
}

void write_image(const std::string& path, const image_rgb& img, const image_metadata& meta, float exposure) {
  const fs::path p(path);
  std::string ext = p.extension().string();
  for (auto& c : ext) c = char(std::tolower(c));
  const bool exr = ext == ".exr";
  if (!exr && ext != ".png") throw input_error(path + ": output must be .exr or .png");
  ImageSpec spec(img.width, img.height, 3, exr ? TypeDesc::FLOAT : TypeDesc::UINT8);
  for (const auto& [k, v] : meta) spec.attribute(k, v);
  spec.attribute("oiio:ColorSpace", exr ? "linear" : "sRGB");
  if (exr) spec.attribute("compression", "zip");

  std::vector<float> out(img.rgb.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = exr ? img.rgb[i] : linear_to_srgb(img.rgb[i] * exposure);

  const fs::path tmp = p.parent_path() / (".tmp." + p.stem().string() + ext);
  auto o = ImageOutput::create(tmp.string());
  if (!o || !o->open(tmp.string(), spec)) throw input_error(path + ": cannot write image: " + geterror());
  const bool ok = o->write_image(TypeDesc::FLOAT, out.data());
  const std::string err = ok ? "" : o->geterror();
  o->close();
  if (!ok) {
    fs::remove(tmp);
    throw input_error(path + ": cannot write image: " + err);
  }
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp);
    throw input_error(path + ": cannot replace file: " + ec.message());
  }
}

image_metadata read_image_metadata(const std::string& path) {
  auto in = ImageInput::open(path);
  if (!in) throw input_error(path + ": cannot read image: " + geterror());
  image_metadata meta;
  for (const auto& a : in->spec().extra_attribs) {
    const std::string name = a.name().string();
    if (name.rfind("airr:", 0) == 0) meta[name] = a.get_string();
  }
  return meta;
}

}  // namespace airr
