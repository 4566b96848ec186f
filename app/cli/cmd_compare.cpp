// airr compare A B [--lpips-model FILE.onnx] [--linear-input] [--data-range L]
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/lpips.hpp"
#include "airr/analysis/similarity.hpp"
#include "cli/commands.hpp"

void add_compare_command(CLI::App& app) {
  struct options {
    std::string a, b, lpips_model;
    airr::image_encoding encoding = airr::image_encoding::automatic;
    double data_range = 0;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("compare",
                                 "Score the similarity of two images of the same size "
                                 "(SSIM and MS-SSIM on luminance; LPIPS with a model)");
  cmd->add_option("a", opt->a, "First image (EXR, PNG, TIFF, JPEG)")->required();
  cmd->add_option("b", opt->b, "Second image, same size")->required();
  cmd->add_option("--lpips-model", opt->lpips_model,
                  "ONNX LPIPS network taking two 1x3xHxW inputs in [-1, 1] (sRGB-encoded)");
  add_image_encoding_flags(cmd, opt->encoding);
  cmd->add_option("--data-range", opt->data_range,
                  "Dynamic range L of the linear luminance for SSIM; default: max - min over both images");
  cmd->callback([opt] {
    if (opt->data_range < 0) throw std::runtime_error("--data-range must be positive");
    const airr::analysis::image_read_params read{.encoding = opt->encoding};
    const auto a = airr::analysis::read_linear_image(opt->a, read);
    const auto b = airr::analysis::read_linear_image(opt->b, read);
    if (a.luminance.size() != b.luminance.size())
      throw std::runtime_error(opt->a + " and " + opt->b + " differ in size: " + std::to_string(a.luminance.cols) +
                               "x" + std::to_string(a.luminance.rows) + " vs " + std::to_string(b.luminance.cols) +
                               "x" + std::to_string(b.luminance.rows));
    airr::analysis::ssim_params params;
    params.data_range =
        opt->data_range > 0 ? opt->data_range : airr::analysis::auto_data_range(a.luminance, b.luminance);
    const double s = airr::analysis::ssim(a.luminance, b.luminance, params);
    const auto ms = airr::analysis::ms_ssim(a.luminance, b.luminance, params);
    std::optional<airr::analysis::lpips_result> lp;
    if (!opt->lpips_model.empty()) lp = airr::analysis::lpips(a.rgb, b.rgb, opt->lpips_model);

    std::printf("images: %s vs %s (%dx%d)\n", opt->a.c_str(), opt->b.c_str(), a.luminance.cols, a.luminance.rows);
    std::printf("SSIM (linear luminance, Gaussian window 11, sigma 1.5, data range %.6g): %.6f\n", params.data_range,
                s);
    std::printf("MS-SSIM (%d scale%s): %.6f\n", ms.scales, ms.scales == 1 ? "" : "s", ms.value);
    if (lp) {
      std::string note;
      if (lp->resized)
        note =
            ", images resized to " + std::to_string(lp->input_size.width) + "x" + std::to_string(lp->input_size.height);
      std::printf("LPIPS (%s%s): %.6f\n", opt->lpips_model.c_str(), note.c_str(), lp->value);
    }
  });
}
