// Reading EXR/PNG/TIFF/JPEG as linear luminance with the pixel-size attribute.
#include <cmath>

#include <gtest/gtest.h>

#include "airr/analysis/edge_file.hpp"
#include "airr/analysis/image_read.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/color.hpp"
#include "synthetic_edge.hpp"
#include "test_files.hpp"

namespace aa = airr::analysis;
namespace at = airr::analysis::testing;

TEST(SrgbCurve, KnownValues) {
  EXPECT_DOUBLE_EQ(airr::srgb_decode(0.0), 0.0);
  EXPECT_NEAR(airr::srgb_decode(1.0), 1.0, 1e-12);
  EXPECT_NEAR(airr::srgb_decode(0.5), 0.21404114, 1e-8);
  EXPECT_NEAR(airr::srgb_decode(0.04), 0.04 / 12.92, 1e-12);
  for (double v : {0.001, 0.01, 0.2, 0.7, 0.99}) EXPECT_NEAR(airr::srgb_encode(airr::srgb_decode(v)), v, 1e-12);
}

TEST(SrgbCurve, EightBitCodesMatchTheCurveRounded) {
  // Every value on a fine ramp (and beyond [0, 1]) gets the code the curve itself rounds to.
  int mismatches = 0;
  for (int i = -1000; i <= 1100000; ++i) {
    const float x = float(i) / 1e6f;
    const long want = std::lround(255.0 * airr::srgb_encode(std::clamp(double(x), 0.0, 1.0)));
    const int got = airr::srgb_encode_8bit(x);
    EXPECT_LE(std::abs(got - want), 1) << x;
    if (got != want) ++mismatches;
  }
  EXPECT_LE(mismatches, 10);  // only values within float rounding of a boundary
  EXPECT_EQ(airr::srgb_encode_8bit(std::nanf("")), 0);
  EXPECT_EQ(airr::srgb_encode_8bit(1e30f), 255);
}

TEST(ImageRead, ExrIsLinearWithStringPixelSize) {
  at::scratch_dir dir("read");
  cv::Mat px(8, 10, CV_64FC1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 10; ++x) px.at<double>(y, x) = 0.1 * x + 2.0 * y;  // values above 1 stay
  const auto path = dir / "linear.exr";
  at::write_exr(path, px, at::attribute_kind::string, "0.0625");
  const auto img = aa::read_linear_image(path);
  EXPECT_FALSE(img.srgb_decoded);
  ASSERT_TRUE(img.mm_per_pixel);
  EXPECT_DOUBLE_EQ(*img.mm_per_pixel, 0.0625);
  ASSERT_EQ(img.luminance.size(), cv::Size(10, 8));
  EXPECT_EQ(img.luminance.type(), CV_64FC1);
  EXPECT_NEAR(img.luminance.at<double>(3, 7), float(0.7 + 6.0), 1e-6);
}

TEST(ImageRead, ExrFloatPixelSizeAndMissingAttribute) {
  at::scratch_dir dir("read");
  const cv::Mat px(4, 4, CV_64FC1, cv::Scalar(0.5));
  at::write_exr(dir / "float_attr.exr", px, at::attribute_kind::floating, "0.125");
  const auto a = aa::read_linear_image(dir / "float_attr.exr");
  ASSERT_TRUE(a.mm_per_pixel);
  EXPECT_DOUBLE_EQ(*a.mm_per_pixel, 0.125);
  at::write_exr(dir / "no_attr.exr", px);
  EXPECT_FALSE(aa::read_linear_image(dir / "no_attr.exr").mm_per_pixel);
}

TEST(ImageRead, ColourBecomesRec709Luminance) {
  at::scratch_dir dir("read");
  cv::Mat px(2, 3, CV_64FC3, cv::Scalar(0, 0, 0));
  px.at<cv::Vec3d>(0, 0) = {1, 0, 0};  // RGB order in the file
  px.at<cv::Vec3d>(0, 1) = {0, 1, 0};
  px.at<cv::Vec3d>(0, 2) = {0, 0, 1};
  px.at<cv::Vec3d>(1, 0) = {0.5, 0.5, 0.5};
  at::write_exr(dir / "rgb.exr", px);
  const auto img = aa::read_linear_image(dir / "rgb.exr");
  EXPECT_NEAR(img.luminance.at<double>(0, 0), 0.2126, 1e-6);
  EXPECT_NEAR(img.luminance.at<double>(0, 1), 0.7152, 1e-6);
  EXPECT_NEAR(img.luminance.at<double>(0, 2), 0.0722, 1e-6);
  EXPECT_NEAR(img.luminance.at<double>(1, 0), 0.5, 1e-6);
  EXPECT_NEAR(img.rgb.at<cv::Vec3d>(0, 0)[0], 1.0, 1e-6);
}

TEST(ImageRead, EightBitPngIsSrgbDecodedUnlessLinearInput) {
  at::scratch_dir dir("read");
  cv::Mat codes(4, 4, CV_8UC1, cv::Scalar(128));
  codes.at<unsigned char>(0, 0) = 255;
  const auto path = dir / "grey8.png";
  at::write_coded(path, codes, "0.04");
  const auto srgb = aa::read_linear_image(path);
  EXPECT_TRUE(srgb.srgb_decoded);
  EXPECT_NEAR(srgb.luminance.at<double>(1, 1), airr::srgb_decode(128.0 / 255.0), 1e-6);
  EXPECT_NEAR(srgb.luminance.at<double>(0, 0), 1.0, 1e-6);
  ASSERT_TRUE(srgb.mm_per_pixel);
  EXPECT_DOUBLE_EQ(*srgb.mm_per_pixel, 0.04);
  const auto linear = aa::read_linear_image(path, {.encoding = airr::image_encoding::linear});
  EXPECT_FALSE(linear.srgb_decoded);
  EXPECT_NEAR(linear.luminance.at<double>(1, 1), 128.0 / 255.0, 1e-6);
}

// The loader's rule: 16-bit files are linear; --srgb-input (image_encoding::srgb) decodes them.
TEST(ImageRead, SixteenBitPngAndTiffAreLinearUnlessSrgbIsAsked) {
  at::scratch_dir dir("read");
  cv::Mat codes(4, 4, CV_16UC3, cv::Scalar(40000, 40000, 40000));
  for (const char* name : {"grey16.png", "grey16.tif"}) {
    at::write_coded(dir / name, codes, "0.5");
    const auto img = aa::read_linear_image(dir / name);
    EXPECT_FALSE(img.srgb_decoded) << name;
    EXPECT_NEAR(img.luminance.at<double>(2, 2), 40000.0 / 65535.0, 1e-5) << name;
    const auto srgb = aa::read_linear_image(dir / name, {.encoding = airr::image_encoding::srgb});
    EXPECT_TRUE(srgb.srgb_decoded) << name;
    EXPECT_NEAR(srgb.luminance.at<double>(2, 2), airr::srgb_decode(40000.0 / 65535.0), 1e-5) << name;
  }
  // PNG keeps the pixel size as a text chunk (TIFF has no place for it).
  const auto png = aa::read_linear_image(dir / "grey16.png");
  ASSERT_TRUE(png.mm_per_pixel);
  EXPECT_DOUBLE_EQ(*png.mm_per_pixel, 0.5);
}

TEST(ImageRead, JpegIsDecodedApproximately) {
  at::scratch_dir dir("read");
  cv::Mat codes(32, 32, CV_8UC3, cv::Scalar(200, 200, 200));
  at::write_coded(dir / "grey.jpg", codes);
  const auto img = aa::read_linear_image(dir / "grey.jpg");
  EXPECT_NEAR(img.luminance.at<double>(16, 16), airr::srgb_decode(200.0 / 255.0), 0.01);
}

TEST(ImageRead, SrgbPngEdgeMeasuresLikeTheLinearEdge) {
  // An sRGB-encoded 16-bit PNG of an edge must give the linear edge's MTF after decoding.
  const aa::image_read_params srgb{.encoding = airr::image_encoding::srgb};
  at::scratch_dir dir("read");
  at::synthetic_edge_params p;
  p.sigma_px = 1.5;
  const cv::Mat linear = at::make_slanted_edge(p);
  cv::Mat codes(linear.size(), CV_16UC1);
  for (int y = 0; y < linear.rows; ++y)
    for (int x = 0; x < linear.cols; ++x)
      codes.at<unsigned short>(y, x) =
          static_cast<unsigned short>(std::lround(65535.0 * airr::srgb_encode(linear.at<double>(y, x))));
  const auto path = dir / "edge16.png";
  at::write_coded(path, codes, "0.1");
  const auto result = aa::measure_edge_file(path, {}, srgb);
  const auto m50 = aa::mtf50(result.curve, *result.image.mm_per_pixel);
  ASSERT_TRUE(m50);
  const double truth = at::analytic_mtf50(1.5, false);
  EXPECT_NEAR(m50->cycles_per_pixel, truth, 0.01 * truth);
  EXPECT_NEAR(m50->lp_per_mm, truth / 0.1, 0.01 * truth / 0.1);
  // Without decoding, the sRGB curve distorts the edge and the MTF50 moves.
  const auto raw = aa::measure_edge_file(path, {}, {.encoding = airr::image_encoding::linear});
  EXPECT_GT(std::abs(aa::mtf50(raw.curve)->cycles_per_pixel - truth), 0.01 * truth);
}
