#pragma once
// Scratch directories and hand-written image files for the analysis tests.
#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "../error_of.hpp"

namespace airr::analysis::testing {

// A fresh directory under the system temp directory, removed on destruction.
struct scratch_dir {
  std::filesystem::path path;
  explicit scratch_dir(const std::string& tag);
  ~scratch_dir();
  scratch_dir(const scratch_dir&) = delete;
  scratch_dir& operator=(const scratch_dir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path / name; }
};

using airr::test::error_of;

enum class attribute_kind { none, string, floating };

// Writes a float EXR (1 or 3 channels, from CV_64FC1/CV_64FC3 in RGB order), optionally with
// the pixel-size attribute stored as a string or a float.
void write_exr(const std::filesystem::path& path, const cv::Mat& pixels, attribute_kind kind = attribute_kind::none,
               const std::string& mm_per_pixel = "");

// Writes integer code values (CV_8U or CV_16U, 1 or 3 channels in RGB order) to any format OIIO
// writes (PNG, TIFF, JPEG), with an optional string pixel-size attribute.
void write_coded(const std::filesystem::path& path, const cv::Mat& codes,
                 const std::optional<std::string>& mm_per_pixel = std::nullopt);

// Writes raw bytes.
void write_bytes(const std::filesystem::path& path, const std::string& bytes);

}  // namespace airr::analysis::testing
