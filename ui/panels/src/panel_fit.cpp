// The fit window: a sheet preset from measurements (the same fit as `airr fit`) or predicted from
// the sheet's model (as `airr predict-preset`), run in the background, saved as a preset file and
// applied to the scene.
#include <algorithm>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/core/assets.hpp"
#include "airr/models/preset.hpp"
#include "airr/ui/panels/panels.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

static void start_fit(studio& st) {
  try {
    st.fit_job_ = std::make_unique<fit_job>(st.fit_dir);
    st.fit_saved_path.clear();
    st.status = "fitting " + st.fit_dir;
  } catch (const std::exception& e) {
    st.fit_job_.reset();
    st.fit_error = e.what();
  }
}

void start_preset_prediction(studio& st) {
  const retro_model_params& model = st.doc.sheet().model;
  if (model.type == "sinc_shift") {
    st.fit_error =
        "the sheet's model is the sinc-shift model already; choose a sheet model to predict from "
        "(prism_sheet, bead_sheet, ...) in the layout panel";
    return;
  }
  try {
    const sheet_description sheet{.name = "predicted " + model.type,
                                  .note = "the designer's sheet model, predicted in the fit window",
                                  .model = model,
                                  .base_dir = st.doc.base_dir};
    // Each prediction's measurements in a folder of their own, as its preset's provenance names it.
    const fs::path predictions = fs::path(config_dir()) / "predictions";
    fs::path bench = predictions / (model.type + "_bench");
    for (int n = 2; fs::exists(bench); ++n) bench = predictions / (model.type + "_bench-" + std::to_string(n));
    const std::string data_dir = bench.string();
    analysis::prediction_params p;
    p.synthesis.samples = st.predict_samples;
    p.fit.psf_samples = std::max<std::uint64_t>(1000, st.predict_samples / 5);
    st.fit_job_ = std::make_unique<fit_job>(sheet, data_dir, p);
    st.fit_saved_path.clear();
    st.fit_dir = data_dir;
    st.status = "predicting a preset for the sheet's " + model.type + " model";
  } catch (const std::exception& e) {
    st.fit_job_.reset();
    st.fit_error = e.what();
  }
}

void apply_fitted_preset(studio& st, const sheet_preset& preset) {
  if (st.fit_saved_path.empty()) {
    const fs::path dir = fs::path(config_dir()) / "presets";
    std::error_code ec;
    fs::create_directories(dir, ec);
    std::string name = preset.name.empty() ? "fitted" : preset.name;
    for (char& c : name) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    }
    // A new file: a scene saved earlier may name a preset of the same name.
    fs::path path = dir / (name + ".json");
    for (int n = 2; fs::exists(path); ++n) path = dir / (name + "-" + std::to_string(n) + ".json");
    st.fit_saved_path = path.string();
    save_preset(preset, st.fit_saved_path);
  }
  auto& m = st.doc.sheet().model;
  m = {.type = "sinc_shift", .values = {}};
  set_model_value(m, "preset", st.fit_saved_path);
  st.status = "the scene now uses the fitted preset " + st.fit_saved_path;
}

void request_fit_preset_save(studio& st) {
  st.dialog.request(file_purpose::save_preset, true, "Save fitted preset", st.fit_dir, {".json"}, "preset.json");
}

void save_fitted_preset(studio& st, const std::string& path) {
  if (!st.fit_job_) return;
  const auto r = st.fit_job_->result();
  if (!r) return;
  try {
    save_preset(r->preset, path);
    st.fit_saved_path = fs::absolute(path).string();
    st.status = "saved preset " + path;
  } catch (const std::exception& e) {
    st.status = std::string("cannot save the preset: ") + e.what();
  }
}

void draw_fit_window(studio& st) {
  if (!st.show_fit) return;
  ImGui::SetNextWindowSize(ImVec2(34 * ImGui::GetFontSize(), 30 * ImGui::GetFontSize()), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Fit a sheet preset", &st.show_fit)) {
    ImGui::End();
    return;
  }
  ImGui::TextWrapped(
      "Fits a and mu per tilt and the corner size c from measured MTF curves or slanted-edge photos "
      "(a directory with fit.json; see assets/fit_example/README.md).");
  ImGui::SetNextItemWidth(-6 * ImGui::GetFontSize());
  ImGui::InputText("data", &st.fit_dir);
  ImGui::SameLine();
  if (ImGui::Button("Browse")) {
    st.dialog.request(file_purpose::choose_fit_data, false, "Choose fit.json",
                      st.fit_dir.empty() ? asset_dir() : st.fit_dir, {".json"});
  }
  const bool running = st.fit_job_ && st.fit_job_->running();
  if (running) {
    const auto p = st.fit_job_->progress();
    ImGui::ProgressBar(float(p.fraction), ImVec2(-6 * ImGui::GetFontSize(), 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) st.fit_job_->cancel();
    ImGui::Text("%s  (about %.0f s left)", p.stage.c_str(), p.eta_seconds);
  } else {
    if (ImGui::Button("Run fit")) {
      st.fit_error.clear();
      start_fit(st);
    }
    ImGui::SameLine();
    if (ImGui::Button("Use the example data")) st.fit_dir = asset_dir() + "/fit_example";
    ImGui::Separator();
    ImGui::TextWrapped(
        "Or predict a preset from the sheet's own model (a prism or bead sheet traced as geometry): the "
        "model is measured on the simulated bench and the preset fitted to it, as `airr predict-preset` does.");
    const std::string& type = st.doc.sheet().model.type;
    ImGui::BeginDisabled(type == "sinc_shift");
    if (ImGui::Button(("Predict a preset for the " + type + " model").c_str())) {
      st.fit_error.clear();
      start_preset_prediction(st);
    }
    ImGui::EndDisabled();
    int samples_k = int(st.predict_samples / 1000);
    ImGui::SetNextItemWidth(8 * ImGui::GetFontSize());
    if (ImGui::InputInt("thousand samples per measurement", &samples_k, 100, 1000))
      st.predict_samples = std::uint64_t(std::clamp(samples_k, 10, 100000)) * 1000;
  }
  if (!st.fit_error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", st.fit_error.c_str());
  if (st.fit_job_ && !running) {
    if (const std::string e = st.fit_job_->error(); !e.empty())
      ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", e.c_str());
  }
  const auto result = st.fit_job_ && !running ? st.fit_job_->result() : std::nullopt;
  if (result) {
    const sheet_preset& p = result->preset;
    ImGui::Separator();
    ImGui::Text("%s: c = %.5g mm, R = %.0f mm", p.name.c_str(), p.c_mm, p.reference_distance_mm);
    if (ImGui::BeginTable("fitted", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
      ImGui::TableSetupColumn("tilt (deg)");
      ImGui::TableSetupColumn("a (1/mm)");
      ImGui::TableSetupColumn("mu");
      ImGui::TableHeadersRow();
      const std::size_t rows = std::max<std::size_t>(1, p.theta_deg.size());
      for (std::size_t i = 0; i < rows; ++i) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        if (p.theta_deg.empty())
          ImGui::TextUnformatted("all");
        else
          ImGui::Text("%.1f", p.theta_deg[i]);
        ImGui::TableNextColumn();
        ImGui::Text("%.5g", p.a_per_mm[std::min(i, p.a_per_mm.size() - 1)]);
        ImGui::TableNextColumn();
        ImGui::Text("%.5g", p.mu[std::min(i, p.mu.size() - 1)]);
      }
      ImGui::EndTable();
    }
    if (ImGui::TreeNode("Losses and inputs")) {
      ImGui::TextUnformatted(analysis::to_json(result->report).dump(2).c_str());
      ImGui::TreePop();
    }
    if (ImGui::Button("Save preset...")) request_fit_preset_save(st);
    ImGui::SameLine();
    if (ImGui::Button("Apply to the scene")) {
      try {
        apply_fitted_preset(st, p);
      } catch (const std::exception& e) {
        st.status = std::string("cannot apply: ") + e.what();
      }
    }
    if (!st.fit_saved_path.empty()) ImGui::TextDisabled("preset file: %s", st.fit_saved_path.c_str());
  }
  ImGui::End();
}

}  // namespace airr::ui
