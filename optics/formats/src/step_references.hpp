#pragma once
// What Open CASCADE's STEP reader would crash on before it could say anything, found in the text
// first: an entity defined twice, a reference to an entity the file does not define, an oriented
// edge whose edge is itself an oriented edge (which STEP forbids: the reader's own check then
// recurses for ever), references that go round in a loop (the reader follows them for ever), and
// an empty list where the reader's checks need members (directions, edge loops, splines ...).
#include <string>
#include <string_view>

namespace airr {

// The first such fault in a STEP file's text, as "entity #12 refers to #34, which the file does not
// define"; empty when there is none.
std::string step_reference_fault(std::string_view text);

}  // namespace airr
