// SSIM and MS-SSIM.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "airr/analysis/similarity.hpp"

namespace aa = airr::analysis;

namespace {

// A structured test scene: smooth shading, a disc and a few bars.
cv::Mat scene(int w = 256, int h = 192) {
  cv::Mat img(h, w, CV_64FC1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double v = 0.3 + 0.2 * std::sin(x * 0.05) * std::cos(y * 0.07);
      if (std::hypot(x - 0.6 * w, y - 0.5 * h) < 0.2 * h) v += 0.3;
      if (x < 0.3 * w && (y / 8) % 2 == 0) v -= 0.2;
      img.at<double>(y, x) = v;
    }
  return img;
}

cv::Mat with_noise(const cv::Mat& img, double sigma, std::uint64_t seed) {
  cv::Mat noise(img.size(), CV_64FC1);
  cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  return img + noise;
}

}  // namespace

TEST(Ssim, ImageWithItselfIsOne) {
  const cv::Mat a = scene();
  EXPECT_NEAR(aa::ssim(a, a), 1.0, 1e-12);
  EXPECT_NEAR(aa::ms_ssim(a, a).value, 1.0, 1e-12);
  EXPECT_EQ(aa::ms_ssim(a, a).scales, 5);
}

TEST(Ssim, FallsMonotonicallyAsNoiseGrows) {
  const cv::Mat a = scene();
  aa::ssim_params p;
  p.data_range = 1.0;  // fixed, so only the noise changes between runs
  double last_ssim = 1.0, last_ms = 1.0;
  for (double sigma : {0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4}) {
    const cv::Mat b = with_noise(a, sigma, 11);
    const double s = aa::ssim(a, b, p);
    const double ms = aa::ms_ssim(a, b, p).value;
    EXPECT_LT(s, last_ssim) << "noise sigma " << sigma;
    EXPECT_LT(ms, last_ms) << "noise sigma " << sigma;
    EXPECT_GT(s, 0.0);
    last_ssim = s;
    last_ms = ms;
  }
  EXPECT_LT(last_ssim, 0.2);
}

TEST(Ssim, ConstantOffsetMatchesLuminanceTerm) {
  // Flat images differ only in mean: SSIM = (2 m1 m2 + C1) / (m1^2 + m2^2 + C1).
  const cv::Mat a(40, 50, CV_64FC1, cv::Scalar(0.4)), b(40, 50, CV_64FC1, cv::Scalar(0.6));
  aa::ssim_params p;
  p.data_range = 1.0;
  const double c1 = 0.01 * 0.01;
  EXPECT_NEAR(aa::ssim(a, b, p), (2 * 0.4 * 0.6 + c1) / (0.16 + 0.36 + c1), 1e-12);
}

TEST(Ssim, NegatedStructureScoresBelowZero) {
  // Strong texture everywhere, so every window's structure is reversed.
  const cv::Mat a = with_noise(scene(), 0.1, 5);
  const cv::Mat b = 2.0 * cv::mean(a)[0] - a;  // same mean and variance, opposite structure
  EXPECT_LT(aa::ssim(a, b), 0.0);
  EXPECT_EQ(aa::ms_ssim(a, b).value, 0.0);
}

TEST(Ssim, DifferentSizesAreAnError) {
  try {
    aa::ssim(scene(64, 64), scene(64, 65));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("differ in size"), std::string::npos) << e.what();
  }
  EXPECT_THROW(aa::ms_ssim(scene(64, 64), scene(65, 64)), std::runtime_error);
}

TEST(Ssim, TooSmallOrInvalidImagesAreErrors) {
  EXPECT_THROW(aa::ssim(cv::Mat(8, 8, CV_64FC1, cv::Scalar(0)), cv::Mat(8, 8, CV_64FC1, cv::Scalar(0))),
               std::runtime_error);
  cv::Mat nan = scene(32, 32);
  nan.at<double>(3, 3) = std::nan("");
  EXPECT_THROW(aa::ssim(nan, scene(32, 32)), std::runtime_error);
  EXPECT_THROW(aa::ssim(cv::Mat(), cv::Mat()), std::runtime_error);
}

TEST(MsSsim, UsesTheScalesThatFit) {
  const cv::Mat a = scene(64, 64);
  const cv::Mat b = with_noise(a, 0.05, 2);
  const auto r = aa::ms_ssim(a, b);
  EXPECT_EQ(r.scales, 3);  // 64, 32, 16 px; 8 px is below the 11 px window
  EXPECT_GT(r.value, 0.0);
  EXPECT_LT(r.value, 1.0);
}

TEST(Ssim, AutoRangeUsesBothImages) {
  const cv::Mat a(20, 20, CV_64FC1, cv::Scalar(0.2)), b(20, 20, CV_64FC1, cv::Scalar(3.0));
  EXPECT_DOUBLE_EQ(aa::auto_data_range(a, b), 2.8);
  EXPECT_DOUBLE_EQ(aa::auto_data_range(a, a), 1.0);
}
