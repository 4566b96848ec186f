#include "airr/ui/studio/edit_history.hpp"

namespace airr::ui {

void edit_history::reset(const scene& s) {
  undo_.clear();
  redo_.clear();
  settled_ = s;
  next_name_.clear();
}

void edit_history::settle(const scene& doc, bool widget_held) {
  if (widget_held || doc == settled_) return;
  undo_.push_back({settled_, doc, next_name_.empty() ? "edit" : next_name_});
  if (undo_.size() > max_steps) undo_.erase(undo_.begin());
  redo_.clear();
  settled_ = doc;
  next_name_.clear();
}

const std::string& edit_history::undo_name() const {
  static const std::string none;
  return undo_.empty() ? none : undo_.back().name;
}

const std::string& edit_history::redo_name() const {
  static const std::string none;
  return redo_.empty() ? none : redo_.back().name;
}

bool edit_history::undo(scene& doc) {
  settle(doc, false);
  if (undo_.empty()) return false;
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  doc = settled_ = redo_.back().before;
  return true;
}

bool edit_history::redo(scene& doc) {
  settle(doc, false);
  if (redo_.empty()) return false;
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  doc = settled_ = undo_.back().after;
  return true;
}

}  // namespace airr::ui
