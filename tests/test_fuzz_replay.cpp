// Every fuzz target on its seeds (tests/fuzz/seeds.txt), each of which it reads, and on every
// input kept from a finding (tests/fuzz/regressions/<target>/), each read or refused with the
// project's error, never anything else (under the asan tree: never a sanitizer report either).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "airr/analysis/fit_data.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "fuzz/fuzz_targets.hpp"
#include "test_helpers.hpp"

namespace fs = std::filesystem;
using airr::test::error_of;

namespace {

const fs::path source_dir = AIRR_SOURCE_DIR;

std::vector<fs::path> files_in(const fs::path& dir, const std::string& extension = "") {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension)) out.push_back(e.path());
  return out;
}

// seeds.txt: "target file" or "target folder [extension]" per line, '#' starts a comment.
std::map<std::string, std::vector<fs::path>> seeds() {
  std::map<std::string, std::vector<fs::path>> out;
  std::ifstream in(source_dir / "tests/fuzz/seeds.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string target, where, extension;
    words >> target >> where >> extension;
    const fs::path p = source_dir / where;
    auto& files = out[target];
    if (fs::is_directory(p)) {
      for (const auto& f : files_in(p, extension)) files.push_back(f);
    } else {
      EXPECT_TRUE(fs::is_regular_file(p)) << "seeds.txt names a missing file: " << where;
      files.push_back(p);
    }
  }
  return out;
}

}  // namespace

TEST(FuzzReplay, SeedsAndKeptFindingsAreReadOrRefused) {
  const auto all_seeds = seeds();
  int inputs = 0;
  for (const char* target : airr::fuzz::targets) {
    const auto found = all_seeds.find(target);
    ASSERT_TRUE(found != all_seeds.end() && !found->second.empty()) << "no seeds for " << target;
    // Seeds are sound files: each loads, or the target does not reach its loader's depths.
    for (const auto& f : found->second) {
      bool loaded = false;
      EXPECT_NO_THROW(loaded = airr::fuzz::run(target, airr::read_text_file(f.string()))) << target << ": " << f;
      EXPECT_TRUE(loaded) << "the seed is refused: " << target << ": " << f;
      ++inputs;
    }
    for (const auto& f : files_in(source_dir / "tests/fuzz/regressions" / target)) {
      EXPECT_NO_THROW(airr::fuzz::run(target, airr::read_text_file(f.string()))) << target << ": " << f;
      ++inputs;
    }
  }
  EXPECT_EQ(all_seeds.size(), std::size(airr::fuzz::targets)) << "seeds.txt names a target that does not exist";
  EXPECT_GT(inputs, 40);
}

// Found by the image target: a JPEG whose Photoshop IPTC block claims more bytes than its segment
// holds made OpenImageIO read past the segment (AddressSanitizer: heap-buffer-overflow in
// decode_iptc_iim). The loader refuses it first; a JPEG with a sound IPTC block still loads.
TEST(FuzzFindings, JpegWhoseIptcBlockOverrunsItsSegmentIsRefused) {
  const fs::path sound = source_dir / "tests/fuzz/seeds/image/rgb.jpg";
  ASSERT_NE(airr::read_text_file(sound.string()).find("Photoshop 3.0"), std::string::npos);
  EXPECT_EQ(airr::load_image(sound.string()).pixels.width, 8);
  // The second one has two stray bytes before the segment, which libjpeg skips.
  for (const char* finding :
       {"crash-56b2e2fecc064e9865224ae525aeb51f7d05a60e", "crash-f1b8460f6a4804672aed385dad49bac54ec23721"}) {
    const std::string error =
        error_of([&] { airr::load_image((source_dir / "tests/fuzz/regressions/image" / finding).string()); });
    EXPECT_NE(error.find("IPTC block claims"), std::string::npos) << finding << ": " << error;
  }
  // The sound file with its first IPTC record's length raised beyond the block.
  std::string bytes = airr::read_text_file(sound.string());
  const std::size_t block = bytes.find("Photoshop 3.0") + 26;
  ASSERT_EQ(bytes[block], '\x1c');
  bytes[block + 3] = '\x7f';
  const airr::test::temp_dir dir;
  airr::write_file_atomic(dir.file("overrun.jpg"), bytes);
  const std::string error = error_of([&] { airr::load_image(dir.file("overrun.jpg")); });
  EXPECT_NE(error.find("an IPTC record claims"), std::string::npos) << error;
}

namespace {

// The seed EXR's bytes with its 38-byte 'capDate' string attribute (name, type, size, value)
// replaced by `attribute`.
std::string exr_with_attribute(const std::string& attribute) {
  std::string bytes = airr::read_text_file((source_dir / "tests/fuzz/seeds/image/rgbh.exr").string());
  const std::size_t at = bytes.find(std::string("capDate\0string\0", 15));
  EXPECT_NE(at, std::string::npos);
  return bytes.replace(at, 38, attribute);
}

std::string le32(std::uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

std::string load_error(const std::string& bytes, std::int64_t pixel_limit = airr::max_image_pixels) {
  const airr::test::temp_dir dir;
  airr::write_file_atomic(dir.file("image.exr"), bytes);
  return error_of([&] { airr::load_image(dir.file("image.exr"), airr::image_encoding::automatic, pixel_limit); });
}

}  // namespace

// Found by the image target (as its slowest inputs): OpenEXR allocates a header attribute by the
// size written before it, and a string list's strings and a preview's pixels by theirs, so a
// damaged size in a file of a few hundred bytes made it allocate up to 2 GB; and it allocates
// several lines of pixels as it opens a file, before the loader's size check. The loader checks
// those sizes first; sound attributes of the same types still load.
TEST(FuzzFindings, ExrHeaderSizesAreCheckedBeforeTheLibraryAllocates) {
  const std::string kept = airr::read_text_file(
      (source_dir / "tests/fuzz/regressions/image/slow-unit-b597cdbd30b352fdb4d423c089ef9cce01d66614").string());
  EXPECT_NE(load_error(kept).find("its header attribute 'capDate' (string) claims 1667457891 bytes, the file holds"),
            std::string::npos)
      << load_error(kept);

  const std::string date("2026:11:24 14:10:54", 19);
  const std::string string_attribute = std::string("capDate\0string\0", 15);
  EXPECT_EQ(load_error(exr_with_attribute(string_attribute + le32(19) + date)), "");
  EXPECT_NE(load_error(exr_with_attribute(string_attribute + le32(0x7fffff00) + date))
                .find("its header attribute 'capDate' (string) claims 2147483392 bytes, the file holds"),
            std::string::npos);

  // 16 + 4 + 18 bytes: one string of 14 characters.
  const std::string list = std::string("cD\0stringvector\0", 16);
  EXPECT_EQ(load_error(exr_with_attribute(list + le32(18) + le32(14) + date.substr(0, 14))), "");
  EXPECT_NE(load_error(exr_with_attribute(list + le32(18) + le32(1000) + date.substr(0, 14)))
                .find("a string in its header attribute 'cD' claims 1000 bytes, the attribute holds 14"),
            std::string::npos);

  // 22 + 4 + 12 bytes: a preview of one pixel.
  const std::string preview = std::string("previewSample\0preview\0", 22);
  EXPECT_EQ(load_error(exr_with_attribute(preview + le32(12) + le32(1) + le32(1) + "RGBA")), "");
  EXPECT_NE(load_error(exr_with_attribute(preview + le32(12) + le32(1000) + le32(1000) + "RGBA"))
                .find("its preview image 'previewSample' declares 1000000 pixels in 12 bytes"),
            std::string::npos);

  // Found by the image target in the check itself: a preview's width times height overflowed.
  EXPECT_NE(load_error(exr_with_attribute(preview + le32(12) + le32(0xffffffff) + le32(0xffffffff) + "RGBA"))
                .find("declares 18446744065119617025 pixels in 12 bytes"),
            std::string::npos);

  // The data window 2^30 pixels wide: refused before the library allocates a line of it.
  std::string wide = exr_with_attribute(string_attribute + le32(19) + date);
  const std::size_t window = wide.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4;
  wide.replace(window + 8, 4, le32((1u << 30) - 1));
  EXPECT_NE(load_error(wide).find("image too large (1073741824x8; the limit is 67108864 pixels)"), std::string::npos)
      << load_error(wide);
}

// Found by the fit_json target: a file name in fit.json too long for the system made the
// existence check throw a filesystem error, which nothing caught.
TEST(FuzzFindings, FitDataFileNameTooLongIsNotFound) {
  const airr::test::temp_dir dir;
  airr::write_file_atomic(dir.file("fit.json"),
                          R"({"format": "airr-fit-data", "version": 1, "scene": ")" + std::string(5000, 'x') + R"("})");
  const std::string error = error_of([&] { airr::analysis::load_fit_data(dir.path.string()); });
  EXPECT_NE(error.find("scene: file 'xxxx"), std::string::npos) << error;
  EXPECT_NE(error.find("not found"), std::string::npos) << error;
}

// Found by the scene_set target: a value of bytes that are not UTF-8 (`--set tilt_deg=12.3` and
// three 0xec bytes) made the message that shows the value as given throw the JSON library's
// type_error instead of the scene's error. The bytes are shown replaced.
TEST(FuzzFindings, AValueThatIsNotUtf8IsShownInItsError) {
  const std::string scene = airr::read_text_file(airr::default_scene_path());
  const std::string error = error_of([&] {
    airr::parse_scene(scene, "scene.json", "", {{"tilt_deg", "12.3\xec\xec\xec"}});
  });
  EXPECT_NE(error.find("must be a number (is \"12.3\xef\xbf\xbd"), std::string::npos) << error;
  EXPECT_NE(error.find("scene.json (with --set)"), std::string::npos) << error;
}
