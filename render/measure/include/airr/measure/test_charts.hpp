#pragma once
// The source images shipped in assets/charts, drawn procedurally so they can be regenerated.
#include "airr/formats/image.hpp"

namespace airr {

// Slanted edge (5 degrees from vertical, white left), resolution bars, a square, a checkerboard
// and an asymmetric "F" that shows whether the aerial image is flipped.
image_rgb make_test_chart(int size = 512);
// A white field with a black right part whose edge is 5 degrees from vertical through the centre.
image_rgb make_slanted_edge_chart(int size = 512, double angle_deg = 5.0);

}  // namespace airr
