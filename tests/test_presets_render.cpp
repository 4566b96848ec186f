// The shipped presets through the tracer: the aerial image's brightness follows mu(tilt).
#include <gtest/gtest.h>

#include "airr/models/preset.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(PresetsRender, BrightnessFallsWithTiltAsMuDoes) {
  for (const char* name : {"rf-ay", "rf-an"}) {
    const sheet_preset preset = load_preset(name);
    double previous = 1e30;
    for (std::size_t i = 0; i < preset.theta_deg.size(); ++i) {
      // A large source keeps the sinc^2 tail's loss small (about 1 / (pi a R tan(delta_edge)));
      // centre pixels see incidence angles within 0.2 deg of the tilt.
      scene s = test::uniform_source_scene(100.0, 64);
      s.sheet().pose.pitch_deg = preset.theta_deg[i];
      s.sheet().model.type = "sinc_shift";
      airr::set_model_value(s.sheet().model, "preset", name);
      const double l = test::centre_mean(test::render_to(s, 32), 3);
      const double expected = s.source.intensity * 0.25 * preset.mu[i];
      EXPECT_NEAR(l, expected, 0.03 * expected) << name << " tilt " << preset.theta_deg[i];
      EXPECT_LT(l, previous) << name << " tilt " << preset.theta_deg[i];
      previous = l;
    }
  }
}
