#include "airr/ui/platform/screenshot.hpp"

#include <filesystem>
#include <vector>

#include <GL/gl.h>
#include <OpenImageIO/imageio.h>

#include "airr/core/error.hpp"

namespace airr::ui {

void write_framebuffer_png(const std::string& path, int width, int height) {
  std::vector<unsigned char> px(std::size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, px.data());
  const std::filesystem::path p(path), tmp = p.parent_path() / (".tmp." + p.filename().string());
  auto out = OIIO::ImageOutput::create(tmp.string());
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!out || !out->open(tmp.string(), spec))
    throw input_error(path + ": cannot write screenshot: " + OIIO::geterror());
  // OpenGL rows start at the bottom: write them top first.
  const auto stride = OIIO::stride_t(width) * 3;
  const bool ok = out->write_image(OIIO::TypeDesc::UINT8, px.data() + (height - 1) * stride, OIIO::AutoStride, -stride);
  out->close();
  std::error_code ec;
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    throw input_error(path + ": cannot write screenshot");
  }
  std::filesystem::rename(tmp, p, ec);
  if (ec) throw input_error(path + ": cannot replace file: " + ec.message());
}

}  // namespace airr::ui
