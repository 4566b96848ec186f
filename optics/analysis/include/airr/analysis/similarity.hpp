#pragma once

#include <opencv2/core.hpp>

namespace airr::analysis {

struct ssim_params {
  int window = 11;     // Gaussian window size in pixels (odd)
  double sigma = 1.5;  // Gaussian window standard deviation in pixels
  double k1 = 0.01;
  double k2 = 0.03;
  // Dynamic range L of the pixel values; <= 0 takes max - min over both images (1 if that is 0).
  double data_range = 0;
};

struct ms_ssim_result {
  double value = 0;
  int scales = 0;  // scales used; fewer than 5 when the images are too small for all five
};

// Dynamic range used when ssim_params::data_range is not set.
double auto_data_range(const cv::Mat& a, const cv::Mat& b);

// Mean SSIM over the positions where the whole window fits. Inputs are single-channel images of
// the same size (any depth); throws std::runtime_error otherwise.
double ssim(const cv::Mat& a, const cv::Mat& b, const ssim_params& params = {});

// Multi-scale SSIM with the five standard scale weights, renormalised over the scales that fit.
ms_ssim_result ms_ssim(const cv::Mat& a, const cv::Mat& b, const ssim_params& params = {});

}  // namespace airr::analysis
