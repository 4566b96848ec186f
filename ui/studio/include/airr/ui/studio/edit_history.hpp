#pragma once
// Undo and redo for the designer's scene. The panels edit the scene in place; once no widget is
// held any more (a drag or a typed number is finished), the change becomes one step. A change made
// at once by a command (e.g. applying an optimised layout) is one step with its own name.
#include <string>
#include <vector>

#include "airr/layout/scene.hpp"

namespace airr::ui {

class edit_history {
 public:
  // Forgets every step; `s` is the scene as it now stands (a scene was opened).
  void reset(const scene& s);
  // Called once per frame: when `doc` differs from the last settled scene and no widget is held,
  // the change becomes a step named `name` (or "edit").
  void settle(const scene& doc, bool widget_held);
  // Names the step the next settle records (a command's change).
  void name_next(std::string name) { next_name_ = std::move(name); }

  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  const std::string& undo_name() const;
  const std::string& redo_name() const;
  // Puts `doc` back as it was before the last step (or forward again); false when there is none.
  // An unsettled change in `doc` is settled first, so that undo takes it back.
  bool undo(scene& doc);
  bool redo(scene& doc);
  std::size_t steps() const { return undo_.size(); }

 private:
  struct step {
    scene before, after;
    std::string name;
  };
  static constexpr std::size_t max_steps = 200;
  std::vector<step> undo_, redo_;
  scene settled_;
  std::string next_name_;
};

}  // namespace airr::ui
