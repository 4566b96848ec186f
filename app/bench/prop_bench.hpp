#pragma once
// airr bench --prop-triangles N: what a large prop costs (see prop_bench.cpp).
#include <cstdint>
#include <string>

void run_prop_bench(const std::string& scene_path, std::uint64_t triangles, std::uint64_t spp);
