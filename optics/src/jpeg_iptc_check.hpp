#pragma once
// OpenImageIO 2.4 reads the IPTC block in a JPEG's Photoshop segment (APP13) trusting the sizes
// written in it, and reads past the segment when they overrun it (found by the image fuzz target).
// The loader checks those sizes before OpenImageIO opens the file.
#include <optional>
#include <string>

namespace airr {

// What is wrong with the file's IPTC block, or nothing (also for files that are not JPEG, and
// for JPEG files whose segments end early: the image library reports those).
std::optional<std::string> jpeg_iptc_problem(const std::string& path);

}  // namespace airr
