// Unsaved changes kept where the next start offers them back (platform/recovery_copy.hpp).
#include "airr/ui/platform/recovery_copy.hpp"
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

void studio_keep_recovery(studio& st, double now) {
  if (!st.keep_recovery) return;
  if (!studio_dirty(st)) {
    if (st.last_recovery_write >= 0) studio_clear_recovery();
    st.last_recovery_write = -1;
    return;
  }
  if (st.last_recovery_write >= 0 && now - st.last_recovery_write < 10.0) return;
  st.last_recovery_write = now;
  if (const auto failed = write_recovery_copy({st.doc_path, st.doc}))
    st.status = "cannot write the recovery copy: " + *failed;
}

void studio_clear_recovery() { remove_recovery_copy(); }

void studio_check_recovery(studio& st) { st.recovery_text = read_recovery_text(); }

void studio_recover(studio& st) {
  try {
    const recovery_copy copy = parse_recovery_copy(st.recovery_text);
    st.doc = copy.doc;
    st.doc_path = copy.path;
    st.saved.reset();  // recovered edits are unsaved
    st.status = "recovered unsaved changes" + (st.doc_path.empty() ? std::string() : " of " + st.doc_path);
  } catch (const std::exception& e) {
    st.status = std::string("cannot recover: ") + e.what();
  }
  st.recovery_text.clear();
}

}  // namespace airr::ui
