#pragma once
// The image library trusts some sizes written in a file's header before it checks them against the
// file, so a few hundred bytes can make it read past a buffer or allocate gigabytes (both found by
// the image fuzz target). The loader checks those sizes before OpenImageIO opens the file:
// - JPEG: OpenImageIO 2.4 reads the IPTC block in the Photoshop segment (APP13) by the sizes
//   written in it, and read past the segment when they overran it;
// - OpenEXR: the library allocates each header attribute (strings, string lists, previews) by its
//   declared size before reading it, so a damaged size made it allocate up to 2 GB; and it
//   allocates several whole lines of pixels as it opens a file, so the data window's size is
//   checked against the loader's limit here.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace airr {

// What is wrong with the file's header, as the error's text after the file's name, or nothing
// (also for files in other formats, and for headers that end early: the image library reports
// those).
std::optional<std::string> image_header_problem(const std::string& path,
                                                std::int64_t pixel_limit = std::numeric_limits<std::int64_t>::max());

}  // namespace airr
