// Undo and redo of the designer's scene: a drag is one step once released, a command's change is
// one named step, undo and redo walk the steps both ways, and a new edit drops what was undone.
#include <gtest/gtest.h>

#include "airr/ui/studio/edit_history.hpp"

using namespace airr;
using airr::ui::edit_history;

TEST(EditHistory, ADragIsOneStepAndUndoRedoWalkTheSteps) {
  scene doc;
  edit_history h;
  h.reset(doc);
  const double start = doc.sheet().pose.pitch_deg;
  // A drag over three frames, the widget held: nothing is recorded until it is released.
  for (double t : {start + 1, start + 2, start + 3}) {
    doc.sheet().pose.pitch_deg = t;
    h.settle(doc, true);
  }
  EXPECT_FALSE(h.can_undo());
  h.settle(doc, false);
  EXPECT_EQ(h.steps(), 1u);
  // A command's change, named.
  h.name_next("apply the optimised layout");
  doc.half_mirror.reflectance = 0.4;
  h.settle(doc, false);
  EXPECT_EQ(h.undo_name(), "apply the optimised layout");

  ASSERT_TRUE(h.undo(doc));
  EXPECT_NE(doc.half_mirror.reflectance, 0.4);
  EXPECT_EQ(doc.sheet().pose.pitch_deg, start + 3);
  ASSERT_TRUE(h.undo(doc));
  EXPECT_EQ(doc.sheet().pose.pitch_deg, start);
  EXPECT_FALSE(h.undo(doc));
  ASSERT_TRUE(h.redo(doc));
  EXPECT_EQ(doc.sheet().pose.pitch_deg, start + 3);
  EXPECT_EQ(h.redo_name(), "apply the optimised layout");
  // A new edit drops the step that was undone.
  doc.sheet().pose.yaw_deg = 5;
  h.settle(doc, false);
  EXPECT_FALSE(h.can_redo());
  // An edit not yet settled is taken back by undo too.
  doc.sheet().pose.yaw_deg = 9;
  ASSERT_TRUE(h.undo(doc));
  EXPECT_EQ(doc.sheet().pose.yaw_deg, 5);
}
