#include "test_files.hpp"

#include <fstream>
#include <random>
#include <stdexcept>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "airr/analysis/image_read.hpp"

namespace airr::analysis::testing {

scratch_dir::scratch_dir(const std::string& tag) {
  std::random_device rd;
  path = std::filesystem::temp_directory_path() /
         ("airr_analysis_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
  std::filesystem::create_directories(path);
}

scratch_dir::~scratch_dir() {
  std::error_code ignored;
  std::filesystem::remove_all(path, ignored);
}

namespace {

void write_oiio(const std::filesystem::path& path, OIIO::ImageSpec spec, const void* data) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out || !out->open(path.string(), spec) || !out->write_image(spec.format, data) || !out->close())
    throw std::runtime_error("test could not write " + path.string() + ": " + OIIO::geterror());
}

}  // namespace

void write_exr(const std::filesystem::path& path, const cv::Mat& pixels, attribute_kind kind,
               const std::string& mm_per_pixel) {
  cv::Mat f;
  pixels.convertTo(f, CV_32F);
  OIIO::ImageSpec spec(f.cols, f.rows, f.channels(), OIIO::TypeDesc::FLOAT);
  if (kind == attribute_kind::string) spec.attribute(mm_per_pixel_attribute, mm_per_pixel);
  if (kind == attribute_kind::floating) spec.attribute(mm_per_pixel_attribute, std::stof(mm_per_pixel));
  const cv::Mat packed = f.isContinuous() ? f : f.clone();
  write_oiio(path, spec, packed.ptr());
}

void write_coded(const std::filesystem::path& path, const cv::Mat& codes,
                 const std::optional<std::string>& mm_per_pixel) {
  const auto type = codes.depth() == CV_8U ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
  if (codes.depth() != CV_8U && codes.depth() != CV_16U) throw std::runtime_error("write_coded takes CV_8U or CV_16U");
  OIIO::ImageSpec spec(codes.cols, codes.rows, codes.channels(), type);
  if (mm_per_pixel) spec.attribute(mm_per_pixel_attribute, *mm_per_pixel);
  const cv::Mat packed = codes.isContinuous() ? codes : codes.clone();
  write_oiio(path, spec, packed.ptr());
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out) throw std::runtime_error("test could not write " + path.string());
}

}  // namespace airr::analysis::testing
