// libFuzzer entry for one target, chosen at compile time (AIRR_FUZZ_TARGET).
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  airr::fuzz::run(AIRR_FUZZ_TARGET, {reinterpret_cast<const char*>(data), size});
  return 0;
}
