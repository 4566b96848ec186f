// Faults: a save killed at any moment leaves the old file or the new one, never a torn one; a
// full disk and a read-only folder give a clear error while the designer keeps the scene and a
// recovery copy; files deleted or replaced under the designer do not bring it down.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <thread>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/ui/studio/studio.hpp"
#include "test_helpers.hpp"

using namespace airr;
namespace fs = std::filesystem;

namespace {

// Writes variant 0 or 1 of one kind of file to a path.
using save_function = std::function<void(int variant, const std::string& path)>;

scene scene_variant(int variant) {
  scene s = test::uniform_source_scene(50, 32);
  s.source.intensity = variant ? 2.0 : 1.0;
  // Enough props to make the file tens of kilobytes, so that kills land inside the write.
  for (int i = 0; i < 200; ++i) {
    prop_params p;
    p.name = "baffle " + std::to_string(i);
    p.mesh = asset_dir() + "/models/corner_cube.gltf";
    p.scale = 0.01;
    p.pose.center_mm = {double(i), -300.0 - variant, 0.0};
    s.props.push_back(p);
  }
  return s;
}

save_function scene_saver() {
  return [](int v, const std::string& path) { save_scene(scene_variant(v), path); };
}

save_function preset_saver() {
  return [](int v, const std::string& path) {
    sheet_preset p = load_preset("rf-ay");
    p.name = v ? "second" : "first";
    p.theta_deg.clear();
    p.a_per_mm.clear();
    p.mu.clear();
    for (int i = 0; i < 4000; ++i) {
      p.theta_deg.push_back(i * 0.01);
      p.a_per_mm.push_back(10.0 + v + i * 1e-4);
      p.mu.push_back(0.3);
    }
    save_preset(p, path);
  };
}

save_function export_saver() {
  return [](int v, const std::string& path) {
    scene s = test::uniform_source_scene(50, 32);
    s.source.intensity = v ? 2.0 : 1.0;
    prop_params p;
    p.name = "cube";
    p.mesh = asset_dir() + "/models/corner_cube.gltf";
    p.scale = 0.02;
    s.props.push_back(p);
    export_gltf_layout(s, path);
  };
}

// What a file holds ("torn: ..." when it cannot be read at all).
std::string content_of(const std::string& path) {
  try {
    return read_text_file(path);
  } catch (const std::exception& e) {
    return std::string("torn: ") + e.what();
  }
}

// Everything in `dir` but the named files: what an interrupted save left behind.
std::vector<fs::path> leftovers(const fs::path& dir, const std::vector<std::string>& expected) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (std::find(expected.begin(), expected.end(), name) == expected.end()) out.push_back(e.path());
  }
  return out;
}

struct kill_counts {
  int rounds = 0;
  int complete = 0;   // the file is exactly one of the two versions
  int torn = 0;       // anything else
  int mid_write = 0;  // the kill left a temporary file: it landed inside a save
};

// A child process saves the two versions into one file, alternately and without end; it is
// killed after a random delay (up to three saves' time), and what the file holds is classified.
// At least `min_rounds` rounds, and more until `mid_writes` kills have landed inside a save (a
// loaded machine starts the child late, so fewer land there), up to `max_rounds`.
kill_counts kill_during_saves(const test::temp_dir& dir, const std::string& name, const save_function& save,
                              int min_rounds, int mid_writes, int max_rounds) {
  const std::string target = dir.file(name), first = dir.file("first." + name), second = dir.file("second." + name);
  save(0, first);
  save(1, second);
  const std::string versions[2] = {content_of(first), content_of(second)};
  EXPECT_NE(versions[0], versions[1]);
  const auto t0 = std::chrono::steady_clock::now();
  save(1, target);
  const double save_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();

  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> delay_us(0.0, 3.0 * save_us + 200.0);
  kill_counts counts;
  for (; counts.rounds < max_rounds && (counts.rounds < min_rounds || counts.mid_write < mid_writes); ++counts.rounds) {
    save(0, target);
    const pid_t child = fork();
    if (child == 0) {
      for (int i = 1;; ++i) save(i & 1, target);
    }
    std::this_thread::sleep_for(std::chrono::duration<double, std::micro>(delay_us(rng)));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    const std::string now = content_of(target);
    if (now == versions[0] || now == versions[1])
      ++counts.complete;
    else
      ++counts.torn;
    const auto left = leftovers(dir.path, {name, "first." + name, "second." + name});
    if (!left.empty()) ++counts.mid_write;
    for (const auto& p : left) fs::remove(p);
  }
  return counts;
}

void expect_never_torn(const std::string& name, const save_function& save) {
  test::temp_dir dir;
  const int mid_writes = 5;
  const kill_counts c = kill_during_saves(dir, name, save, 100, mid_writes, 2000);
  EXPECT_EQ(c.torn, 0) << name;
  EXPECT_EQ(c.complete, c.rounds) << name;
  // The kills did land inside saves (else this would test nothing).
  EXPECT_GE(c.mid_write, mid_writes) << name << ": only " << c.mid_write << " of " << c.rounds
                                     << " kills landed inside a save";
  std::printf("%s: %d kills, %d inside a save, %d torn\n", name.c_str(), c.rounds, c.mid_write, c.torn);
}

// Runs `body` in a child process; what it returns, and how the child ended.
struct child_result {
  std::string report;
  bool exited_cleanly = false;
};
child_result in_child(const std::function<std::string()>& body) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return {"pipe failed", false};
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_fds[0]);
    const std::string report = body();
    (void)!write(pipe_fds[1], report.data(), report.size());
    _exit(0);
  }
  close(pipe_fds[1]);
  child_result r;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) r.report.append(buffer, std::size_t(n));
  close(pipe_fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  r.exited_cleanly = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return r;
}

// Runs `save` in a child process limited to `max_bytes` per file (as `ulimit -f` does, with the
// signal ignored as the programs do); returns the error it reported (empty: none).
std::string error_past_file_size_limit(const save_function& save, const std::string& path, rlim_t max_bytes) {
  const child_result r = in_child([&] {
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{max_bytes, max_bytes};
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
      save(1, path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  });
  EXPECT_TRUE(r.exited_cleanly) << "the save crashed past the file-size limit";
  return r.report;
}

}  // namespace

TEST(Faults, SceneSaveKilledAtRandomIsNeverTorn) { expect_never_torn("scene.json", scene_saver()); }
TEST(Faults, PresetSaveKilledAtRandomIsNeverTorn) { expect_never_torn("preset.json", preset_saver()); }
TEST(Faults, GltfExportKilledAtRandomIsNeverTorn) { expect_never_torn("layout.glb", export_saver()); }

// A full disk (a file-size limit): every writer says which file and why, and the file it would
// have replaced is untouched, with nothing left beside it. (Images, whose encoder keeps a thread
// pool that a forked child cannot use, are tried through the command line in
// test_resource_limits.cpp.)
TEST(Faults, FullDiskGivesAClearErrorAndLeavesTheOldFile) {
  const std::vector<std::pair<std::string, save_function>> writers = {
      {"scene.json", scene_saver()}, {"preset.json", preset_saver()}, {"layout.glb", export_saver()}};
  for (const auto& [name, save] : writers) {
    test::temp_dir dir;
    save(0, dir.file(name));
    const std::string before = content_of(dir.file(name));
    const std::string error = error_past_file_size_limit(save, dir.file(name), 1024);
    EXPECT_NE(error.find(dir.file(name)), std::string::npos) << name << ": " << error;
    if (name.find(".json") != std::string::npos || name.find(".glb") != std::string::npos) {
      EXPECT_NE(error.find(std::strerror(EFBIG)), std::string::npos) << name << ": " << error;
    }
    EXPECT_EQ(content_of(dir.file(name)), before) << name;
    EXPECT_TRUE(leftovers(dir.path, {name}).empty()) << name;
  }
}

// The designer, told to save where it cannot (the disk full), keeps the scene open and unsaved.
TEST(Faults, DesignerSaveOnAFullDiskKeepsTheScene) {
  test::temp_dir dir;
  setenv("XDG_STATE_HOME", dir.file("state").c_str(), 1);
  ui::studio st;
  st.doc = scene_variant(0);
  st.saved = st.doc;
  st.doc.source.intensity = 1.75;
  const scene edited = st.doc;
  signal(SIGXFSZ, SIG_IGN);
  rlimit saved_limit{};
  getrlimit(RLIMIT_FSIZE, &saved_limit);
  const rlimit small{1024, saved_limit.rlim_max};
  setrlimit(RLIMIT_FSIZE, &small);
  const bool saved = ui::studio_save(st, dir.file("scene.json"));
  setrlimit(RLIMIT_FSIZE, &saved_limit);
  EXPECT_FALSE(saved);
  EXPECT_NE(st.status.find("cannot save: " + dir.file("scene.json")), std::string::npos) << st.status;
  EXPECT_NE(st.status.find(std::strerror(EFBIG)), std::string::npos) << st.status;
  EXPECT_NE(st.status.find("unsaved"), std::string::npos) << st.status;
  EXPECT_TRUE(st.doc == edited);
  EXPECT_TRUE(ui::studio_dirty(st));
  EXPECT_EQ(st.doc_path, "");
  unsetenv("XDG_STATE_HOME");
}

// A read-only folder: the save fails naming the file and the reason; the designer keeps the scene
// and writes a recovery copy, and says where it is. (As root, the child drops to "nobody" first,
// since root writes anywhere.)
TEST(Faults, DesignerSaveIntoAReadOnlyFolderKeepsTheSceneAndSaysWhereTheRecoveryCopyIs) {
  test::temp_dir dir;
  fs::permissions(dir.path, fs::perms::all);
  const std::string folder = dir.file("readonly"), state = dir.file("state");
  fs::create_directories(folder);
  fs::create_directories(state);
  save_scene(scene_variant(0), folder + "/scene.json");
  const std::string before = read_text_file(folder + "/scene.json");
  fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(state, fs::perms::all);
  setenv("XDG_STATE_HOME", state.c_str(), 1);

  const child_result r = in_child([&] {
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) return std::string("cannot drop root");
    ui::studio st;
    st.doc = scene_variant(0);
    st.saved = st.doc;
    st.doc.source.intensity = 1.75;
    const bool saved = ui::studio_save(st, folder + "/scene.json");
    return std::string(saved ? "saved" : "refused") + (ui::studio_dirty(st) ? " dirty " : " clean ") +
           number_text(st.doc.source.intensity) + "\n" + st.status;
  });
  unsetenv("XDG_STATE_HOME");
  ASSERT_TRUE(r.exited_cleanly);
  const std::string& report = r.report;

  EXPECT_EQ(report.rfind("refused dirty 1.75", 0), 0u) << report;
  EXPECT_NE(report.find("cannot save: " + folder + "/scene.json"), std::string::npos) << report;
  EXPECT_NE(report.find(std::strerror(EACCES)), std::string::npos) << report;
  const std::string recovery = state + "/airr-studio/recovery.json";
  EXPECT_NE(report.find("with a recovery copy in " + recovery), std::string::npos) << report;
  ASSERT_TRUE(fs::exists(recovery));
  EXPECT_DOUBLE_EQ(read_json_file(recovery)["scene"]["source"]["intensity"].get<double>(), 1.75);
  EXPECT_EQ(read_text_file(folder + "/scene.json"), before);
  fs::permissions(folder, fs::perms::all);
}

// The source image and the sheet's preset deleted, then replaced by garbage, then by good files,
// while the designer shows them: each edit is refused naming the file, the session keeps its
// last good layout, and a good file is taken up again.
TEST(Faults, FilesDeletedOrReplacedUnderTheDesignerAreNamedNotFatal) {
  test::temp_dir dir;
  const std::string chart = dir.file("chart.png"), preset = dir.file("sheet.json");
  fs::copy_file(asset_dir() + "/charts/test_chart.png", chart);
  fs::copy_file(asset_dir() + "/presets/rf-ay.json", preset);
  scene s = test::uniform_source_scene(50, 32);
  s.source.image = chart;
  s.sheet().model.type = "sinc_shift";
  set_model_value(s.sheet().model, "preset", preset);

  ui::studio st;
  st.keep_recovery = false;
  st.session_options = {.threads = 1, .target_spp = 4};
  ui::studio_start(st, s, "");
  double now = 1;
  const auto edit = [&] {
    st.doc.source.intensity += 0.125;
    ui::studio_apply_edits(st, now += 1);
  };
  // Why an edit was refused: the designer's check, or the session's when it loads the files.
  const auto refusal = [&] { return st.doc_error.empty() ? st.session->snapshot().error : st.doc_error; };
  const auto wait_for = [&](const std::function<bool()>& done) {
    for (int i = 0; i < 200 && !done(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
  };
  const auto expect_refused_naming = [&](const std::string& file, const char* what) {
    edit();
    wait_for([&] { return refusal().find(file) != std::string::npos; });
    EXPECT_NE(refusal().find(file), std::string::npos) << what << ": " << refusal();
  };
  const auto expect_taken_up = [&](const char* what) {
    edit();
    wait_for([&] { return refusal().empty(); });
    EXPECT_EQ(refusal(), "") << what;
  };

  fs::remove(chart);
  expect_refused_naming(chart, "image deleted");
  std::ofstream(chart, std::ios::binary) << "\x89PNG\r\n\x1a\n not really a PNG";
  expect_refused_naming(chart, "image replaced by garbage");
  fs::copy_file(asset_dir() + "/charts/slanted_edge.png", chart, fs::copy_options::overwrite_existing);
  expect_taken_up("image restored");
  const std::uint64_t good_generation = st.generation;

  fs::remove(preset);
  expect_refused_naming(preset, "preset deleted");
  std::ofstream(preset) << "{\"format\": \"airr-preset\", ";
  expect_refused_naming(preset, "preset replaced by broken JSON");
  fs::copy_file(asset_dir() + "/presets/rf-an.json", preset, fs::copy_options::overwrite_existing);
  expect_taken_up("preset restored");
  EXPECT_GT(st.generation, good_generation);

  // The session still renders.
  for (int i = 0; i < 100 && st.session->snapshot().spp == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_GT(st.session->snapshot().spp, 0u);
  EXPECT_EQ(st.session->snapshot().error, "");
  st.session->stop();
}

namespace {

// Holds this process's address space to what it uses now and `more` bytes besides, for a test's
// length.
struct address_space_limit {
  rlimit before{};
  explicit address_space_limit(std::uint64_t more) {
    ::getrlimit(RLIMIT_AS, &before);
    std::ifstream statm("/proc/self/statm");
    std::uint64_t pages = 0;
    statm >> pages;
    rlimit limit = before;
    limit.rlim_cur = rlim_t(pages * std::uint64_t(::sysconf(_SC_PAGESIZE)) + more);
    ::setrlimit(RLIMIT_AS, &limit);
  }
  ~address_space_limit() { ::setrlimit(RLIMIT_AS, &before); }
};

}  // namespace

// Under an address-space limit, the designer refuses an edit whose render would not fit (its
// memory check), and a session made to take one anyway says it ran out of memory: both keep the
// last image, and the next edit that fits renders.
TEST(Faults, AnEditBeyondTheProcesssMemoryIsRefusedAndTheLastImageStays) {
  AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED();
  const scene small = test::uniform_source_scene(50, 32);
  ui::studio st;
  st.keep_recovery = false;
  st.session_options = {.threads = 1, .target_spp = 4};
  ui::studio_start(st, small, "");
  const auto wait_for = [&](const std::function<bool()>& done) {
    for (int i = 0; i < 400 && !done(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
  };
  wait_for([&] { return st.session->snapshot().spp >= 4; });
  ASSERT_GE(st.session->snapshot().spp, 4u);
  // 8192 x 4096 takes four sums of 805 MB each before its first sample: with 1 GB to spare, the
  // second fails even where the address space read here overstates what stays mapped.
  const address_space_limit limit(1'000'000'000ULL);

  const std::uint64_t generation = st.generation;
  st.doc.observer.width = 8192;
  st.doc.observer.height = 4096;
  ui::studio_apply_edits(st, 2);
  EXPECT_NE(st.doc_error.find("render: 8192 x 4096 needs about"), std::string::npos) << st.doc_error;
  EXPECT_NE(st.doc_error.find("ulimit -v"), std::string::npos) << st.doc_error;
  EXPECT_EQ(st.generation, generation);
  EXPECT_EQ(st.session->snapshot().width, 32);

  // Past the check: the session's worker fails to allocate, says so, and waits for the next edit.
  scene big = small;
  big.observer.width = 8192;
  big.observer.height = 4096;
  const std::uint64_t refused = st.session->edit(big);
  wait_for([&] { return !st.session->snapshot().error.empty(); });
  const render_snapshot failed = st.session->snapshot();
  EXPECT_NE(failed.error.find("render: out of memory (an allocation failed"), std::string::npos) << failed.error;
  EXPECT_GE(failed.generation, refused);

  scene again = small;
  again.observer.width = 40;
  const std::uint64_t good = st.session->edit(again);
  wait_for([&] { return st.session->snapshot().generation == good && st.session->snapshot().spp >= 4; });
  EXPECT_EQ(st.session->snapshot().error, "");
  EXPECT_EQ(st.session->snapshot().width, 40);
  st.session->stop();
}

// Under an address-space limit, the designer's background jobs end in one line saying what ran out:
// a tolerance run refused by its memory check before its first layout, and a job whose allocation
// fails past any check (a 4 GB block with 1 GB to spare).
TEST(Faults, BackgroundJobsOutOfMemorySayWhatRanOut) {
  AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED();
  const scene base = load_scene(default_scene_path());
  const design_spec spec = parse_design_spec(
      R"({"format": "airr-design", "version": 1, "eyes_mm": [[0, 0, 450]],
          "objectives": [{"metric": "r50_mm", "goal": "minimise"}],
          "tolerances": [{"key": "half_mirror.pose.pitch_deg", "sd": 0.3}],
          "search": {"psf_samples": 100000000}})",
      "spec", base);
  const address_space_limit limit(1'000'000'000ULL);
  const auto wait_for_end = [](const auto& job) {
    for (int i = 0; i < 400 && job.running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
    return job.error();
  };
  const ui::design_job tolerance(spec, ui::design_job::kind::tolerance);
  const std::string refused = wait_for_end(tolerance);
  EXPECT_EQ(refused.rfind("tolerance: ", 0), 0) << refused;
  EXPECT_NE(refused.find(" at once of 100000000 samples needs about "), std::string::npos) << refused;
  EXPECT_NE(refused.find("ulimit -v"), std::string::npos) << refused;
  EXPECT_FALSE(tolerance.tolerances());

  const ui::background_job<double, std::size_t> greedy("viewing zone", [](const auto&) -> std::optional<std::size_t> {
    std::vector<char> block(std::size_t(4) << 30);
    asm volatile("" : : "g"(block.data()) : "memory");  // the block escapes: its allocation stays
    return block.size();
  });
  const std::string failed = wait_for_end(greedy);
  EXPECT_EQ(failed.rfind("viewing zone: out of memory (an allocation failed; this process may take", 0), 0) << failed;
  EXPECT_FALSE(greedy.result());
}
