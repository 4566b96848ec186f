// Every fuzz target on its seeds (tests/fuzz/seeds.txt) and on every input kept from a finding
// (tests/fuzz/regressions/<target>/): each is read or refused with the project's error, never
// anything else (under the asan tree: never a sanitizer report either).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "airr/optics/error.hpp"
#include "airr/optics/files.hpp"
#include "airr/optics/image.hpp"
#include "fuzz/fuzz_targets.hpp"

namespace fs = std::filesystem;

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
    std::vector<fs::path> all = found->second;
    for (const auto& f : files_in(source_dir / "tests/fuzz/regressions" / target)) all.push_back(f);
    for (const auto& f : all) {
      const std::string bytes = airr::read_text_file(f.string());
      EXPECT_NO_THROW(EXPECT_TRUE(airr::fuzz::run(target, bytes))) << target << ": " << f;
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
    try {
      airr::load_image((source_dir / "tests/fuzz/regressions/image" / finding).string());
      ADD_FAILURE() << finding << " loaded";
    } catch (const airr::input_error& e) {
      EXPECT_NE(std::string(e.what()).find("IPTC block claims"), std::string::npos) << e.what();
    }
  }
  // The sound file with its first IPTC record's length raised beyond the block.
  std::string bytes = airr::read_text_file(sound.string());
  const std::size_t block = bytes.find("Photoshop 3.0") + 26;
  ASSERT_EQ(bytes[block], '\x1c');
  bytes[block + 3] = '\x7f';
  const fs::path overrun = fs::temp_directory_path() / ("airr-iptc-" + std::to_string(::getpid()) + ".jpg");
  airr::write_file_atomic(overrun.string(), bytes);
  try {
    airr::load_image(overrun.string());
    ADD_FAILURE() << "loaded";
  } catch (const airr::input_error& e) {
    EXPECT_NE(std::string(e.what()).find("an IPTC record claims"), std::string::npos) << e.what();
  }
  fs::remove(overrun);
}
